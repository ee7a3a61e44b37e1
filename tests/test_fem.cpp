#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include <Eigen/Dense>

#include "core/bind/fem.h"
#include "core/util/error.h"
#include "tests/weights_test_meshes.h"

using namespace dfm;

// Independent reference: the dihedral-angle formula, K_ij = -(l_kl / 6) cot(theta_kl).
static double dihedral_entry(const Eigen::Matrix<double, 4, 3>& P, int i, int j) {
  int kl[2], n = 0;
  for (int c = 0; c < 4; ++c)
    if (c != i && c != j) kl[n++] = c;
  const Eigen::Vector3d pk = P.row(kl[0]), pl = P.row(kl[1]);
  const Eigen::Vector3d e = (pl - pk).normalized();
  Eigen::Vector3d u = P.row(i).transpose() - pk, v = P.row(j).transpose() - pk;
  u -= u.dot(e) * e;
  v -= v.dot(e) * e;
  const double cot = u.dot(v) / u.cross(v).norm();
  return -((pl - pk).norm() / 6.0) * cot;
}

TEST_CASE("stiffness of one tet matches -(l_kl/6) cot(theta_kl); sign convention PSD", "[fem]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::Matrix<double, 4, 3> P;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 3; ++c) P(r, c) = U(rng);
    Eigen::MatrixXi T(1, 4);
    T << 0, 1, 2, 3;
    Eigen::Matrix3d J;
    for (int c = 0; c < 3; ++c) J.col(c) = (P.row(c + 1) - P.row(0)).transpose();
    if (std::abs(J.determinant()) < 1e-3) continue;
    if (J.determinant() < 0) std::swap(T(0, 1), T(0, 2));
    const Eigen::MatrixXd K = Eigen::MatrixXd(cotangent_stiffness(Eigen::MatrixXd(P), T));
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        if (i != j) REQUIRE(K(i, j) == Approx(dihedral_entry(P, i, j)).margin(1e-12));
    // PSD with exactly the constants in the kernel.
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(K);
    REQUIRE(es.eigenvalues()(0) == Approx(0).margin(1e-10));
    REQUIRE(es.eigenvalues()(1) > 1e-8);
  }
}

TEST_CASE("stiffness on a grid: symmetric, rows sum to 0, linear functions in the kernel inside", "[fem]") {
  TetMesh m = test::cube_grid(4, 3, 3, 0.25);
  // Perturb interior vertices so the test does not rely on the grid's symmetry.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-0.03, 0.03);
  std::vector<bool> interior(m.V.rows(), false);
  for (int v = 0; v < m.V.rows(); ++v) {
    const Eigen::RowVector3d p = m.V.row(v);
    interior[v] = p(0) > 1e-9 && p(0) < 1 - 1e-9 && p(1) > 1e-9 && p(1) < 0.75 - 1e-9 && p(2) > 1e-9 && p(2) < 0.75 - 1e-9;
    if (interior[v]) m.V.row(v) += Eigen::RowVector3d(U(rng), U(rng), U(rng));
  }
  const Eigen::SparseMatrix<double> K = cotangent_stiffness(m.V, m.T);
  REQUIRE((Eigen::MatrixXd(K) - Eigen::MatrixXd(K).transpose()).cwiseAbs().maxCoeff() < 1e-14);
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(m.V.rows());
  REQUIRE((K * ones).cwiseAbs().maxCoeff() < 1e-13);
  const Eigen::Vector3d a(0.3, -1.2, 2.0);
  const Eigen::VectorXd lin = m.V * a + 0.7 * ones;
  const Eigen::VectorXd Kl = K * lin;
  int checked = 0;
  for (int v = 0; v < m.V.rows(); ++v)
    if (interior[v]) {
      REQUIRE(std::abs(Kl(v)) < 1e-12);
      ++checked;
    }
  REQUIRE(checked == 3 * 2 * 2);
  // Not zero on the boundary (the linear function has a flux there).
  REQUIRE(Kl.cwiseAbs().maxCoeff() > 1e-3);
}

TEST_CASE("centre of a 2x2x2 cube grid split around the diagonal: the 7-point stencil", "[fem]") {
  const double h = 0.5;
  const TetMesh m = test::cube_grid(2, 2, 2, h);
  const Eigen::MatrixXd K = Eigen::MatrixXd(cotangent_stiffness(m.V, m.T));
  const int c = 1 + 3 * (1 + 3 * 1);
  for (int v = 0; v < m.V.rows(); ++v) {
    const Eigen::Vector3d d = (m.V.row(v) - m.V.row(c)).transpose() / h;
    const double manhattan = d.cwiseAbs().sum();
    const bool axis_neighbour = std::abs(manhattan - 1) < 1e-9;
    const double expected = v == c ? 6 * h : (axis_neighbour ? -h : 0.0);
    INFO("vertex " << v << " offset " << d.transpose());
    REQUIRE(K(c, v) == Approx(expected).margin(1e-12));
  }
}

TEST_CASE("lumped mass sums to the volume; gradients exact on linear functions; mask rho=1 is K", "[fem]") {
  const TetMesh m = test::cube_grid(3, 2, 2, 0.5);  // 1.5 x 1 x 1
  REQUIRE(lumped_mass(m.V, m.T).sum() == Approx(1.5).epsilon(1e-12));
  REQUIRE(tet_volumes(m.V, m.T).minCoeff() == Approx(0.125 / 6).epsilon(1e-12));
  const Eigen::Vector3d a(1.5, -0.5, 2.0);
  const Eigen::VectorXd f = m.V * a;
  const Eigen::VectorXd gf = tet_gradient(m.V, m.T) * f;
  for (int t = 0; t < m.T.rows(); ++t) REQUIRE((gf.segment<3>(3 * t) - a).norm() < 1e-12);
  const Eigen::MatrixXd K = Eigen::MatrixXd(cotangent_stiffness(m.V, m.T));
  const Eigen::MatrixXd Km = Eigen::MatrixXd(masked_stiffness(m.V, m.T, Eigen::VectorXd::Ones(m.T.rows())));
  REQUIRE((K - Km).cwiseAbs().maxCoeff() < 1e-12);
  // A mask on half the tets gives a PSD matrix between 0 and K.
  Eigen::VectorXd rho = Eigen::VectorXd::Zero(m.T.rows());
  rho.head(m.T.rows() / 2).setOnes();
  const Eigen::MatrixXd Kh = Eigen::MatrixXd(masked_stiffness(m.V, m.T, rho));
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> e1(Kh), e2(K - Kh);
  REQUIRE(e1.eigenvalues().minCoeff() > -1e-12);
  REQUIRE(e2.eigenvalues().minCoeff() > -1e-12);
}

TEST_CASE("stiffness assembled in place equals G^T diag(rho vol) G from Eigen's own products", "[fem]") {
  // Independent path: tet_gradient's triplets and Eigen's sparse products, on a perturbed grid with a
  // random mask, so every slot of the in-place assembly is checked.
  TetMesh m = test::cube_grid(5, 4, 3, 0.25);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-0.02, 0.02), R(0.0, 3.0);
  for (int v = 0; v < m.V.rows(); ++v)
    for (int c = 0; c < 3; ++c) m.V(v, c) += U(rng);
  Eigen::VectorXd rho(m.T.rows());
  for (int t = 0; t < rho.size(); ++t) rho(t) = R(rng);
  const Eigen::SparseMatrix<double> G = tet_gradient(m.V, m.T);
  const Eigen::VectorXd vol = tet_volumes(m.V, m.T);
  Eigen::VectorXd d1(3 * m.T.rows()), d2(3 * m.T.rows());
  for (int t = 0; t < m.T.rows(); ++t) d1.segment<3>(3 * t).setConstant(vol(t)), d2.segment<3>(3 * t).setConstant(rho(t) * vol(t));
  const Eigen::MatrixXd K_ref = Eigen::MatrixXd(Eigen::SparseMatrix<double>(G.transpose() * d1.asDiagonal() * G));
  const Eigen::MatrixXd Km_ref = Eigen::MatrixXd(Eigen::SparseMatrix<double>(G.transpose() * d2.asDiagonal() * G));
  const Eigen::SparseMatrix<double> K = cotangent_stiffness(m.V, m.T);
  const double scale = K_ref.cwiseAbs().maxCoeff();
  REQUIRE((Eigen::MatrixXd(K) - K_ref).cwiseAbs().maxCoeff() < 1e-13 * scale);
  REQUIRE((Eigen::MatrixXd(masked_stiffness(m.V, m.T, rho)) - Km_ref).cwiseAbs().maxCoeff() < 1e-13 * 3 * scale);
  // Structure: one stored entry per vertex pair sharing a tet (and the diagonal), rows sorted.
  REQUIRE(K.isCompressed());
  long pairs = 0;
  for (int i = 0; i < K_ref.rows(); ++i)
    for (int j = 0; j < K_ref.cols(); ++j) pairs += K_ref(i, j) != 0.0 || i == j;
  REQUIRE(K.nonZeros() >= pairs);
  for (int j = 0; j < K.outerSize(); ++j)
    for (int p = K.outerIndexPtr()[j] + 1; p < K.outerIndexPtr()[j + 1]; ++p)
      REQUIRE(K.innerIndexPtr()[p - 1] < K.innerIndexPtr()[p]);
}

TEST_CASE("degenerate or inverted tets and bad indices are errors", "[fem]") {
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  Eigen::MatrixXi T(1, 4);
  T << 0, 2, 1, 3;  // inverted
  REQUIRE_THROWS_AS(cotangent_stiffness(V, T), Error);
  T << 0, 1, 2, 4;
  REQUIRE_THROWS_AS(cotangent_stiffness(V, T), Error);
  V.row(3) << 1, 1, 0;  // flat
  T << 0, 1, 2, 3;
  REQUIRE_THROWS_AS(cotangent_stiffness(V, T), Error);
}
