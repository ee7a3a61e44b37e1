#pragma once
// The convex QP of Jacobson 2013, Eq. 5.12-5.14, for one weight function:
//   min 1/2 x^T H x + g^T x   s.t.  x[upper] >= x[lower] for each constraint (monotone_constraints.h),
// where a node past #free stands for a fixed value. The box 0 <= x <= 1 is implied: every chain of
// constraints ends at a handle's values.
//
// Solver: primal-dual active set on the pairwise constraints. An active set says which neighbours are
// equal; they are merged into one unknown (fixed when the group reaches a fixed value), and the reduced
// system P^T H P is solved exactly (CHOLMOD). The multipliers of the active constraints follow from the
// gradient on a spanning tree of each group (flows from its leaves); negative ones are released, violated
// constraints added. After max_iterations such steps, or on a repeated active set, it only adds (the
// active set grows, so it ends): every constraint holds exactly at return, optimal or not. On the hand and
// the arm the objective has settled to 1e-8 relative well within 10 steps while the active set still
// churns on multipliers of ~1e-4 weight units, hence the small default cap.
#include <atomic>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>

#include "core/bind/monotone_constraints.h"

namespace dfm {

struct MonotoneQPResult {
  Eigen::VectorXd x;
  int iterations = 0;          // reduced solves
  int add_only_iterations = 0; // of which after a repeated active set
  int active = 0;              // active constraints at the end
  int groups = 0;              // unknowns of the last reduced system
  // Largest released-but-needed multiplier, in weight units (|lambda| / mean diag H): 0 at the optimum.
  double dual_residual = 0;
  bool optimal = false;        // the active set settled with every multiplier >= -tolerance
};

// x0: a start whose ordering picks the first active set (e.g. the bounded biharmonic weights), or empty.
// tolerance: on multipliers, in weight units. Throws dfm::Cancelled when cancel is set.
MonotoneQPResult solve_monotone_qp(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& g,
                                   const MonotoneProblem& problem, const Eigen::VectorXd& x0, double tolerance,
                                   const std::atomic<bool>* cancel = nullptr, int max_iterations = 10);

}  // namespace dfm
