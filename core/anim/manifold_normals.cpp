#include "core/anim/manifold_normals.h"

#include <string>

#include <Eigen/LU>

#include "core/util/error.h"

namespace dfm {

Eigen::Vector4d tet_normal4(const AnimationManifold& m, int k) {
  const Eigen::Vector4d p0 = m.V.row(m.T(k, 0)).transpose();
  return cross4(m.V.row(m.T(k, 1)).transpose() - p0, m.V.row(m.T(k, 2)).transpose() - p0,
                m.V.row(m.T(k, 3)).transpose() - p0);
}

Eigen::Vector4d cross4(const Eigen::Vector4d& e1, const Eigen::Vector4d& e2, const Eigen::Vector4d& e3) {
  // Cofactor expansion of det[w, e1, e2, e3] along its first column w.
  Eigen::Vector4d N;
  for (int j = 0; j < 4; ++j) {
    Eigen::Matrix3d minor;
    for (int r = 0, i = 0; r < 4; ++r) {
      if (r == j) continue;
      minor.row(i++) << e1[r], e2[r], e3[r];
    }
    N[j] = (j % 2 ? -1.0 : 1.0) * minor.determinant();
  }
  return N;
}

int tet_normal_sums(const AnimationManifold& m, int k, int c) {
  const int v = m.T(k, c);
  const bool ends = m.num_layers() >= 2;
  if (!ends || (m.V(v, 3) != m.times.front() && m.V(v, 3) != m.times.back())) return 1;
  int in_plane = 0;
  for (int d = 0; d < 4; ++d) in_plane += m.V(m.T(k, d), 3) == m.V(v, 3);
  return in_plane >= 3 ? 3 : 2;
}

void add_tet_normal(const AnimationManifold& m, int k, int c, const Eigen::RowVector4d& n, Eigen::MatrixXd& sum, int row) {
  const int sums = tet_normal_sums(m, k, c);
  auto r = sum.row(row);
  if (sums & 1) r.head<4>() += n;
  if (sums & 2) r.tail<4>() += n;
}

void accumulate_tet_normals(const AnimationManifold& m, int first_tet, int last_tet, int vertex_offset,
                            Eigen::MatrixXd& sum) {
  for (int k = first_tet; k < last_tet; ++k) {
    const Eigen::RowVector4d n = tet_normal4(m, k).transpose();
    for (int c = 0; c < 4; ++c) add_tet_normal(m, k, c, n, sum, m.T(k, c) - vertex_offset);
  }
}

Eigen::Vector4d unit_or_zero(const Eigen::Vector4d& sum) {
  const double len = sum.norm();
  return len > 0 ? Eigen::Vector4d(sum / len) : Eigen::Vector4d::Zero();
}

Eigen::Vector4d vertex_normal4(const Eigen::Matrix<double, 1, 8>& sums) {
  const Eigen::Vector4d n = unit_or_zero(sums.head<4>().transpose());
  return n.squaredNorm() > 0 ? n : unit_or_zero(sums.tail<4>().transpose());
}

VertexNormalSource::VertexNormalSource(const AnimationManifold& m, const Eigen::MatrixXd* given, int first_tet,
                                       int last_tet)
    : given_(given) {
  if (given) {
    if (given->rows() != m.num_vertices() || given->cols() != 4)
      throw Error("vertex normals must be " + std::to_string(m.num_vertices()) + " x 4, got " +
                  std::to_string(given->rows()) + " x " + std::to_string(given->cols()));
    return;
  }
  if (first_tet >= last_tet) return;
  const auto T = m.T.middleRows(first_tet, last_tet - first_tet);
  offset_ = T.minCoeff();
  sum_ = Eigen::MatrixXd::Zero(T.maxCoeff() - offset_ + 1, 8);
  accumulate_tet_normals(m, first_tet, last_tet, offset_, sum_);
}

Eigen::Vector4d VertexNormalSource::operator()(int v) const {
  if (given_) return given_->row(v).transpose();
  return vertex_normal4(sum_.row(v - offset_));
}

Eigen::MatrixXd manifold_vertex_normals(const AnimationManifold& m) {
  Eigen::MatrixXd sums = Eigen::MatrixXd::Zero(m.num_vertices(), 8);
  accumulate_tet_normals(m, 0, m.num_tets(), 0, sums);
  Eigen::MatrixXd N(m.num_vertices(), 4);
  for (int v = 0; v < N.rows(); ++v) N.row(v) = vertex_normal4(sums.row(v)).transpose();
  return N;
}

Eigen::Vector3d slice_normal3(const Eigen::Vector4d& n4, SliceAxis axis) {
  const int a = static_cast<int>(axis);
  Eigen::Vector3d n;
  for (int d = 0, i = 0; d < 4; ++d)
    if (d != a) n[i++] = n4[d];
  const double len = n.norm();
  return len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

}  // namespace dfm
