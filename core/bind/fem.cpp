#include "core/bind/fem.h"

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "core/util/error.h"

namespace dfm {
namespace {

// Gradients of the 4 barycentric (hat) functions of tet t (columns), and its signed volume.
// Throws on a degenerate or inverted tet: the FEM is meaningless there.
void hat_gradients(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, int t, Eigen::Matrix<double, 3, 4>& grad,
                   double& vol) {
  const Eigen::Vector3d p0 = V.row(T(t, 0)).transpose();
  Eigen::Matrix3d J;
  for (int c = 0; c < 3; ++c) J.col(c) = V.row(T(t, c + 1)).transpose() - p0;
  const double det = J.determinant();
  vol = det / 6.0;
  const double scale = J.colwise().norm().maxCoeff();
  if (!(det > 1e-14 * scale * scale * scale))
    throw Error("tet " + std::to_string(t) + " is degenerate or inverted (volume " + std::to_string(vol) +
                "): the tet mesh must be positively oriented");
  const Eigen::Matrix3d Jinv = J.inverse();  // rows = gradients of hats 1..3
  grad.block<3, 3>(0, 1) = Jinv.transpose();
  grad.col(0) = -grad.block<3, 3>(0, 1).rowwise().sum();
}

void check_indices(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  if (T.cols() != 4) throw Error("tet index matrix must have 4 columns");
  if (V.cols() != 3) throw Error("tet vertex matrix must have 3 columns");
  if (T.size() && (T.minCoeff() < 0 || T.maxCoeff() >= V.rows()))
    throw Error("tet index out of range (" + std::to_string(V.rows()) + " vertices)");
}

}  // namespace

Eigen::VectorXd tet_volumes(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  check_indices(V, T);
  Eigen::VectorXd vol(T.rows());
  for (int t = 0; t < T.rows(); ++t) {
    Eigen::Matrix3d J;
    for (int c = 0; c < 3; ++c) J.col(c) = (V.row(T(t, c + 1)) - V.row(T(t, 0))).transpose();
    vol(t) = J.determinant() / 6.0;
  }
  return vol;
}

Eigen::SparseMatrix<double> cotangent_stiffness(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  check_indices(V, T);
  // vol * grad(phi_i) . grad(phi_j) == -(l_kl / 6) cot(theta_kl) for i != j (tests check the identity).
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(T.rows() * 16);
  Eigen::Matrix<double, 3, 4> g;
  double vol;
  for (int t = 0; t < T.rows(); ++t) {
    hat_gradients(V, T, t, g, vol);
    const Eigen::Matrix4d Ke = vol * (g.transpose() * g);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) trip.emplace_back(T(t, i), T(t, j), Ke(i, j));
  }
  Eigen::SparseMatrix<double> K(V.rows(), V.rows());
  K.setFromTriplets(trip.begin(), trip.end());
  return K;
}

Eigen::VectorXd lumped_mass(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  const Eigen::VectorXd vol = tet_volumes(V, T);
  Eigen::VectorXd m = Eigen::VectorXd::Zero(V.rows());
  for (int t = 0; t < T.rows(); ++t)
    for (int c = 0; c < 4; ++c) m(T(t, c)) += vol(t) / 4.0;
  return m;
}

Eigen::SparseMatrix<double> tet_gradient(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  check_indices(V, T);
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(T.rows() * 12);
  Eigen::Matrix<double, 3, 4> g;
  double vol;
  for (int t = 0; t < T.rows(); ++t) {
    hat_gradients(V, T, t, g, vol);
    for (int d = 0; d < 3; ++d)
      for (int c = 0; c < 4; ++c) trip.emplace_back(3 * t + d, T(t, c), g(d, c));
  }
  Eigen::SparseMatrix<double> G(3 * T.rows(), V.rows());
  G.setFromTriplets(trip.begin(), trip.end());
  return G;
}

Eigen::SparseMatrix<double> masked_stiffness(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                                             const Eigen::VectorXd& rho) {
  if (rho.size() != T.rows())
    throw Error("shape mask has " + std::to_string(rho.size()) + " values for " + std::to_string(T.rows()) + " tets");
  if (rho.size() && rho.minCoeff() < 0) throw Error("shape mask values must be >= 0");
  const Eigen::SparseMatrix<double> G = tet_gradient(V, T);
  const Eigen::VectorXd vol = tet_volumes(V, T);
  Eigen::VectorXd rd(3 * T.rows());
  for (int t = 0; t < T.rows(); ++t) rd.segment<3>(3 * t).setConstant(rho(t) * vol(t));
  return Eigen::SparseMatrix<double>(G.transpose() * rd.asDiagonal() * G);
}

}  // namespace dfm
