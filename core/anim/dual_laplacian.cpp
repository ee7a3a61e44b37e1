#include "core/anim/dual_laplacian.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <unordered_set>

#include <Eigen/QR>

#include "core/util/error.h"

namespace dfm {

Eigen::RowVector4d ghost_dual_vertex(const Eigen::Matrix<double, 3, 4>& face, const Eigen::RowVector4d& opposite) {
  // Centroid of (face, 2 c_f - v_l): (sum v_k + 2/3 sum v_k - v_l) / 4.
  return (5.0 / 12.0) * face.colwise().sum() - 0.25 * opposite;
}

Eigen::VectorXd affine_projection_weights(const Eigen::RowVector4d& c, const Eigen::MatrixXd& P) {
  const int k = static_cast<int>(P.rows());
  if (k == 0) throw Error("affine projection: no points");
  Eigen::VectorXd w = Eigen::VectorXd::Zero(k);
  w[k - 1] = 1;
  if (k == 1) return w;
  // w_last = 1 - sum z: minimise | (P_last - c) + sum_j z_j (P_j - P_last) |.
  Eigen::MatrixXd A(4, k - 1);
  for (int j = 0; j + 1 < k; ++j) A.col(j) = (P.row(j) - P.row(k - 1)).transpose();
  const Eigen::Vector4d b = (c - P.row(k - 1)).transpose();
  const Eigen::VectorXd z = A.completeOrthogonalDecomposition().solve(b);
  w.head(k - 1) = z;
  w[k - 1] = 1 - z.sum();
  return w;
}

namespace {

struct FaceRef {
  std::array<int, 3> v;  // sorted
  int tet, opposite;     // the tetrahedron and its vertex off the face
  bool operator<(const FaceRef& o) const { return v < o.v || (v == o.v && tet < o.tet); }
};

}  // namespace

std::vector<DualLaplacianRow> dual_laplacian_rows(const AnimationManifold& m, const std::vector<int>& tets,
                                                  double time_scale) {
  if (!(time_scale > 0) || !std::isfinite(time_scale))
    throw Error("dual Laplacian: the time scale must be positive and finite");
  std::unordered_set<int> near;  // vertices of the rows' tetrahedra: a face neighbour has 3 of them
  for (int k : tets) {
    if (k < 0 || k >= m.num_tets()) throw Error("dual Laplacian: tetrahedron " + std::to_string(k) + " out of range");
    for (int j = 0; j < 4; ++j) near.insert(m.T(k, j));
  }
  std::vector<FaceRef> faces;
  for (int k = 0; k < m.num_tets(); ++k) {
    int in = 0;
    for (int j = 0; j < 4; ++j) in += near.count(m.T(k, j)) ? 1 : 0;
    if (in < 3) continue;
    for (int skip = 0; skip < 4; ++skip) {
      FaceRef f{{}, k, m.T(k, skip)};
      for (int j = 0, c = 0; j < 4; ++j)
        if (j != skip) f.v[c++] = m.T(k, j);
      if (!near.count(f.v[0]) || !near.count(f.v[1]) || !near.count(f.v[2])) continue;
      std::sort(f.v.begin(), f.v.end());
      faces.push_back(f);
    }
  }
  std::sort(faces.begin(), faces.end());

  auto scaled = [&](int v) {
    Eigen::RowVector4d p = m.V.row(v);
    p[3] *= time_scale;
    return p;
  };
  std::vector<DualLaplacianRow> rows;
  rows.reserve(tets.size());
  for (int k : tets) {
    // The 4 dual neighbours as weighted sums of primal vertices (a neighbour's centroid or a ghost).
    std::vector<std::vector<std::pair<int, double>>> nb;
    DualLaplacianRow row;
    row.tet = k;
    for (int skip = 0; skip < 4; ++skip) {
      FaceRef key{{}, -1, -1};
      for (int j = 0, c = 0; j < 4; ++j)
        if (j != skip) key.v[c++] = m.T(k, j);
      std::sort(key.v.begin(), key.v.end());
      auto it = std::lower_bound(faces.begin(), faces.end(), key);
      std::vector<std::pair<int, double>> terms;
      int count = 0;
      for (; it != faces.end() && it->v == key.v; ++it) {
        ++count;
        if (it->tet == k) continue;
        terms.clear();
        for (int j = 0; j < 4; ++j) terms.emplace_back(m.T(it->tet, j), 0.25);
      }
      if (count > 2)
        throw Error("dual Laplacian: a face of tetrahedron " + std::to_string(k) + " lies in " + std::to_string(count) +
                    " tetrahedra (not a manifold)");
      if (count == 1) {  // a boundary face: the ghost (4.4.2)
        for (int v : key.v) terms.emplace_back(v, 5.0 / 12.0);
        terms.emplace_back(m.T(k, skip), -0.25);
        ++row.ghosts;
      }
      nb.push_back(std::move(terms));
    }
    Eigen::MatrixXd P(4, 4);
    Eigen::RowVector4d c = Eigen::RowVector4d::Zero();
    for (int j = 0; j < 4; ++j) {
      c += 0.25 * scaled(m.T(k, j));
      P.row(j).setZero();
      for (const auto& [v, a] : nb[j]) P.row(j) += a * scaled(v);
    }
    const Eigen::VectorXd w = affine_projection_weights(c, P);
    std::vector<std::pair<int, double>> all;
    for (int j = 0; j < 4; ++j) all.emplace_back(m.T(k, j), 0.25);
    for (int j = 0; j < 4; ++j)
      for (const auto& [v, a] : nb[j]) all.emplace_back(v, -w[j] * a);
    std::sort(all.begin(), all.end());
    for (const auto& [v, a] : all) {
      if (!row.vertices.empty() && row.vertices.back() == v)
        row.coeffs.back() += a;
      else
        row.vertices.push_back(v), row.coeffs.push_back(a);
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace dfm
