#include "core/anim/space_warp.h"

#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "core/util/error.h"

namespace dfm {

namespace {

std::string point_text(const Eigen::RowVector3d& p) {
  return "(" + std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + ")";
}

}  // namespace

Eigen::RowVector3d SpaceWarp::displacement(const Eigen::RowVector3d& x) const {
  if (identity()) return Eigen::RowVector3d::Zero();
  const Eigen::RowVector3d xh = (x - mean) / spread;
  Eigen::RowVector3d d = affine.row(0) + xh * affine.bottomRows<3>();
  for (Eigen::Index i = 0; i < centres.rows(); ++i) d += std::pow((xh - centres.row(i)).norm(), 3) * weights.row(i);
  return d;
}

Eigen::Matrix3d SpaceWarp::displacement_jacobian(const Eigen::RowVector3d& x) const {
  if (identity()) return Eigen::Matrix3d::Zero();
  const Eigen::RowVector3d xh = (x - mean) / spread;
  // d|y|^3/dy = 3 |y| y; chain rule through x^ = (x - mean) / spread.
  Eigen::Matrix3d J = affine.bottomRows<3>().transpose();
  for (Eigen::Index i = 0; i < centres.rows(); ++i) {
    const Eigen::RowVector3d y = xh - centres.row(i);
    J += weights.row(i).transpose() * (3 * y.norm() * y);
  }
  return J / spread;
}

SpaceWarp fit_space_warp(const Eigen::MatrixXd& from, const Eigen::MatrixXd& to) {
  SpaceWarp w;
  const Eigen::Index n = from.rows();
  if (n == 0) return w;
  if (to.rows() != n || from.cols() != 3 || to.cols() != 3) throw Error("space warp: pairs need 3 columns on each side");
  if (!from.allFinite() || !to.allFinite()) throw Error("space warp: a picked point is not finite");
  w.mean = from.colwise().mean();
  w.spread = std::sqrt((from.rowwise() - w.mean).rowwise().squaredNorm().mean());
  if (!(w.spread > 0)) w.spread = 1;  // one pair
  w.centres = (from.rowwise() - w.mean) / w.spread;
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < i; ++j)
      if ((w.centres.row(i) - w.centres.row(j)).norm() < 1e-9)
        throw Error("space warp: picked points " + std::to_string(j + 1) + " and " + std::to_string(i + 1) + " coincide");
  // [Phi P; P^T 0] [w; affine] = [to - from; 0].
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n + 4, n + 4), b = Eigen::MatrixXd::Zero(n + 4, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) A(i, j) = std::pow((w.centres.row(i) - w.centres.row(j)).norm(), 3);
    A(i, n) = A(n, i) = 1;
    for (int k = 0; k < 3; ++k) A(i, n + 1 + k) = A(n + 1 + k, i) = w.centres(i, k);
    b.row(i) = to.row(i) - from.row(i);
  }
  const Eigen::MatrixXd x = A.completeOrthogonalDecomposition().solve(b);
  w.weights = x.topRows(n);
  w.affine = x.bottomRows(4);
  return w;
}

Eigen::RowVector3d warp(const SpaceWarp& w, const Eigen::RowVector3d& x, double u) {
  if (w.identity() || u == 0) return x;
  return x + u * w.displacement(x);
}

Eigen::RowVector3d unwarp(const SpaceWarp& w, const Eigen::RowVector3d& y) {
  if (w.identity()) return y;
  Eigen::RowVector3d x = y, best = y;
  const double scale = w.spread + y.norm();
  double best_r = HUGE_VAL;
  for (int it = 0; it < 60; ++it) {
    const Eigen::RowVector3d r = x + w.displacement(x) - y;
    const Eigen::Matrix3d J = Eigen::Matrix3d::Identity() + w.displacement_jacobian(x);
    if (!(J.determinant() > 0)) break;
    if (r.norm() < best_r) best_r = r.norm(), best = x;
    if (r.norm() <= 1e-14 * scale) return x;
    x -= (J.partialPivLu().solve(r.transpose())).transpose();
    if (!x.allFinite()) break;
  }
  // Rounding may stall Newton a little above 1e-14.
  if (best_r <= 1e-11 * scale && Eigen::Matrix3d(Eigen::Matrix3d::Identity() + w.displacement_jacobian(best)).determinant() > 0)
    return best;
  throw Error("the picked pairs fold space near " + point_text(y) + ": the warp through them has no inverse there");
}

}  // namespace dfm
