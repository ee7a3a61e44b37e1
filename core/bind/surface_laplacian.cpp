#include "core/bind/surface_laplacian.h"

#include <algorithm>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/util/error.h"

namespace dfm {
namespace {

void check_faces(int nv, const Eigen::MatrixXi& F) {
  if (F.size() && (F.cols() != 3 || F.minCoeff() < 0 || F.maxCoeff() >= nv))
    throw Error("surface Laplacian: face index out of range (" + std::to_string(nv) + " vertices)");
}

// Off-diagonal couplings c_ij (i != j, both directions; an edge's triangles summed) -> K with
// K_ij = -max(c_ij, 0), K_ii = -sum_j K_ij. unit: every positive coupling counts as 1. clamp = false
// keeps negative couplings as they are.
Eigen::SparseMatrix<double> from_couplings(int nv, const std::vector<Eigen::Triplet<double>>& c, bool unit,
                                           bool clamp = true) {
  Eigen::SparseMatrix<double> C(nv, nv);
  C.setFromTriplets(c.begin(), c.end());  // sums the two triangles of an edge
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(C.nonZeros() + nv);
  Eigen::VectorXd diag = Eigen::VectorXd::Zero(nv);
  for (int k = 0; k < C.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(C, k); it; ++it) {
      const double w = !clamp ? it.value() : it.value() > 0 ? (unit ? 1.0 : it.value()) : 0.0;
      t.emplace_back(it.row(), it.col(), -w);
      diag(it.row()) += w;
    }
  for (int i = 0; i < nv; ++i) t.emplace_back(i, i, diag(i));
  Eigen::SparseMatrix<double> K(nv, nv);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

}  // namespace

Eigen::SparseMatrix<double> surface_cotangent_stiffness(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                                        bool clamp_negative) {
  const int nv = static_cast<int>(V.rows());
  check_faces(nv, F);
  std::vector<Eigen::Triplet<double>> c;
  c.reserve(6 * F.rows());
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d p[3] = {V.row(F(f, 0)).transpose(), V.row(F(f, 1)).transpose(), V.row(F(f, 2)).transpose()};
    const double area2 = (p[1] - p[0]).cross(p[2] - p[0]).norm();  // twice the area
    const double scale = std::max({(p[1] - p[0]).squaredNorm(), (p[2] - p[1]).squaredNorm(), (p[0] - p[2]).squaredNorm()});
    if (!(area2 > 1e-12 * scale)) continue;
    for (int k = 0; k < 3; ++k) {
      // The angle at corner k faces edge (i, j): cot = (a . b) / |a x b|.
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      const double cot = (p[i] - p[k]).dot(p[j] - p[k]) / area2;
      c.emplace_back(F(f, i), F(f, j), 0.5 * cot);
      c.emplace_back(F(f, j), F(f, i), 0.5 * cot);
    }
  }
  return from_couplings(nv, c, false, clamp_negative);
}

Eigen::SparseMatrix<double> uniform_stiffness(int nv, const Eigen::MatrixXi& F) {
  check_faces(nv, F);
  std::vector<Eigen::Triplet<double>> c;
  c.reserve(6 * F.rows());
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      if (a == b) continue;
      c.emplace_back(a, b, 1.0);
      c.emplace_back(b, a, 1.0);
    }
  return from_couplings(nv, c, true);  // an edge in two triangles still weighs 1
}

Eigen::VectorXd surface_lumped_mass(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  check_faces(static_cast<int>(V.rows()), F);
  Eigen::VectorXd m = Eigen::VectorXd::Zero(V.rows());
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const double third = (b - a).cross(c - a).norm() / 6.0;
    for (int k = 0; k < 3; ++k) m(F(f, k)) += third;
  }
  return m;
}

}  // namespace dfm
