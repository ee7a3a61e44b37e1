#include "core/anim/rounded_distance.h"

#include <cmath>

#include "core/util/error.h"

namespace dfm {

Eigen::VectorXd rounded_distance(const SignedDistance& d, const Eigen::MatrixXd& P, double r, Eigen::MatrixXd* gradient) {
  if (!(r >= 0 && r < 1)) throw Error("rounded distance: the radius factor must be in [0, 1)");
  if (P.cols() != 3) throw Error("rounded distance: needs #P x 3 points");
  if (r == 0) return d(P, gradient);
  Eigen::MatrixXd g_at_points;
  const Eigen::VectorXd d_at_points = d(P, gradient ? &g_at_points : nullptr);
  // The octahedron's vertices about each point: Q's rows 6 i .. 6 i + 5 for P's row i.
  const Eigen::Index n = P.rows();
  Eigen::MatrixXd Q(6 * n, 3);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int j = 0; j < 6; ++j)
      Q.row(6 * i + j) = P.row(i) + (j % 2 ? 1 : -1) * r * std::abs(d_at_points[i]) * Eigen::RowVector3d::Unit(j / 2);
  Eigen::MatrixXd g_at;
  const Eigen::VectorXd at = d(Q, gradient ? &g_at : nullptr);
  Eigen::VectorXd out(n);
  for (Eigen::Index i = 0; i < n; ++i) out[i] = at.segment(6 * i, 6).mean();
  if (gradient) {
    gradient->resize(n, 3);
    for (Eigen::Index i = 0; i < n; ++i) {
      const double sign = d_at_points[i] < 0 ? -1 : d_at_points[i] > 0 ? 1 : 0;
      Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
      for (int j = 0; j < 6; ++j)
        sum += g_at.row(6 * i + j) + (j % 2 ? 1 : -1) * r * sign * g_at(6 * i + j, j / 2) * g_at_points.row(i);
      gradient->row(i) = sum / 6;
    }
  }
  return out;
}

}  // namespace dfm
