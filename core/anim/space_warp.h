#pragma once
// A smooth space warp through picked pairs of points (Cohen-Or, Solomovici and Levin 1998: a warp the
// user guides by corresponding features, interpolated over the morph; Southern 10.1.1, guiding
// shapes). Radial basis functions with the triharmonic kernel r^3 plus an affine part (the smoothest
// interpolant in 3D, C2, exact on affine maps):
//   W(x) = x + D(x),  D(x) = sum_i w_i |x^ - c^_i|^3 + a + B x^,  x^ = (x - mean) / spread
// (mean and spread of the `from` points: the fit does not depend on the frame or the units), with
// D(from_i) = to_i - from_i, sum_i w_i = 0 and sum_i w_i c^_i^T = 0. B acts only along the principal
// axes of the c^_i whose spread is at least a tenth of the largest (B = sum over those axes e of
// b_e e^T; the side conditions likewise): fewer than 4 pairs, or pairs in or near a plane, leave the
// affine part underdetermined across it, and read off the pairs' small deviations from the plane it
// would squash space flat there. (One pair: a translation; two: a translation and a stretch along
// the pair's line.)
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace dfm {

struct SpaceWarp {
  Eigen::RowVector3d mean = Eigen::RowVector3d::Zero();
  double spread = 1;
  Eigen::MatrixXd centres = Eigen::MatrixXd(0, 3);  // c^_i, normalised
  Eigen::MatrixXd weights = Eigen::MatrixXd(0, 3);  // w_i
  Eigen::Matrix<double, 4, 3> affine = Eigen::Matrix<double, 4, 3>::Zero();  // rows a, then B^T's rows

  bool identity() const { return centres.rows() == 0; }
  Eigen::RowVector3d displacement(const Eigen::RowVector3d& x) const;  // D(x)
  Eigen::Matrix3d displacement_jacobian(const Eigen::RowVector3d& x) const;  // dD/dx (rows: components of D)
};

// The warp with W(from_i) = to_i (#pairs x 3 each; none: the identity). Throws dfm::Error when two
// `from` points coincide or a value is not finite.
SpaceWarp fit_space_warp(const Eigen::MatrixXd& from, const Eigen::MatrixXd& to);

// W(x), and W interpolated linearly to u in [0, 1]: x + u D(x) (Cohen-Or et al. 1998, the warp's
// in-betweens).
Eigen::RowVector3d warp(const SpaceWarp& w, const Eigen::RowVector3d& x, double u = 1);

// The x with W(x) = y (Newton's method from y). Throws dfm::Error when it does not converge or the
// warp turns space inside out there (det dW/dx <= 0).
Eigen::RowVector3d unwarp(const SpaceWarp& w, const Eigen::RowVector3d& y);

// The warp through picked pairs taken in equal steps: step k is the warp (above) from the points
// from + (k - 1)/n (to - from) to from + k/n (to - from), and W the steps in turn. Each step moves
// space by 1/n of the pairs' displacements, so where one warp through far-moved pairs folds space
// (pairs pulled apart across a limb), the steps stay invertible and so does their composition (a
// flow along the pairs' straight paths). An affine map between the pairs is reproduced exactly, as
// by one warp.
struct WarpPath {
  std::vector<SpaceWarp> steps;
  bool identity() const { return steps.empty(); }
};
WarpPath fit_warp_path(const Eigen::MatrixXd& from, const Eigen::MatrixXd& to, int steps);

// W_u: the first floor(u n) steps, then the next one's displacement times the rest of u n (each
// step's own in-between, as above). A picked point travels its straight path: W_u(from_i) =
// from_i + u (to_i - from_i).
Eigen::RowVector3d warp(const WarpPath& w, const Eigen::RowVector3d& x, double u = 1);

// The x with W(x) = y, the steps undone in reverse order. Throws as unwarp does.
Eigen::RowVector3d unwarp(const WarpPath& w, const Eigen::RowVector3d& y);

// unwarp of each row of Y (#Y x 3). Throws as unwarp does.
Eigen::MatrixXd unwarp_rows(const WarpPath& w, const Eigen::MatrixXd& Y);

// The smallest u in {1/4, 1/2, ...} of each step (at the step's quarters) where W_u turns space
// inside out at x's path (det of the step's map at most 0), or none.
std::optional<double> fold_time(const WarpPath& w, const Eigen::RowVector3d& x);

// The first row of X (#X x 3) whose path folds (fold_time) and when, or none.
struct PathFold {
  Eigen::Index row = -1;
  double u = 0;
};
std::optional<PathFold> first_fold(const WarpPath& w, const Eigen::MatrixXd& X);

}  // namespace dfm
