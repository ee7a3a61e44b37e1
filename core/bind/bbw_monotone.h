#pragma once
// Monotone bounded biharmonic weights (Jacobson 2013, ch. 5): each handle's bounded weights re-solved
// under the monotonicity constraints of 5.3.2 (no local extrema away from the handles), from the
// bounded solution as the first active set. Runs after the bounded solves, handles spread over threads.
// With normalize_rows and monotone_exact_sums, then all handles jointly with exact row sums (5.3.4,
// monotone_joint.h) from those active sets, so the rows need no division that could break an ordering.
#include <Eigen/Core>

#include "core/bind/bbw.h"
#include "core/bind/bbw_system.h"

namespace dfm {

// sys: the renumbered free system (order_free_system); X: its bounded solutions (#free x #handles),
// replaced by the monotone ones. Fills stats.monotone_*. Throws dfm::Cancelled on cancel.
void solve_monotone(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, const Eigen::VectorXi& b,
                    const Eigen::MatrixXd& bc, const FreeSystem& sys, const BbwOptions& opts, Eigen::MatrixXd& X,
                    BbwStats& stats);

}  // namespace dfm
