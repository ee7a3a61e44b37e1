#pragma once
// Monotone weights with an exact partition of unity (Jacobson 2013, 5.3.4): all handles' QPs (monotone_qp.h)
// solved jointly with sum_j x_ij = 1 at every free vertex, so no post-hoc division by the row sums can
// break a weight's ordering (dividing a flat stretch by sums that vary turns it into local extrema).
//   min sum_j 1/2 x_j^T H x_j + g_j^T x_j   s.t.  x_j[upper] >= x_j[lower] (problem j),  sum_j x_ij = 1.
// Primal-dual active set as in monotone_qp.h, one active set per handle. Each step solves the equality-
// constrained reduced problem by the method of multipliers on one CHOLMOD factorization of
// blockdiag(P_j^T H P_j) + rho C^T C (C: the rows' sums over the group unknowns), to round-off.
#include <atomic>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>

#include "core/bind/monotone_constraints.h"

namespace dfm {

struct MonotoneJointResult {
  Eigen::MatrixXd X;           // #free x #handles
  int iterations = 0;          // joint reduced solves
  int add_only_iterations = 0;
  double dual_residual = 0;    // largest released-but-needed multiplier, weight units
  double sum_residual = 0;     // max |sum_j x_ij - 1|
  bool optimal = false;         // feasible, and every multiplier >= -tolerance (with the row multipliers found)
  // Every ordering constraint and row sum holds (sum_residual <= 1e-12). False when the add-only phase
  // fixed every handle's weight at a vertex to values not summing to 1: X is then the last iterate.
  bool feasible = false;
};

// problems[j]: handle j's constraints (fixed nodes carry the handle's boundary values, whose rows sum to 1).
// X0: a start whose ties and orderings pick the first active sets (the per-handle monotone solutions).
// max_iterations: PDAS steps (releasing constraints with negative multipliers) before it only adds violated
// ones. The default 1 only adds: from the per-handle optimal active sets the joint PDAS churns (about
// twice the joint solves for a barely lower objective), and the row multipliers are not unique where a
// row has no group of its own, so a released constraint can be wrong.
// Adding only can end infeasible from a poor start (feasible false); the bind then retries with 10 steps.
MonotoneJointResult solve_monotone_joint(const Eigen::SparseMatrix<double>& H, const Eigen::MatrixXd& G,
                                         const std::vector<MonotoneProblem>& problems, const Eigen::MatrixXd& X0,
                                         double tolerance, const std::atomic<bool>* cancel = nullptr,
                                         int max_iterations = 1);

}  // namespace dfm
