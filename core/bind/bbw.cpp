#include "core/bind/bbw.h"

#include <chrono>
#include <string>
#include <vector>

#include "core/bind/bbw_exact.h"
#include "core/bind/bbw_monotone.h"
#include "core/bind/bbw_schedule.h"
#include "core/bind/bbw_system.h"
#include "core/bind/cholmod_memory.h"
#include "core/bind/fem.h"
#include "core/bind/sparse_kdk.h"
#include "core/util/error.h"

namespace dfm {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void validate(const Eigen::MatrixXd& V, const Eigen::VectorXi& b, const Eigen::MatrixXd& bc) {
  if (b.size() == 0) throw Error("bind: no constrained vertices (no handle touches the volume)");
  if (bc.rows() != b.size())
    throw Error("bind: " + std::to_string(bc.rows()) + " boundary-condition rows for " + std::to_string(b.size()) +
                " constrained vertices");
  if (bc.cols() == 0) throw Error("bind: no handles");
  if (!bc.allFinite()) throw Error("bind: boundary conditions are not finite");
  std::vector<char> seen(V.rows(), 0);
  for (int k = 0; k < b.size(); ++k) {
    if (b(k) < 0 || b(k) >= V.rows()) throw Error("bind: constrained vertex index " + std::to_string(b(k)) + " out of range");
    if (seen[b(k)]++) throw Error("bind: vertex " + std::to_string(b(k)) + " constrained twice");
  }
  for (int j = 0; j < bc.cols(); ++j)
    if (bc.col(j).maxCoeff() <= 0)
      throw Error("bind: handle " + std::to_string(j) + " has no vertex in the volume (its weights would be all zero)");
}

Eigen::MatrixXd solve_weights(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, const Eigen::VectorXi& b,
                              const Eigen::MatrixXd& bc, const BbwOptions& opts, BbwStats* stats_out);

}  // namespace

Eigen::MatrixXd bbw_weights(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, const Eigen::VectorXi& b,
                            const Eigen::MatrixXd& bc, const BbwOptions& opts, BbwStats* stats_out) {
  try {
    return solve_weights(V, T, b, bc, opts, stats_out);
  } catch (const Error& e) {
    // The solvers speak of matrices; what it means for a bind is said here.
    const std::string what = e.what();
    if (what.find("not positive definite") == std::string::npos) throw;
    throw Error(what + " (is every connected part of the volume constrained by a handle?)");
  }
}

Eigen::SparseMatrix<double> bbw_energy_matrix(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                                              const Eigen::VectorXd& shape_mask, int threads) {
  const Eigen::SparseMatrix<double> K = cotangent_stiffness(V, T);
  const Eigen::VectorXd m = lumped_mass(V, T);
  const Eigen::VectorXd minv = m.cwiseInverse();
  Eigen::SparseMatrix<double> Q = symmetric_kdk(K, minv, threads);
  if (shape_mask.size()) {
    const double qd = Q.diagonal().mean(), kd = K.diagonal().mean();
    Q += (qd / kd) * masked_stiffness(V, T, shape_mask);
  }
  Q.makeCompressed();
  return Q;
}

namespace {

// Default mode: each handle's weights divided by their row sums. A row of all zeros (every handle's weight
// hit the bound there) takes the clipped starting point instead (the bound-free solution, which sums to 1
// before clipping, or the coarse level's weights).
int normalize_rows(Eigen::MatrixXd& W, const Eigen::VectorXi& vertex, const Eigen::MatrixXd& start) {
  int from_zero = 0;
  for (int k = 0; k < vertex.size(); ++k) {
    const int i = vertex(k);
    double s = W.row(i).sum();
    if (s <= 1e-12) {
      W.row(i) = start.row(k).cwiseMax(0.0).cwiseMin(1.0);
      s = W.row(i).sum();
      ++from_zero;
      if (s <= 1e-12) W.row(i).setConstant(1.0 / W.cols()), s = 1.0;
    }
    W.row(i) /= s;
  }
  return from_zero;
}

// The recipe (Jacobson 2013, 4.2): energy, free/fixed split, a start, one box QP per handle (or the
// joint QP with exact partition of unity), normalized rows.
Eigen::MatrixXd solve_weights(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, const Eigen::VectorXi& b,
                              const Eigen::MatrixXd& bc, const BbwOptions& opts, BbwStats* stats_out) {
  validate(V, b, bc);
  if (opts.monotone && opts.exact_partition_of_unity)
    throw Error("bind: monotone weights sum to 1 exactly on their own; they do not combine with "
                "exact_partition_of_unity");
  const CholmodBlockCacheScope release_cache;
  auto progress = [&](const char* stage, double f) {
    if (opts.qp.cancel && opts.qp.cancel->load()) throw Cancelled();
    if (opts.progress) opts.progress(stage, f);
  };
  const bool multilevel = !opts.exact_partition_of_unity && opts.multilevel_min_vertices > 0 &&
                          V.rows() >= opts.multilevel_min_vertices;
  // With monotone weights the bounded solves take the progress to 0.65 and the monotone ones the rest.
  BbwOptions bounded_opts = opts;
  if (opts.monotone && opts.progress)
    bounded_opts.progress = [&opts](const std::string& s, double f) {
      opts.progress(s, f <= 0.3 ? f : 0.3 + 0.35 * (f - 0.3) / 0.7);
    };
  BoundedSolves bounded(V, T, b, bc, bounded_opts, multilevel);  // a coarse level starts now, on its own thread
  BbwStats stats;

  progress("assembly", 0.0);
  auto t0 = std::chrono::steady_clock::now();
  // Both cores, unless the coarse level's thread has the other one.
  FreeSystem sys = split_free_fixed(bbw_energy_matrix(V, T, opts.shape_mask, multilevel ? 1 : opts.threads), b, bc);
  stats.assembly_seconds = seconds_since(t0);

  progress("factorization", 0.1);
  t0 = std::chrono::steady_clock::now();
  Eigen::MatrixXd X0 = order_free_system(sys, !multilevel, opts.threads, [&] { progress("factorization", 0.2); });
  stats.factor_nonzeros = sys.factor_nonzeros;
  if (multilevel) trim_heap();  // the ordering's workspace, before the face solves reach the bind's peak
  stats.factorization_seconds = seconds_since(t0);

  progress("solve", 0.3);
  t0 = std::chrono::steady_clock::now();
  Eigen::MatrixXd X, start;
  if (opts.exact_partition_of_unity) {
    const ExactPouResult r = solve_exact_pou(sys.Qff, sys.G, X0, opts.qp.tolerance, opts.qp.cancel);
    X = r.X;
    start = X0;
    stats.iterations_total = stats.iterations_max = r.iterations;
    stats.fallback_iterations = r.fallback_iterations;
    stats.kkt_residual = r.kkt_residual;
    stats.converged = r.converged;
  } else {
    X = bounded.run(sys, std::move(X0), start, stats);
  }
  if (!stats.converged)
    throw Error("bind: the weight solver did not converge (relative KKT residual " +
                std::to_string(stats.kkt_residual) + ")");
  if (opts.monotone) solve_monotone(V, T, b, bc, sys, opts, X, stats);
  stats.solve_seconds = seconds_since(t0);

  Eigen::MatrixXd W(V.rows(), bc.cols());
  for (int k = 0; k < sys.vertex.size(); ++k) W.row(sys.vertex(k)) = X.row(k);
  for (int k = 0; k < b.size(); ++k) W.row(b(k)) = bc.row(k);
  if (!opts.exact_partition_of_unity && opts.normalize_rows && !stats.monotone_joint)
    stats.rows_renormalized_from_zero = normalize_rows(W, sys.vertex, start);
  if (stats_out) *stats_out = stats;
  progress("done", 1.0);
  return W;
}

}  // namespace
}  // namespace dfm
