#include "core/anim/shape_space_pad.h"

#include <algorithm>
#include <limits>
#include <string>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include "core/util/error.h"

namespace dfm {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using Delaunay2 = CGAL::Delaunay_triangulation_2<K, Tds>;

void check_points(const PadPoints& points) {
  if (points.rows() < 2) throw Error("a shape-space pad needs at least 2 points, got " + std::to_string(points.rows()));
  for (int i = 0; i < points.rows(); ++i)
    if (!points.row(i).allFinite()) throw Error("pad point " + std::to_string(i) + " is not finite");
}

// Info = the first index of the points at each place.
Delaunay2 triangulate(const PadPoints& points) {
  Delaunay2 dt;
  for (int i = 0; i < points.rows(); ++i) {
    const size_t before = dt.number_of_vertices();
    const Delaunay2::Vertex_handle v = dt.insert(K::Point_2(points(i, 0), points(i, 1)));
    if (dt.number_of_vertices() > before) v->info() = i;
  }
  return dt;
}

double orient(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// Nearest point to q on the segments (a, b) of index pairs: the two weights (1 - s, s) on a and b.
Eigen::VectorXd nearest_on_segments(const PadPoints& p, const std::vector<std::array<int, 2>>& segments,
                                    const Eigen::Vector2d& q) {
  double best = std::numeric_limits<double>::infinity();
  Eigen::VectorXd w = Eigen::VectorXd::Zero(p.rows());
  for (const auto& s : segments) {
    const Eigen::Vector2d a = p.row(s[0]).transpose(), b = p.row(s[1]).transpose();
    const double len2 = (b - a).squaredNorm();
    const double u = len2 > 0 ? std::clamp((q - a).dot(b - a) / len2, 0.0, 1.0) : 0.0;
    const double d = (a + u * (b - a) - q).squaredNorm();
    if (d < best) {
      best = d;
      w.setZero();
      w(s[0]) = 1.0 - u;
      w(s[1]) += u;
    }
  }
  return w;
}

}  // namespace

Eigen::VectorXd pad_weights(const PadPoints& points, const Eigen::Vector2d& cursor) {
  check_points(points);
  if (!cursor.allFinite()) throw Error("the pad cursor is not finite");
  const int n = static_cast<int>(points.rows());
  Eigen::VectorXd w = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i)
    if (points(i, 0) == cursor.x() && points(i, 1) == cursor.y()) {  // a base's own point: e_i exactly
      w(i) = 1.0;
      return w;
    }
  const Delaunay2 dt = triangulate(points);
  if (dt.dimension() == 0) {
    w(dt.finite_vertices_begin()->info()) = 1.0;
    return w;
  }
  const K::Point_2 q(cursor.x(), cursor.y());
  std::vector<std::array<int, 2>> segments;
  if (dt.dimension() == 1) {
    for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e)
      segments.push_back({e->first->vertex(dt.cw(e->second))->info(), e->first->vertex(dt.ccw(e->second))->info()});
    return nearest_on_segments(points, segments, cursor);
  }
  const Delaunay2::Face_handle f = dt.locate(q);
  if (!dt.is_infinite(f)) {
    int id[3];
    Eigen::Vector2d v[3];
    for (int k = 0; k < 3; ++k) id[k] = f->vertex(k)->info(), v[k] = points.row(id[k]).transpose();
    const double area = orient(v[0], v[1], v[2]);
    double sum = 0;
    for (int k = 0; k < 3; ++k) {
      const double b = std::max(0.0, orient(cursor, v[(k + 1) % 3], v[(k + 2) % 3]) / area);  // on an edge: >= 0
      w(id[k]) = b;
      sum += b;
    }
    return w / sum;
  }
  // Outside the hull: the nearest point on a hull edge (the finite edge of each infinite face).
  auto c = dt.incident_faces(dt.infinite_vertex()), done = c;
  do {
    const int i = c->index(dt.infinite_vertex());
    segments.push_back({c->vertex(dt.ccw(i))->info(), c->vertex(dt.cw(i))->info()});
  } while (++c != done);
  return nearest_on_segments(points, segments, cursor);
}

std::vector<std::array<int, 3>> pad_triangles(const PadPoints& points) {
  check_points(points);
  const Delaunay2 dt = triangulate(points);
  std::vector<std::array<int, 3>> out;
  if (dt.dimension() < 2) return out;
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f)
    out.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  return out;
}

Eigen::Vector2d pad_position(const PadPoints& points, const Eigen::VectorXd& x) {
  if (x.size() != points.rows())
    throw Error(std::to_string(x.size()) + " coordinates for " + std::to_string(points.rows()) + " pad points");
  return points.transpose() * x;
}

}  // namespace dfm
