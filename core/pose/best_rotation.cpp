#include "core/pose/best_rotation.h"

#include <Eigen/Dense>

namespace dfm {
namespace {

Eigen::Matrix3d jacobi_best_rotation(const Eigen::Matrix3d& S) {
  const Eigen::JacobiSVD<Eigen::Matrix3d, Eigen::NoQRPreconditioner> svd(S, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d Vm = svd.matrixV();
  const Eigen::Matrix3d U = svd.matrixU();
  if ((Vm * U.transpose()).determinant() < 0) Vm.col(2) = -Vm.col(2);
  return Vm * U.transpose();
}

}  // namespace

// The SVD from the closed-form eigenvectors V of S^T S (5x faster than Jacobi SVD, which matters: r of
// these are most of an iteration): u1 = S v1 / |S v1|, u2 the same for v2 made orthogonal to u1, and
// u3 = u1 x u2, which is S v3's direction when det S > 0 and its reflection otherwise, exactly the
// no-reflection rule. The optimum makes R S symmetric; where the closed form is not accurate enough for
// that (nearly equal or vanishing singular values), Jacobi SVD decides.
Eigen::Matrix3d best_rotation(const Eigen::Matrix3d& S) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(S.transpose() * S);
  Eigen::Matrix3d V = eig.eigenvectors().rowwise().reverse();  // descending eigenvalues
  V.col(0).normalize();
  V.col(1) = (V.col(1) - V.col(1).dot(V.col(0)) * V.col(0)).normalized();
  V.col(2) = V.col(0).cross(V.col(1));
  Eigen::Matrix3d U;
  U.col(0) = (S * V.col(0)).normalized();
  U.col(1) = S * V.col(1);
  U.col(1) = (U.col(1) - U.col(1).dot(U.col(0)) * U.col(0)).normalized();
  U.col(2) = U.col(0).cross(U.col(1));
  const Eigen::Matrix3d R = V * U.transpose();
  const Eigen::Matrix3d RS = R * S;
  if (!R.allFinite() || (RS - RS.transpose()).norm() > 1e-11 * S.norm()) return jacobi_best_rotation(S);
  return R;
}

}  // namespace dfm
