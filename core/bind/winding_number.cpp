#include "core/bind/winding_number.h"

#include <Eigen/Geometry>
#include <cmath>

#include "core/bind/parallel_for.h"

namespace dfm {

double solid_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& p) {
  const Eigen::Vector3d x = a - p, y = b - p, z = c - p;
  const double lx = x.norm(), ly = y.norm(), lz = z.norm();
  const double num = x.dot(y.cross(z));
  const double den = lx * ly * lz + x.dot(y) * lz + y.dot(z) * lx + z.dot(x) * ly;
  // atan2 keeps the correct branch when den < 0 (solid angle beyond a hemisphere).
  return 2.0 * std::atan2(num, den);
}

double winding_number(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::Vector3d& p) {
  double sum = 0;
  for (int f = 0; f < F.rows(); ++f)
    sum += solid_angle(V.row(F(f, 0)).transpose(), V.row(F(f, 1)).transpose(), V.row(F(f, 2)).transpose(), p);
  return sum / (4.0 * M_PI);
}

Eigen::VectorXd winding_numbers_direct(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                       const Eigen::MatrixXd& P, int threads) {
  Eigen::VectorXd w(P.rows());
  parallel_for(static_cast<int>(P.rows()), threads,
               [&](int i) { w(i) = winding_number(V, F, P.row(i).transpose()); });
  return w;
}

}  // namespace dfm
