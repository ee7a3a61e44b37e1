#pragma once
// Box-constrained convex QP:  min 1/2 x^T H x + g^T x  subject to  lo <= x <= hi,
// H sparse symmetric positive definite (both triangles stored).
//
// Solver: primal-dual active set (Hintermueller-Ito-Kunisch semismooth Newton). Each iteration fixes
// the active variables at their bounds and solves exactly (sparse Cholesky, CHOLMOD) on the free set
// only, so the cost follows the support of the solution, not the mesh size. Between face solves a few
// projected Gauss-Seidel sweeps move the support front (see smoothing_sweeps). PDAS can cycle when H is
// not an M-matrix (H = L M^-1 L is not): on a repeated active set it drops the sweeps and goes on as plain
// PDAS, and on a second repeat or the iteration cap it switches to a monotone primal active-set method
// (strict objective decrease, so it cannot cycle). It stops only at a KKT point: it never returns a
// fixed-few-iterations answer as converged.
#include <atomic>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>

#include "core/bind/cholesky.h"

namespace dfm {

// The lower triangle of a symmetric H in the elimination order perm (perm[k] = the variable eliminated
// k-th): entry (r, c) of column c is H(perm[r], perm[c]) for r >= c, rows sorted. A face is read off it by
// dropping the bound positions, which keeps it sorted and in elimination order.
struct OrderedLower {
  std::vector<int> perm;
  std::vector<int> colptr, rows;
  std::vector<double> values;
};
// Throws dfm::Error if perm is not a permutation of H's rows.
OrderedLower ordered_lower(const Eigen::SparseMatrix<double>& H, std::vector<int> perm);

struct BoxQPOptions {
  double tolerance = 1e-6;     // KKT residual to stop at (see box_qp_kkt_residual)
  const std::atomic<bool>* cancel = nullptr;  // polled once per iteration; throws dfm::Cancelled
  // H's lower triangle in a fill-reducing order (ordered_lower), shared by every face solve of every QP
  // on H (and by concurrent solver threads). Null: built once per call with an AMD ordering.
  const OrderedLower* ordered = nullptr;
  // H's own variable order is already a fill-reducing one (H was renumbered by it, rows sorted, H
  // compressed): faces are read straight off H's lower part, no OrderedLower copy; `ordered` is ignored.
  bool in_elimination_order = false;
  // Projected Gauss-Seidel sweeps after each PDAS face solve (0 = plain PDAS): at least this many, more
  // on large faces (a face's factorization costs ~n^2 in 3-D, a sweep ~n, so more sweeps pay there).
  // The sweeps carry the support front many rings per face. Deterministic, unlike a time budget.
  int smoothing_sweeps = 20;
  // Over-relaxation factor of the sweeps, in (0, 2) (1 = plain Gauss-Seidel): carries the smooth,
  // far-reaching part of a correction further per sweep; near 1.8 PDAS starts to revisit active sets.
  double smoothing_relaxation = 1.6;
  // The sweeps visit only variables whose neighbours moved by more than max(tolerance / 10, this times
  // the KKT residual of the face's solution): corrections far below the current residual are redone
  // exactly by the next face solve anyway. After a face that does not halve the residual of the one
  // before, tolerance / 10 for the rest of the solve. 0 = always tolerance / 10.
  double smoothing_threshold_relative = 0.01;
  // Sweeps before the first face when a start x0 is given: the larger of smoothing_sweeps and this times
  // the number of variables (0 = none), thresholded as above relative to the start's KKT residual. They
  // fix what a start is worst at (clipped, or interpolated from a coarser mesh: off on the fine scale)
  // before the first face is read off it.
  double presmoothing_sweeps_per_variable = 0;
};

struct BoxQPResult {
  Eigen::VectorXd x;
  int iterations = 0;          // linear solves on a free set
  int fallback_iterations = 0; // of which in the monotone fallback
  double kkt_residual = 0;     // see box_qp_kkt_residual
  bool converged = false;
  int num_free = 0;            // free variables at the solution
  bool sweeps_dropped = false; // PDAS with sweeps revisited an active set and went on without them
};

// KKT residual of x, in the units of x: the natural residual max_i |x_i - clip(x_i - grad_i / H_ii)|,
// grad = H x + g: the gradient relative to each variable's own curvature (its scale). It is zero exactly
// at the minimizer: |grad_i| for free i, max(0, -grad_i) at a lower bound, max(0, grad_i) at an upper
// bound, each divided by H_ii; bound violations count as their size.
double box_qp_kkt_residual(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& g, const Eigen::VectorXd& lo,
                           const Eigen::VectorXd& hi, const Eigen::VectorXd& x);

// x0: starting guess (e.g. the bound-free minimizer); it need not be feasible. Empty = start at lo.
BoxQPResult solve_box_qp(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& g, const Eigen::VectorXd& lo,
                         const Eigen::VectorXd& hi, const Eigen::VectorXd& x0, const BoxQPOptions& opts = {});

// Rows and columns `idx` of A (in that order).
Eigen::SparseMatrix<double> principal_submatrix(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXi& idx);

}  // namespace dfm
