#include "core/bind/bbw.h"

#include <malloc.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/bind/bbw_exact.h"
#include "core/bind/cholmod_memory.h"
#include "core/bind/coarse_level.h"
#include "core/bind/numeric_threads.h"
#include "core/bind/fem.h"
#include "core/bind/qp.h"
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

}  // namespace

Eigen::SparseMatrix<double> bbw_energy_matrix(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                                              const Eigen::VectorXd& shape_mask) {
  const Eigen::SparseMatrix<double> K = cotangent_stiffness(V, T);
  const Eigen::VectorXd m = lumped_mass(V, T);
  const Eigen::VectorXd minv = m.cwiseInverse();
  Eigen::SparseMatrix<double> Q = symmetric_kdk(K, minv);
  if (shape_mask.size()) {
    const double qd = Q.diagonal().mean(), kd = K.diagonal().mean();
    Q += (qd / kd) * masked_stiffness(V, T, shape_mask);
  }
  Q.makeCompressed();
  return Q;
}

Eigen::MatrixXd bbw_weights(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, const Eigen::VectorXi& b,
                            const Eigen::MatrixXd& bc, const BbwOptions& opts, BbwStats* stats_out) {
  validate(V, b, bc);
  single_threaded_numerics();  // we run one QP per thread; see numeric_threads.h
  install_cholmod_block_cache();
  const CholmodBlockCacheScope release_cache;
  BbwStats stats;
  auto progress = [&](const char* stage, double f) {
    if (opts.cancel && opts.cancel->load()) throw Error("cancelled");
    if (opts.progress) opts.progress(stage, f);
  };
  const int n = static_cast<int>(V.rows()), m = static_cast<int>(bc.cols());

  // ---- on large meshes, a coarse level of the same domain (coarse_level.h), built and solved on a
  // thread of its own while this one assembles and orders Q: its weights, carried to this mesh, start
  // the bounded solves. Only an accelerator: if it cannot be built, the bound-free solution starts them.
  struct CoarseStart {
    bool ok = false;
    CoarseLevel level;
    Eigen::MatrixXd W;
    double seconds = 0;
    std::atomic<bool> stop{false}, done{false};
  } coarse;
  std::thread coarse_thread;
  struct Joiner {  // stops and joins on every path out of here, exceptions (cancel) included
    std::thread& t;
    std::atomic<bool>& stop;
    ~Joiner() {
      stop = true;
      if (t.joinable()) t.join();
    }
  } join_coarse{coarse_thread, coarse.stop};
  if (!opts.exact_partition_of_unity && opts.multilevel_min_vertices > 0 && n >= opts.multilevel_min_vertices) {
    coarse_thread = std::thread([&] {
      const auto tc = std::chrono::steady_clock::now();
      try {
        single_threaded_numerics();
        const CholmodBlockCacheScope release;
        if (build_coarse_level(V, T, b, bc, coarse.level, opts.multilevel_min_vertices)) {
          BbwOptions co;
          co.normalize_rows = false;
          co.tolerance = std::max(opts.tolerance, 1e-5);  // a start, not the answer
          co.threads = 1;                                 // the other core assembles and orders meanwhile
          co.cancel = &coarse.stop;
          co.multilevel_min_vertices = 0;
          // Delaunay-of-a-subset tets are often badly shaped: with sweeps that skip small moves, or
          // sweeps before the first face, PDAS needed 2-3x the faces on armadillo's coarse level (or
          // cycled); full sweeps between faces only, there.
          co.smoothing_threshold_relative = 0;
          co.presmoothing_sweeps_per_variable = 0;
          coarse.W = bbw_weights(coarse.level.V, coarse.level.T, coarse.level.b, coarse.level.bc, co);
          coarse.ok = true;
        }
      } catch (const std::exception&) {
        coarse.ok = false;  // stopped, or failed: the bound-free start instead
      }
      coarse.seconds = seconds_since(tc);
      coarse.done = true;
    });
  }

  // ---- assembly
  progress("assembly", 0.0);
  auto t0 = std::chrono::steady_clock::now();
  Eigen::SparseMatrix<double> Q = bbw_energy_matrix(V, T, opts.shape_mask);
  std::vector<int> fmap(n, 0);
  for (int k = 0; k < b.size(); ++k) fmap[b(k)] = -1;
  std::vector<int> free_list;
  for (int i = 0; i < n; ++i)
    if (fmap[i] == 0) fmap[i] = static_cast<int>(free_list.size()), free_list.push_back(i);
  const Eigen::VectorXi f = Eigen::Map<Eigen::VectorXi>(free_list.data(), free_list.size());
  const int nf = static_cast<int>(f.size());
  Eigen::SparseMatrix<double> Qff = principal_submatrix(Q, f);
  // Linear term g_j = Q_fb bc_j for every handle at once.
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(nf, m);
  for (int k = 0; k < b.size(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(Q, b(k)); it; ++it)
      if (fmap[it.row()] >= 0) G.row(fmap[it.row()]) += it.value() * bc.row(k);
  Q = Eigen::SparseMatrix<double>();  // only Q_ff from here on: 47 MB less at armadillo's peak
  stats.assembly_seconds = seconds_since(t0);

  // ---- a fill-reducing ordering of Q_ff, restricted to every face of every handle; without a coarse
  // level also one factorization shared by every handle: the bound-free biharmonic solutions start the
  // bounded solves (often nearly feasible).
  progress("factorization", 0.1);
  t0 = std::chrono::steady_clock::now();
  Eigen::MatrixXd X0;
  std::vector<int> perm;
  {
    SpdSolver chol;
    chol.analyze(Qff);
    stats.factor_nonzeros = chol.factor_nonzeros();
    perm = chol.permutation();
    if (coarse_thread.joinable()) {
      // A coarse level normally finishes about when the ordering does. One that is not done after
      // twice this thread's own work so far, and at least 2 s (a badly shaped coarse mesh can make its
      // QPs slow), is stopped: the bound-free start then costs one numeric factorization instead.
      const double wait = std::max(2.0, 2 * (stats.assembly_seconds + seconds_since(t0)));
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(wait);
      while (!coarse.done && std::chrono::steady_clock::now() < deadline) {
        if (opts.cancel && opts.cancel->load()) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
      }
      if (!coarse.done) coarse.stop = true;
      coarse_thread.join();
      if (coarse.stop) coarse.ok = false;  // stopped late: its result may be partial
    }
    progress("factorization", 0.2);
    stats.multilevel_seconds = coarse.seconds;
    if (!coarse.ok) {
      chol.factorize(Qff);
      X0 = chol.solve(-G);
    }
  }
  release_cholmod_block_cache();  // the whole-matrix factor's blocks: faces are smaller
  // From here on the free variables are renumbered in the factorization's (nested-dissection) order:
  // a vertex's neighbours then sit close to it in memory, which makes the Gauss-Seidel sweeps and
  // products with Q_ff (most of the bounded solve's time outside the factorizations) 2x faster than in
  // TetGen's order, and every face is already in elimination order.
  {
    const Eigen::VectorXi p = Eigen::Map<const Eigen::VectorXi>(perm.data(), nf);
    Qff = principal_submatrix(Qff, p);
    Eigen::MatrixXd tmp(nf, m);
    for (int k = 0; k < nf; ++k) tmp.row(k) = G.row(perm[k]);
    G.swap(tmp);
    if (X0.size()) {
      for (int k = 0; k < nf; ++k) tmp.row(k) = X0.row(perm[k]);
      X0.swap(tmp);
    }
  }
  stats.factorization_seconds = seconds_since(t0);

  // ---- bounded solves
  progress("solve", 0.3);
  t0 = std::chrono::steady_clock::now();
  // Starting points: the coarse level's weights carried to this mesh, else the bound-free solution
  // clipped to the box.
  Eigen::MatrixXd start;
  if (coarse.ok) {
    const Eigen::MatrixXd Wf = coarse.level.P * coarse.W;
    start.resize(nf, m);
    for (int k = 0; k < nf; ++k) start.row(k) = Wf.row(f(perm[k])).cwiseMax(0.0).cwiseMin(1.0);
    // Values under 1e-4 are within the coarse solve's accuracy; starting them at the bound keeps the
    // first faces (and the bind's peak memory: armadillo 606 -> 579 MB) smaller at no extra faces.
    start = (start.array() < 1e-4).select(0.0, start);
    stats.multilevel = true;
    coarse.level = CoarseLevel();
    coarse.W = Eigen::MatrixXd();
    // The coarse level's memory is free again but the C library keeps it mapped; hand it back before
    // the fine solves reach the bind's peak.
    malloc_trim(0);
  }
  const Eigen::MatrixXd& x_start = start.size() ? start : X0;
  Eigen::MatrixXd X(nf, m);
  if (opts.exact_partition_of_unity) {
    ExactPouResult r = solve_exact_pou(Qff, G, X0, opts.tolerance, opts.cancel);
    X = r.X;
    stats.iterations_total = stats.iterations_max = r.iterations;
    stats.fallback_iterations = r.fallback_iterations;
    stats.kkt_residual = r.kkt_residual;
    stats.converged = r.converged;
  } else {
    const Eigen::VectorXd lo = Eigen::VectorXd::Zero(nf), hi = Eigen::VectorXd::Ones(nf);
    std::vector<BoxQPResult> results(m);
    std::vector<std::string> errors;
    std::mutex mu;
    int next = 0, finished = 0;
    // Largest first (by the first face, the start's positive support; a face costs ~its size squared), so the
    // last handles to finish are small ones and neither thread idles long at the end.
    std::vector<int> order(m);
    std::vector<long> support(m, 0);
    for (int j = 0; j < m; ++j) {
      order[j] = j;
      for (int k = 0; k < nf; ++k) support[j] += x_start(k, j) > 0.0;
    }
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return support[a] > support[b]; });
    BoxQPOptions qo;
    qo.tolerance = opts.tolerance;
    qo.cancel = opts.cancel;
    qo.in_elimination_order = true;  // every face is read off Q_ff's lower part, shared by both threads
    qo.smoothing_threshold_relative = opts.smoothing_threshold_relative;
    qo.presmoothing_sweeps_per_variable = opts.presmoothing_sweeps_per_variable;
    auto worker = [&] {
      single_threaded_numerics();
      const CholmodBlockCacheScope release_cache;
      for (;;) {
        int j;
        {
          std::lock_guard<std::mutex> lock(mu);
          if (next >= m || !errors.empty()) return;
          j = order[next++];
        }
        try {
          BoxQPResult r = solve_box_qp(Qff, G.col(j), lo, hi, x_start.col(j), qo);
          std::lock_guard<std::mutex> lock(mu);
          results[j] = std::move(r);
          ++finished;
          if (opts.progress) opts.progress("solve", 0.3 + 0.7 * double(finished) / m);
        } catch (const std::exception& e) {
          std::lock_guard<std::mutex> lock(mu);
          errors.push_back(e.what());
        }
      }
    };
    const int nthreads = std::max(1, std::min(opts.threads, m));
    std::vector<std::thread> pool;
    for (int t = 1; t < nthreads; ++t) pool.emplace_back(worker);
    worker();
    for (auto& th : pool) th.join();
    if (!errors.empty()) throw Error(errors.front() == "cancelled" ? "cancelled" : "bind: " + errors.front());
    stats.converged = true;
    for (int j = 0; j < m; ++j) {
      X.col(j) = results[j].x;
      stats.iterations_total += results[j].iterations;
      stats.iterations_max = std::max(stats.iterations_max, results[j].iterations);
      stats.fallback_iterations += results[j].fallback_iterations;
      stats.kkt_residual = std::max(stats.kkt_residual, results[j].kkt_residual);
      stats.converged = stats.converged && results[j].converged;
    }
  }
  stats.solve_seconds = seconds_since(t0);
  if (!stats.converged)
    throw Error("bind: the weight solver did not converge (relative KKT residual " +
                std::to_string(stats.kkt_residual) + ")");

  Eigen::MatrixXd W(n, m);
  for (int k = 0; k < nf; ++k) W.row(f(perm[k])) = X.row(k);
  for (int k = 0; k < b.size(); ++k) W.row(b(k)) = bc.row(k);
  if (!opts.exact_partition_of_unity && opts.normalize_rows) {
    // Default mode: normalize rows. A row of all zeros (every handle's weight hit the bound there) takes
    // the clipped starting point instead (the bound-free solution, which sums to 1 before clipping, or
    // the coarse level's weights).
    for (int k = 0; k < nf; ++k) {
      const int i = f(perm[k]);
      double s = W.row(i).sum();
      if (s <= 1e-12) {
        W.row(i) = x_start.row(k).cwiseMax(0.0).cwiseMin(1.0);
        s = W.row(i).sum();
        ++stats.rows_renormalized_from_zero;
        if (s <= 1e-12) W.row(i).setConstant(1.0 / m), s = 1.0;
      }
      W.row(i) /= s;
    }
  }
  if (stats_out) *stats_out = stats;
  progress("done", 1.0);
  return W;
}

}  // namespace dfm
