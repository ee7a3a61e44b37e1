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
#include "core/bind/monotone_qp.h"

namespace dfm {

void solve_monotone(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, const Eigen::VectorXi& b,
                    const Eigen::MatrixXd& bc, const FreeSystem& sys, const BbwOptions& opts, Eigen::MatrixXd& X,
                    BbwStats& stats) {
  const auto t0 = std::chrono::steady_clock::now();
  const int m = static_cast<int>(bc.cols());
  // One representative function per handle (5.15-5.17), one factorization for all of them.
  const Eigen::MatrixXd U = monotone_representatives(cotangent_stiffness(V, T), b, bc);
  const std::vector<std::vector<int>> neighbours = tet_vertex_neighbours(T, static_cast<int>(V.rows()));
  stats.monotone_representative_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  std::vector<MonotoneQPResult> results(m);
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
        const MonotoneProblem p = monotone_problem(neighbours, U.col(j), sys.vertex, b, bc.col(j));
        results[j] = solve_monotone_qp(sys.Qff, sys.G.col(j), p, X.col(j), opts.qp.tolerance, opts.qp.cancel);
        std::lock_guard<std::mutex> lock(mu);
        X.col(j) = results[j].x;
        results[j].x.resize(0);
        stats.monotone_sides_without_neighbour += p.free_without_neighbour;
        if (opts.progress) opts.progress("monotone", 0.65 + 0.35 * ++done / m);
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
  stats.monotone_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace dfm
