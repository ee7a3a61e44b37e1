#include "core/anim/delaunay_4d.h"

#include <cstring>
#include <string>
#include <unordered_map>
#include <vector>

#include <CGAL/Delaunay_triangulation.h>
#include <CGAL/Epick_d.h>
#include <CGAL/Triangulation_data_structure.h>
#include <CGAL/Triangulation_full_cell.h>
#include <CGAL/Triangulation_vertex.h>

#include "core/util/error.h"

namespace dfm {

namespace {

using K4 = CGAL::Epick_d<CGAL::Dimension_tag<4>>;
using Vertex4 = CGAL::Triangulation_vertex<K4, int>;
using Cell4 = CGAL::Triangulation_full_cell<K4, int>;
using Tds4 = CGAL::Triangulation_data_structure<CGAL::Dimension_tag<4>, Vertex4, Cell4>;
using DT4 = CGAL::Delaunay_triangulation<K4, Tds4>;

struct CoordHash {
  size_t operator()(const std::array<double, 4>& p) const {
    std::uint64_t h = 14695981039346656037ull;
    for (double d : p) {
      std::uint64_t b;
      std::memcpy(&b, &d, sizeof b);
      h = (h ^ b) * 1099511628211ull;
    }
    return static_cast<size_t>(h);
  }
};

}  // namespace

Delaunay4 delaunay_4d(const Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>& P) {
  const int n = static_cast<int>(P.rows());
  std::vector<K4::Point_d> pts;
  pts.reserve(n);
  std::unordered_map<std::array<double, 4>, int, CoordHash> index_of;
  index_of.reserve(2 * static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const std::array<double, 4> c = {P(i, 0), P(i, 1), P(i, 2), P(i, 3)};
    if (!index_of.emplace(c, i).second) throw Error("4D Delaunay: points " + std::to_string(index_of[c]) + " and " +
                                                   std::to_string(i) + " coincide");
    pts.emplace_back(c.begin(), c.end());
  }
  DT4 dt(4);
  dt.insert(pts.begin(), pts.end());  // spatially sorted inside
  if (dt.current_dimension() != 4) throw Error("4D Delaunay: the points do not span 4 dimensions");
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
    const auto& p = v->point();
    v->data() = index_of.at({p[0], p[1], p[2], p[3]});
  }
  int count = 0;
  for (auto c = dt.finite_full_cells_begin(); c != dt.finite_full_cells_end(); ++c) c->data() = count++;
  for (auto c = dt.full_cells_begin(); c != dt.full_cells_end(); ++c)
    if (dt.is_infinite(c)) c->data() = -1;
  Delaunay4 out;
  out.simplices.resize(count, 5);
  out.neighbors.resize(count, 5);
  for (auto c = dt.finite_full_cells_begin(); c != dt.finite_full_cells_end(); ++c) {
    const int id = c->data();
    for (int i = 0; i < 5; ++i) {
      out.simplices(id, i) = c->vertex(i)->data();
      out.neighbors(id, i) = c->neighbor(i)->data();
    }
  }
  return out;
}

int orientation_4d(const Eigen::Matrix<double, 5, 4, Eigen::RowMajor>& P) {
  std::vector<K4::Point_d> pts;
  for (int i = 0; i < 5; ++i) pts.emplace_back(P.row(i).data(), P.row(i).data() + 4);
  const CGAL::Orientation o = K4().orientation_d_object()(pts.begin(), pts.end());
  return o == CGAL::POSITIVE ? 1 : o == CGAL::NEGATIVE ? -1 : 0;
}

}  // namespace dfm
