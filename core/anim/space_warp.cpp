#include "core/anim/space_warp.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "core/util/error.h"

namespace dfm {

namespace {

std::string point_text(const Eigen::RowVector3d& p) {
  return "(" + std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + ")";
}

// A principal axis of the picked points whose spread is under this share of the largest one's
// takes no part in the affine map.
constexpr double kThin = 0.1;

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
  // The affine part's linear map only along the principal axes the points spread over (kThin): across
  // a nearly flat set of pairs it would be read off their small deviations from the plane.
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(w.centres, Eigen::ComputeFullV);
  const Eigen::VectorXd sigma = svd.singularValues();
  int m = 0;
  while (m < sigma.size() && sigma[m] > kThin * sigma[0]) ++m;
  const Eigen::MatrixXd axes = svd.matrixV().leftCols(m);
  const Eigen::MatrixXd coords = w.centres * axes;
  // [Phi P; P^T 0] [w; affine] = [to - from; 0], P = [1, coords].
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n + 1 + m, n + 1 + m), b = Eigen::MatrixXd::Zero(n + 1 + m, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) A(i, j) = std::pow((w.centres.row(i) - w.centres.row(j)).norm(), 3);
    A(i, n) = A(n, i) = 1;
    for (int k = 0; k < m; ++k) A(i, n + 1 + k) = A(n + 1 + k, i) = coords(i, k);
    b.row(i) = to.row(i) - from.row(i);
  }
  const Eigen::MatrixXd x = A.completeOrthogonalDecomposition().solve(b);
  w.weights = x.topRows(n);
  w.affine.row(0) = x.row(n);
  w.affine.bottomRows<3>() = axes * x.bottomRows(m);
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

WarpPath fit_warp_path(const Eigen::MatrixXd& from, const Eigen::MatrixXd& to, int steps) {
  if (steps < 1) throw Error("space warp: needs at least one step");
  WarpPath w;
  if (from.rows() == 0) return w;
  if (to.rows() != from.rows() || from.cols() != 3 || to.cols() != 3) throw Error("space warp: pairs need 3 columns on each side");
  for (int k = 1; k <= steps; ++k) {
    const double a = static_cast<double>(k - 1) / steps, b = static_cast<double>(k) / steps;
    try {
      w.steps.push_back(fit_space_warp(from + a * (to - from), from + b * (to - from)));
    } catch (const Error& e) {
      if (k == 1) throw;
      throw Error(std::string("the picked pairs fold space: two of their paths meet at u = ") + std::to_string(a) + " (" +
                  e.what() + ")");
    }
  }
  return w;
}

Eigen::RowVector3d warp(const WarpPath& w, const Eigen::RowVector3d& x, double u) {
  const int n = static_cast<int>(w.steps.size());
  Eigen::RowVector3d y = x;
  const double s = std::min(std::max(u, 0.0), 1.0) * n;
  for (int k = 0; k < n && k < s; ++k) y = warp(w.steps[k], y, std::min(1.0, s - k));
  return y;
}

Eigen::RowVector3d unwarp(const WarpPath& w, const Eigen::RowVector3d& y) {
  Eigen::RowVector3d x = y;
  for (auto k = w.steps.rbegin(); k != w.steps.rend(); ++k) x = unwarp(*k, x);
  return x;
}

Eigen::MatrixXd unwarp_rows(const WarpPath& w, const Eigen::MatrixXd& Y) {
  Eigen::MatrixXd X = Y;
  for (Eigen::Index v = 0; v < X.rows() && !w.identity(); ++v) X.row(v) = unwarp(w, Eigen::RowVector3d(Y.row(v)));
  return X;
}

std::optional<PathFold> first_fold(const WarpPath& w, const Eigen::MatrixXd& X) {
  for (Eigen::Index v = 0; v < X.rows() && !w.identity(); ++v)
    if (const auto u = fold_time(w, X.row(v))) return PathFold{v, *u};
  return std::nullopt;
}

std::optional<double> fold_time(const WarpPath& w, const Eigen::RowVector3d& x) {
  const int n = static_cast<int>(w.steps.size());
  Eigen::RowVector3d y = x;
  for (int k = 0; k < n; ++k) {
    const Eigen::Matrix3d J = w.steps[k].displacement_jacobian(y);
    for (int q = 1; q <= 4; ++q)
      if (!((Eigen::Matrix3d::Identity() + 0.25 * q * J).determinant() > 0)) return (k + 0.25 * q) / n;
    y = warp(w.steps[k], y);
  }
  return std::nullopt;
}

}  // namespace dfm
