#include "core/anim/key_distance.h"

#include <cmath>
#include <cstdint>
#include <unordered_map>
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

namespace {

// Unit face normals; per face, its three edges' normals (the sum of the two faces sharing each);
// per vertex, the angle-weighted sum of its faces' normals.
void pseudo_normals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, Eigen::MatrixXd& face, Eigen::MatrixXd& edge,
                    Eigen::MatrixXd& vertex) {
  face.resize(F.rows(), 3);
  edge.setZero(F.rows(), 9);
  vertex.setZero(V.rows(), 3);
  std::unordered_map<std::uint64_t, Eigen::Vector3d> sum;
  auto key = [](int a, int b) { return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint32_t>(std::max(a, b)); };
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    face.row(f) = n.transpose();
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d p = V.row(F(f, j)), e0 = V.row(F(f, (j + 1) % 3)).transpose() - p,
                            e1 = V.row(F(f, (j + 2) % 3)).transpose() - p;
      vertex.row(F(f, j)) += std::atan2(e0.cross(e1).norm(), e0.dot(e1)) * n.transpose();
      auto [it, fresh] = sum.try_emplace(key(F(f, j), F(f, (j + 1) % 3)), n);
      if (!fresh) it->second += n;
    }
  }
  for (int f = 0; f < F.rows(); ++f)
    for (int j = 0; j < 3; ++j) edge.block<1, 3>(f, 3 * j) = sum.at(key(F(f, j), F(f, (j + 1) % 3))).transpose();
}

}  // namespace

struct SignedDistance::Impl {
  Triangles triangles;
  Tree tree;
  WindingTree winding;
  Eigen::MatrixXi F;
  Eigen::MatrixXd face_normal, edge_normal, vertex_normal;  // #F x 3, #F x 9 (edge j from corner j), #V x 3

  // The pseudo-normal of the feature of triangle f nearest to c (Baerentzen and Aanaes 2005): the
  // face's, an edge's (its two faces' sum) or a corner's (angle-weighted).
  Eigen::Vector3d pseudo_normal(int f, const Eigen::Vector3d& c) const;
};

Eigen::Vector3d SignedDistance::Impl::pseudo_normal(int f, const Eigen::Vector3d& c) const {
  const K::Triangle_3& t = triangles[f];
  Eigen::Vector3d p[3];
  for (int j = 0; j < 3; ++j) p[j] = Eigen::Vector3d(t[j].x(), t[j].y(), t[j].z());
  // Barycentric coordinates of c from the sub-triangles' areas along the face normal.
  const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
  double b[3];
  for (int j = 0; j < 3; ++j) b[j] = (p[(j + 1) % 3] - c).cross(p[(j + 2) % 3] - c).dot(n) / n.squaredNorm();
  const double tol = 1e-7;
  int zeros = 0, at = -1;
  for (int j = 0; j < 3; ++j)
    if (b[j] <= tol) ++zeros;
    else at = j;
  if (zeros == 0) return face_normal.row(f).transpose();
  if (zeros == 2) return vertex_normal.row(F(f, at)).transpose();
  for (int j = 0; j < 3; ++j)
    if (b[j] <= tol) return edge_normal.block<1, 3>(f, 3 * ((j + 1) % 3)).transpose();  // the edge opposite corner j
  return face_normal.row(f).transpose();
}

SignedDistance::SignedDistance(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) : impl_(std::make_unique<Impl>()) {
  auto p = [&](int v) { return K::Point_3(V(v, 0), V(v, 1), V(v, 2)); };
  impl_->triangles.reserve(F.rows());
  for (int f = 0; f < F.rows(); ++f) impl_->triangles.emplace_back(p(F(f, 0)), p(F(f, 1)), p(F(f, 2)));
  impl_->tree.insert(impl_->triangles.cbegin(), impl_->triangles.cend());
  impl_->tree.build();
  impl_->tree.accelerate_distance_queries();
  impl_->winding = build_winding_tree(V, F);
  impl_->F = F;
  pseudo_normals(V, F, impl_->face_normal, impl_->edge_normal, impl_->vertex_normal);
}

SignedDistance::~SignedDistance() = default;
SignedDistance::SignedDistance(SignedDistance&&) noexcept = default;
SignedDistance& SignedDistance::operator=(SignedDistance&&) noexcept = default;

Eigen::VectorXd SignedDistance::operator()(const Eigen::MatrixXd& P, Eigen::MatrixXd* gradient) const {
  Eigen::VectorXd d(P.rows());
  if (gradient) gradient->resize(P.rows(), 3);
  std::vector<char> unsure(P.rows(), 0);
  parallel_for(static_cast<int>(P.rows()), 0, [&](int i) {
    const K::Point_3 q(P(i, 0), P(i, 1), P(i, 2));
    const auto [c, id] = impl_->tree.closest_point_and_primitive(q);
    const Eigen::Vector3d x = P.row(i).transpose(), y(c.x(), c.y(), c.z());
    const double r = (x - y).norm();
    const Eigen::Vector3d n = impl_->pseudo_normal(static_cast<int>(id - impl_->triangles.cbegin()), y);
    const double side = (x - y).dot(n);
    d[i] = side < 0 ? -r : r;
    if (gradient) gradient->row(i) = (r > 0 ? Eigen::Vector3d((x - y) / r) : n.normalized()).transpose();
    // Near the surface, or nearly along it, the nearest feature may be misread: the winding number decides.
    unsure[i] = !(std::abs(side) > 0.1 * r * n.norm()) || !n.allFinite();
  });
  std::vector<int> ask;
  for (int i = 0; i < static_cast<int>(P.rows()); ++i)
    if (unsure[i]) ask.push_back(i);
  if (!ask.empty()) {
    Eigen::MatrixXd Q(static_cast<Eigen::Index>(ask.size()), 3);
    for (size_t k = 0; k < ask.size(); ++k) Q.row(static_cast<Eigen::Index>(k)) = P.row(ask[k]);
    const Eigen::VectorXd w = winding_numbers(impl_->winding, Q);
    for (size_t k = 0; k < ask.size(); ++k) d[ask[k]] = w[static_cast<Eigen::Index>(k)] > 0.5 ? -std::abs(d[ask[k]]) : std::abs(d[ask[k]]);
  }
  if (gradient)
    for (Eigen::Index i = 0; i < P.rows(); ++i)
      if (d[i] < 0) gradient->row(i) *= -1;
  return d;
}

}  // namespace dfm
