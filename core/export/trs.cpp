#include "core/export/trs.h"

#include <cmath>

#include <Eigen/SVD>

#include "core/util/error.h"

namespace dfm {

Eigen::Affine3d compose_trs(const Trs& trs) {
  Eigen::Affine3d M = Eigen::Affine3d::Identity();
  M.linear() = trs.rotation.normalized().toRotationMatrix() * trs.scale.asDiagonal();
  M.translation() = trs.translation;
  return M;
}

TrsFit decompose_trs(const Eigen::Affine3d& M) {
  const Eigen::Matrix3d L = M.linear();
  if (!L.allFinite() || !M.translation().allFinite()) throw Error("transform has a non-finite entry");
  const double norm = L.norm();
  Eigen::Vector3d s = L.colwise().norm().transpose();
  if (s.minCoeff() <= 1e-12 * std::max(norm, 1e-300)) throw Error("transform is singular (a zero scale axis)");
  // A reflection cannot be a rotation: carry it as a negative x scale.
  if (L.determinant() < 0) s.x() = -s.x();
  const Eigen::Matrix3d A = L * s.cwiseInverse().asDiagonal();
  // Nearest rotation to A (polar factor); A is orthonormal already when there is no shear.
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d R = svd.matrixU() * svd.matrixV().transpose();
  if (R.determinant() < 0) {
    Eigen::Matrix3d U = svd.matrixU();
    U.col(2) = -U.col(2);
    R = U * svd.matrixV().transpose();
  }
  TrsFit fit;
  fit.trs.translation = M.translation();
  fit.trs.rotation = Eigen::Quaterniond(R).normalized();
  fit.trs.scale = s;
  fit.shear = (L - R * s.asDiagonal()).norm() / norm;
  return fit;
}

}  // namespace dfm
