#pragma once
// Local transitions between two same-connectivity keys in Laplacian (differential) coordinates
// (Alexa 2002, 4.3): each vertex i has its own transition state s_i (0: the first key, 1: the second);
// the Laplacian coordinates are blended per vertex (Eq. 4.18 with T(i) = (1 - s_i, s_i)) and the
// absolute coordinates recovered by a sparse least-squares solve, so a region can take the second key's
// shape while staying attached to the rest.
//
// L = I - D A is 4.3.1's uniform Laplacian (Eq. 4.16-4.17). With W_k = L V_k the blend asks for
//   min_V |L V - W~|^2,  W~_i = (1 - s_i) W0_i + s_i W1_i.
// L has the constants of each connected part as its null space (4.3.3), so the translation is free; we
// solve for the correction E = V - P to the per-vertex blend of absolute coordinates
// P_i = (1 - s_i) K0_i + s_i K1_i, i.e. min |L E - (W~ - L P)|^2, anchored at one vertex per part and then
// shifted so E has zero mean on each part: the centroid of every part is that of P. This keeps the
// acceptance properties exact: a uniform state s makes W~ - L P vanish up to rounding, so V is the linear
// blend; states all 0 (all 1) make it vanish exactly, so V is K0 (K1) bit for bit. The normal matrix
// L^T L (anchors removed) depends only on the connectivity; it is factored once per key set (CHOLMOD);
// 4.3.3's ILU-preconditioned CG is for memory this program does not lack.
#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>

#include "core/bind/cholesky.h"

namespace dfm {

class DifferentialBlend {
 public:
  // K0, K1: #V x 3 keys of the one triangle set F. Throws dfm::Error if the keys differ in size or F
  // indexes past them.
  DifferentialBlend(const Eigen::MatrixXd& K0, const Eigen::MatrixXd& K1, const Eigen::MatrixXi& F);

  // The blended surface for per-vertex states (#V); a state outside [0, 1] extrapolates.
  Eigen::MatrixXd at(const Eigen::VectorXd& states) const;

  double factor_seconds() const { return factor_seconds_; }

 private:
  Eigen::MatrixXd K0_, K1_, W0_, W1_;
  Eigen::SparseMatrix<double> L_;
  std::vector<int> part_;     // connected part of each vertex
  std::vector<int> free_;     // every vertex but one anchor per part
  int parts_ = 0;
  SpdSolver solver_;          // (L^T L)_{free, free}
  double factor_seconds_ = 0;
};

// Per-vertex states at the interval's time t from per-vertex offsets S (each in (-1, 1)): S_i > 0 makes
// vertex i arrive early, running its whole transition over t in [0, 1 - S_i]; S_i < 0 makes it start
// late, over [-S_i, 1]; S_i = 0 is s_i = t. So every vertex is at state 0 at t = 0 and 1 at t = 1 (the
// keys stay keys) and s_i(t) is continuous and non-decreasing. Outside [0, 1] every state is t
// (extrapolation as for one uniform state). Throws dfm::Error for an offset outside (-1, 1).
Eigen::VectorXd transition_states(const Eigen::VectorXd& offsets, double t);

}  // namespace dfm
