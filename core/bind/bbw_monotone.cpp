#include "core/bind/bbw_monotone.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "core/bind/fem.h"
#include "core/bind/monotone_constraints.h"
#include "core/bind/monotone_joint.h"
#include "core/bind/monotone_qp.h"
#include "core/mesh/mesh_info.h"

namespace dfm {

void solve_monotone(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, const Eigen::VectorXi& b,
                    const Eigen::MatrixXd& bc, const FreeSystem& sys, const BbwOptions& opts, Eigen::MatrixXd& X,
                    BbwStats& stats) {
  const auto t0 = std::chrono::steady_clock::now();
  const int m = static_cast<int>(bc.cols());
  // One representative function per handle (5.15-5.17), one factorization for all of them.
  const Eigen::MatrixXd U = monotone_representatives(cotangent_stiffness(V, T), b, bc);
  const std::vector<std::vector<int>> neighbours = vertex_neighbours(T, static_cast<int>(V.rows()));
  stats.monotone_representative_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  const bool joint = opts.normalize_rows && opts.monotone_exact_sums;
  std::vector<MonotoneQPResult> results(m);
  std::vector<MonotoneProblem> problems(m);
  std::atomic<int> next{0}, done{0};
  std::mutex mu;
  std::exception_ptr failed;
  auto work = [&] {
    for (int j; (j = next.fetch_add(1)) < m;) {
      try {
        {
          std::lock_guard<std::mutex> lock(mu);
          if (failed) return;
        }
        problems[j] = monotone_problem(neighbours, U.col(j), sys.vertex, b, bc.col(j));
        const MonotoneProblem& p = problems[j];
        results[j] = solve_monotone_qp(sys.Qff, sys.G.col(j), p, X.col(j), opts.qp.tolerance, opts.qp.cancel);
        std::lock_guard<std::mutex> lock(mu);
        X.col(j) = results[j].x;
        results[j].x.resize(0);
        stats.monotone_sides_without_neighbour += p.free_without_neighbour;
        if (opts.progress) opts.progress("monotone", 0.65 + (joint ? 0.2 : 0.35) * ++done / m);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mu);
        if (!failed) failed = std::current_exception();
        return;
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::min(opts.threads, m); ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  if (failed) std::rethrow_exception(failed);

  stats.monotone = true;
  stats.monotone_optimal = true;
  for (const MonotoneQPResult& r : results) {
    stats.monotone_iterations_total += r.iterations;
    stats.monotone_iterations_max = std::max(stats.monotone_iterations_max, r.iterations);
    stats.monotone_dual_residual = std::max(stats.monotone_dual_residual, r.dual_residual);
    stats.monotone_optimal = stats.monotone_optimal && r.optimal;
  }
  if (joint) {
    // 5.3.4: dividing by row sums that differ between neighbours turns flat stretches into extrema; the
    // joint solve with exact sums, from the per-handle active sets, needs no division.
    const auto tj = std::chrono::steady_clock::now();
    MonotoneJointResult r = solve_monotone_joint(sys.Qff, sys.G, problems, X, opts.qp.tolerance, opts.qp.cancel);
    if (!r.feasible) {  // adding only fixed a whole row to values not summing to 1: with PDAS steps instead
      const int before = r.iterations;
      r = solve_monotone_joint(sys.Qff, sys.G, problems, X, opts.qp.tolerance, opts.qp.cancel, 10);
      r.iterations += before;
    }
    stats.monotone_joint_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - tj).count();
    stats.monotone_joint_iterations = r.iterations;
    stats.monotone_sum_residual = r.sum_residual;
    stats.monotone_joint = r.feasible;
    if (r.feasible) {
      X = r.X;
      stats.monotone_optimal = r.optimal;
      stats.monotone_dual_residual = r.dual_residual;
    }
  }
  stats.monotone_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace dfm
