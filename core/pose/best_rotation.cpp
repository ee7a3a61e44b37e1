#include "core/pose/best_rotation.h"

#include <Eigen/Dense>

namespace dfm {

Eigen::Matrix3d best_rotation(const Eigen::Matrix3d& S) {
  const Eigen::JacobiSVD<Eigen::Matrix3d, Eigen::NoQRPreconditioner> svd(S, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d Vm = svd.matrixV();
  const Eigen::Matrix3d U = svd.matrixU();
  if ((Vm * U.transpose()).determinant() < 0) Vm.col(2) = -Vm.col(2);
  return Vm * U.transpose();
}

}  // namespace dfm
