#pragma once
// Bounded biharmonic weights (Jacobson 2013, ch. 4) on a tet mesh with given boundary conditions.
//
//   min  sum_j 1/2 w_j^T Q w_j   s.t.  w_j(b) = bc_j,  0 <= w_j <= 1       (default: each handle alone,
//   Q = K M^-1 K [+ G^T (R D) G]                                            then rows normalized)
//   [+ sum_j w_ij = 1 for every vertex i, all handles jointly]             (exact partition of unity)
// K: cotangent stiffness, M: lumped mass (fem.h); the optional per-tet mask rho (R) adds the
// shape-preservation term of Eq. 4.7 with D the tet volumes.
#include <atomic>
#include <functional>
#include <string>

#include <Eigen/Core>
#include <Eigen/Sparse>

#include "core/bind/qp.h"

namespace dfm {

// The box QP settings of the bounded weight solves: presmoothing on, since every start handed to them
// (a clipped bound-free solution, a coarse level's weights) is off on the fine scale.
inline BoxQPOptions bbw_qp_defaults() {
  BoxQPOptions o;
  o.presmoothing_sweeps_per_variable = 0.001;
  return o;
}

struct BbwOptions {
  // tolerance: KKT residual in weight units (box_qp_kkt_residual / exact_pou_kkt_residual); cancel:
  // throws dfm::Cancelled when set; the sweeps of each bounded solve.
  BoxQPOptions qp = bbw_qp_defaults();
  bool exact_partition_of_unity = false;
  // Ch. 5: no local extrema away from the handles (bbw_monotone.h); default mode only (not with
  // exact_partition_of_unity).
  bool monotone = false;
  // Monotone with normalize_rows: solve all handles jointly with exact row sums (monotone_joint.h), so the
  // final weights keep every ordering; false divides the per-handle solutions by their row sums (5.3.4).
  bool monotone_exact_sums = true;
  bool normalize_rows = true;  // default mode; false returns each handle's own minimizer (analysis, tests)
  // Per-tet rho >= 0, or empty. Scaled so that rho = 1 weighs like the biharmonic term (the mask term is
  // multiplied by mean diag(Q) / mean diag(K), making rho unitless); painted regions use rho >> 1.
  Eigen::VectorXd shape_mask;
  int threads = 2;
  // Volumes with at least this many vertices start their bounded solves from the weights of a coarser
  // mesh of the same domain (coarse_level.h); 0 = always from the bound-free solution.
  int multilevel_min_vertices = 20000;
  // How long the first solver thread may sit idle waiting for the coarse level's next handle before it
  // stops it (the remaining handles then start from the bound-free solution); < 0: max(2 s, twice the
  // assembly and ordering time).
  double multilevel_patience_seconds = -1;
  // Called from the calling thread and the solver threads (serialized); fraction of the whole solve in
  // [0, 1]: assembly 0, factorization 0.1, solve 0.3 .. 1. May be empty.
  std::function<void(const std::string& stage, double fraction)> progress;
  // Default mode: called (serialized) as soon as a handle's QP is solved, with its weights on every
  // vertex before rows are normalized. May be empty.
  std::function<void(int handle, const Eigen::VectorXd& weights)> handle_solved;
};

struct BbwStats {
  double assembly_seconds = 0;       // K, M, Q
  double factorization_seconds = 0;  // ordering (+ shared factorization and bound-free solve when no
                                     // coarse level starts the solves)
  double solve_seconds = 0;          // bounded QPs (with a coarse level: from the end of the ordering)
  int iterations_total = 0;          // free-set solves over all handles
  int iterations_max = 0;            // the worst handle
  int fallback_iterations = 0;       // monotone fallback steps (0 when PDAS converged alone)
  double kkt_residual = 0;           // worst relative KKT residual of the QP(s) solved
  bool converged = false;
  long factor_nonzeros = 0;
  int rows_renormalized_from_zero = 0;  // default mode: vertices where every weight was 0
  bool multilevel = false;              // some bounded solves started from a coarse level's weights
  int multilevel_handles = 0;           // how many
  double multilevel_seconds = 0;        // building and solving the coarse level (on its own thread,
                                        // alongside assembly and ordering)
  // Monotone weights (opts.monotone): seconds in all (within solve_seconds), of which the representative
  // functions; per-handle reduced solves; the worst released multiplier (weight units) and optimality, of
  // the joint solve when it ran, else of the per-handle ones;
  // vertex sides where u had no strictly lower/higher neighbour (the box held there instead).
  bool monotone = false;
  double monotone_seconds = 0, monotone_representative_seconds = 0;
  int monotone_iterations_total = 0, monotone_iterations_max = 0;
  double monotone_dual_residual = 0;
  bool monotone_optimal = false;
  int monotone_sides_without_neighbour = 0;
  // With normalize_rows: the joint solve with exact row sums (monotone_joint.h) that replaces the division
  // by the row sums; its seconds (within monotone_seconds), reduced solves, max |row sum - 1|, and whether
  // it met every constraint (false: the rows were divided as before).
  bool monotone_joint = false;
  double monotone_joint_seconds = 0, monotone_sum_residual = 0;
  int monotone_joint_iterations = 0;
};

// V, T: positively oriented tets. b: constrained vertex indices (distinct). bc: #b x #handles.
// Returns #V x #handles weights. Throws dfm::Error on bad input or if the solver did not converge.
Eigen::MatrixXd bbw_weights(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, const Eigen::VectorXi& b,
                            const Eigen::MatrixXd& bc, const BbwOptions& opts = {}, BbwStats* stats = nullptr);

// The biharmonic energy matrix Q = K M^-1 K (+ shape term) used above (#V x #V).
// threads: for the product K M^-1 K (same result).
Eigen::SparseMatrix<double> bbw_energy_matrix(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                                              const Eigen::VectorXd& shape_mask = {}, int threads = 1);

}  // namespace dfm
