#include "core/bind/closest_surface_point.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/bind/handle_geometry.h"
#include "core/mesh/mesh_info.h"
#include "core/util/error.h"

namespace dfm {

Eigen::Vector3d closest_point_barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = va + vb + vc;
  if (!(std::abs(denom) > 0)) return {1, 0, 0};  // degenerate triangle: its first corner
  const double v = vb / denom, w = vc / denom;
  return {1 - v - w, v, w};
}

SurfaceLocator::SurfaceLocator(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, double max_distance)
    : V_(V), F_(F), max_distance_(max_distance) {
  if (F.size() && (F.minCoeff() < 0 || F.maxCoeff() >= V.rows()))
    throw Error("surface locator: face index out of range (" + std::to_string(V.rows()) + " vertices)");
  if (!(max_distance >= 0)) throw Error("surface locator: the search distance must be >= 0");
  cell_ = std::max(max_distance, mean_edge_length(V, F));
  if (!(cell_ > 0)) cell_ = 1;
  origin_ = bounding_box(V).min;
  for (int f = 0; f < F.rows(); ++f) {
    Eigen::Vector3d lo = V.row(F(f, 0)).transpose(), hi = lo;
    for (int k = 1; k < 3; ++k) lo = lo.cwiseMin(V.row(F(f, k)).transpose()), hi = hi.cwiseMax(V.row(F(f, k)).transpose());
    const Eigen::Vector3d a = ((lo - origin_) / cell_).array().floor(), b = ((hi - origin_) / cell_).array().floor();
    for (long long x = a.x(); x <= b.x(); ++x)
      for (long long y = a.y(); y <= b.y(); ++y)
        for (long long z = a.z(); z <= b.z(); ++z) cells_[key(x, y, z)].push_back(f);
  }
}

long long SurfaceLocator::key(long long x, long long y, long long z) const {
  return x * 73856093LL ^ y * 19349663LL ^ z * 83492791LL;  // collisions only add candidates
}

SurfaceSample SurfaceLocator::closest(const Eigen::Vector3d& p) const {
  SurfaceSample best;
  double best_d = max_distance_;
  const Eigen::Vector3d c = ((p - origin_) / cell_).array().floor();
  for (long long x = c.x() - 1; x <= c.x() + 1; ++x)
    for (long long y = c.y() - 1; y <= c.y() + 1; ++y)
      for (long long z = c.z() - 1; z <= c.z() + 1; ++z) {
        const auto it = cells_.find(key(x, y, z));
        if (it == cells_.end()) continue;
        for (int f : it->second) {
          const Eigen::Vector3d a = V_.row(F_(f, 0)), b = V_.row(F_(f, 1)), cc = V_.row(F_(f, 2));
          Eigen::Vector3d w = closest_point_barycentric(p, a, b, cc);
          const double d = (w(0) * a + w(1) * b + w(2) * cc - p).norm();
          if (d > best_d || (best.found() && d == best_d)) continue;
          for (int k = 0; k < 3; ++k)
            if (w(k) < 1e-9) w(k) = 0;
          w /= w.sum();
          best_d = d;
          best.distance = d;
          for (int k = 0; k < 3; ++k) best.vertex[k] = F_(f, k), best.weight[k] = w(k);
        }
      }
  return best;
}

namespace {
using AabbKernel = CGAL::Simple_cartesian<double>;
using AabbTriangles = std::vector<AabbKernel::Triangle_3>;
using AabbPrimitive = CGAL::AABB_triangle_primitive<AabbKernel, AabbTriangles::const_iterator>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<AabbKernel, AabbPrimitive>>;
}  // namespace

struct SurfaceTree::Impl {
  const Eigen::MatrixXd& V;
  const Eigen::MatrixXi& F;
  double max_distance;
  AabbTriangles triangles;
  AabbTree tree;
};

SurfaceTree::SurfaceTree(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, double max_distance)
    : impl_(new Impl{V, F, max_distance, {}, {}}) {
  if (F.size() && (F.minCoeff() < 0 || F.maxCoeff() >= V.rows()))
    throw Error("surface tree: face index out of range (" + std::to_string(V.rows()) + " vertices)");
  if (!(max_distance >= 0)) throw Error("surface tree: the search distance must be >= 0");
  auto p = [&](int v) { return AabbKernel::Point_3(V(v, 0), V(v, 1), V(v, 2)); };
  impl_->triangles.reserve(F.rows());
  for (int f = 0; f < F.rows(); ++f) impl_->triangles.emplace_back(p(F(f, 0)), p(F(f, 1)), p(F(f, 2)));
  if (F.rows() == 0) return;
  impl_->tree.insert(impl_->triangles.cbegin(), impl_->triangles.cend());
  impl_->tree.build();
  impl_->tree.accelerate_distance_queries();
}

SurfaceTree::~SurfaceTree() = default;

SurfaceSample SurfaceTree::closest(const Eigen::Vector3d& p) const {
  SurfaceSample best;
  if (impl_->triangles.empty()) return best;
  const auto hit = impl_->tree.closest_point_and_primitive(AabbKernel::Point_3(p.x(), p.y(), p.z()));
  const int f = static_cast<int>(hit.second - impl_->triangles.cbegin());
  const Eigen::MatrixXd& V = impl_->V;
  const Eigen::Vector3d a = V.row(impl_->F(f, 0)), b = V.row(impl_->F(f, 1)), c = V.row(impl_->F(f, 2));
  Eigen::Vector3d w = closest_point_barycentric(p, a, b, c);
  const double d = (w(0) * a + w(1) * b + w(2) * c - p).norm();
  if (d > impl_->max_distance) return best;
  for (int k = 0; k < 3; ++k)
    if (w(k) < 1e-9) w(k) = 0;
  w /= w.sum();
  best.distance = d;
  for (int k = 0; k < 3; ++k) best.vertex[k] = impl_->F(f, k), best.weight[k] = w(k);
  return best;
}

}  // namespace dfm
