#pragma once
// Smooth weights (Blender's weight paint "Smooth"): each iteration moves every free weight a fraction
// `factor` of the way to the weighted mean of its neighbours,
//   w_i <- (1 - factor) w_i + factor * sum_j c_ij w_j / sum_j c_ij,
// with c_ij = 1 per edge (uniform, Blender's) or the clamped cotangent weights (surface_laplacian.h),
// then renormalizes the row with the locked weights kept (normalize_locked). A convex combination of
// rows in [0, 1] that sum to 1 stays so (Jacobson 2013, Eq. 4.5-4.6). It is a damped Jacobi step on
// K w = 0, so for factor in (0, 1] it never raises the Dirichlet energy w^T K w of a column (K's
// diagonal dominates: its eigenvalues relative to the diagonal lie in [0, 2]).
// Smoothing spreads weights: rows may get more nonzeros (limit_influences afterwards if that matters).
#include <vector>

#include <Eigen/Core>

namespace dfm {

struct SmoothOptions {
  int iterations = 1;      // 0..1000
  double factor = 0.5;     // (0, 1]
  bool cotangent = false;  // false: uniform neighbour average (Blender); true: clamped cotangent weights
};

// W: #V x #handles on the surface (V, F). Locked columns and `fixed` rows (#V flags or empty: the
// bind's constrained vertices) are kept bit for bit. Throws dfm::Error for bad options or sizes.
Eigen::MatrixXd smooth_weights(const Eigen::MatrixXd& W, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                               const std::vector<int>& locked, const std::vector<bool>& fixed,
                               const SmoothOptions& opts);

}  // namespace dfm
