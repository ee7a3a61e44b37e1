#pragma once
// Limit total influences (Blender's "Limit Total"), smoothly: each vertex keeps its k largest weights,
// and instead of only cutting the others and rescaling (a jump wherever a handle falls from k-th to
// (k+1)-th place), each handle's kept weights are re-solved near the cut.
//
// The re-solve, per handle j, near the vertices where j was cut (within 3 * radius edges): the unknowns
// are w_j at those vertices that keep j; w_j is 0 where j was cut and keeps its value everywhere else.
// It minimizes
//   t w^T K w + (w - w0)^T M (w - w0),   t = (radius * mean edge length)^2
// (K: clamped cotangent stiffness, M: lumped mass, surface_laplacian.h; w0: the weights before): an
// implicit diffusion step of about `radius` edges that brings w_j down to the 0 where it was cut
// instead of jumping there; K an M-matrix keeps w_j in [0, 1] (maximum principle). Then every changed
// row is divided by its sum. So: at most k nonzeros per row (nonzeros never appear), rows sum to 1,
// weights in [0, 1] (BBW's Eq. 4.5-4.6, Jacobson 2013, 4.3.1), away from the cuts the weights as they
// were, and a smaller Dirichlet energy than the plain cut (bench_weight_tools prints both).
// A larger radius smooths more (lower energy) and departs further from the bind's weights.
#include <vector>

#include <Eigen/Core>

namespace dfm {

struct LimitOptions {
  int k = 4;            // influences kept per vertex (>= 1)
  double radius = 1.0;  // how far the re-solve spreads a cut, in mean edge lengths; 0 = plain cut
};

struct LimitReport {
  int rows_limited = 0;       // rows that had more than k nonzero weights
  int fixed_rows_over_k = 0;  // constrained rows (fixed) with more than k nonzeros, kept as they were
};

// W: #V x #handles, rows summing to 1. V, F: the surface W lives on. fixed: #V flags (or empty) of rows
// kept bit for bit (the bind's constrained vertices, weight_constraints.h), and so are rows farther
// than the re-solve's reach from every cut. Throws dfm::Error for k < 1, radius < 0 or mismatched sizes.
Eigen::MatrixXd limit_influences(const Eigen::MatrixXd& W, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                 const std::vector<bool>& fixed, const LimitOptions& opts,
                                 LimitReport* report = nullptr);

// The k largest nonzeros of each row (ties: the lower handle), as flags #V x #handles; rows of `fixed`
// and rows with at most k nonzeros keep all of theirs.
Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic> kept_influences(const Eigen::MatrixXd& W, int k,
                                                                   const std::vector<bool>& fixed);

}  // namespace dfm
