#include "core/anim/rounded_distance.h"

#include <cmath>

#include "core/util/error.h"

namespace dfm {

Eigen::VectorXd rounded_distance(const SignedDistance& d, const Eigen::MatrixXd& P, double r) {
  if (!(r >= 0 && r < 1)) throw Error("rounded distance: the radius factor must be in [0, 1)");
  if (P.cols() != 3) throw Error("rounded distance: needs #P x 3 points");
  const Eigen::VectorXd d_at_points = d(P);
  if (r == 0) return d_at_points;
  // The octahedron's vertices about each point: Q's rows 6 i .. 6 i + 5 for P's row i.
  const Eigen::Index n = P.rows();
  Eigen::MatrixXd Q(6 * n, 3);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int j = 0; j < 6; ++j)
      Q.row(6 * i + j) = P.row(i) + (j % 2 ? 1 : -1) * r * std::abs(d_at_points[i]) * Eigen::RowVector3d::Unit(j / 2);
  const Eigen::VectorXd at = d(Q);
  Eigen::VectorXd out(n);
  for (Eigen::Index i = 0; i < n; ++i) out[i] = at.segment(6 * i, 6).mean();
  return out;
}

}  // namespace dfm
