#include "core/anim/key_distance.h"

#include <cmath>
#include <list>
#include <vector>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include "core/bind/parallel_for.h"
#include "core/bind/winding_bvh.h"

namespace dfm {

namespace {
using K = CGAL::Simple_cartesian<double>;
using Triangles = std::vector<K::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
}  // namespace

struct SignedDistance::Impl {
  Triangles triangles;
  Tree tree;
  WindingTree winding;
};

SignedDistance::SignedDistance(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) : impl_(std::make_unique<Impl>()) {
  auto p = [&](int v) { return K::Point_3(V(v, 0), V(v, 1), V(v, 2)); };
  impl_->triangles.reserve(F.rows());
  for (int f = 0; f < F.rows(); ++f) impl_->triangles.emplace_back(p(F(f, 0)), p(F(f, 1)), p(F(f, 2)));
  impl_->tree.insert(impl_->triangles.cbegin(), impl_->triangles.cend());
  impl_->tree.build();
  impl_->tree.accelerate_distance_queries();
  impl_->winding = build_winding_tree(V, F);
}

SignedDistance::~SignedDistance() = default;
SignedDistance::SignedDistance(SignedDistance&&) noexcept = default;
SignedDistance& SignedDistance::operator=(SignedDistance&&) noexcept = default;

Eigen::VectorXd SignedDistance::operator()(const Eigen::MatrixXd& P) const {
  const Eigen::VectorXd w = winding_numbers(impl_->winding, P);
  Eigen::VectorXd d(P.rows());
  parallel_for(static_cast<int>(P.rows()), 0, [&](int i) {
    const double r = std::sqrt(impl_->tree.squared_distance(K::Point_3(P(i, 0), P(i, 1), P(i, 2))));
    d[i] = w[i] > 0.5 ? -r : r;
  });
  return d;
}

}  // namespace dfm
