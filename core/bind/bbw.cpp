#include "core/bind/bbw.h"

#include <malloc.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <functional>
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

Eigen::MatrixXd solve_weights(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, const Eigen::VectorXi& b,
                              const Eigen::MatrixXd& bc, const BbwOptions& opts, BbwStats* stats_out) {
  validate(V, b, bc);
  single_threaded_numerics();  // we run one QP per thread; see numeric_threads.h
  install_cholmod_block_cache();
  const CholmodBlockCacheScope release_cache;
  BbwStats stats;
  auto progress = [&](const char* stage, double f) {
    if (opts.qp.cancel && opts.qp.cancel->load()) throw Error("cancelled");
    if (opts.progress) opts.progress(stage, f);
  };
  const int n = static_cast<int>(V.rows()), m = static_cast<int>(bc.cols());

  // ---- on large meshes, a coarse level of the same domain (coarse_level.h), built and solved on a
  // thread of its own while this one assembles and orders Q: its weights, carried to this mesh, start
  // the bounded solves. Each handle's coarse weights are handed over as soon as they are solved, so this
  // thread starts on the fine solves right after its ordering instead of waiting for the last coarse
  // handle; the coarse thread joins the fine solves when it is done. Only an accelerator: handles it has
  // no weights for (it could not be built, failed, or was stopped) start from the bound-free solution.
  const bool multilevel =
      !opts.exact_partition_of_unity && opts.multilevel_min_vertices > 0 && n >= opts.multilevel_min_vertices;
  struct Shared {
    std::mutex mu;
    std::condition_variable cv;
    // Coarse level (written by the coarse thread; P before the first handle is handed over).
    CoarseLevel level;
    Eigen::MatrixXd Wc;                // coarse weights, a column per handle as it is solved
    std::vector<int> coarse_solved;    // handles in the order their coarse weights arrived
    bool coarse_done = false;          // the coarse thread will hand over nothing more
    double coarse_seconds = 0;
    std::atomic<bool> coarse_stop{false};
    // Fine solves.
    bool fine_ready = false;           // Q_ff, G, ordering in place: the coarse thread may join
    bool abandon = false;              // an error or cancel: every thread leaves
    std::vector<char> taken;
    bool x0_ready = false, x0_busy = false;
    std::vector<std::string> errors;
    int finished = 0;
  } sh;
  sh.taken.assign(m, 0);
  std::thread coarse_thread;
  struct Joiner {  // stops and joins on every path out of here, exceptions (cancel) included
    std::thread& t;
    Shared& sh;
    ~Joiner() {
      {
        std::lock_guard<std::mutex> lock(sh.mu);
        sh.abandon = true;
        sh.coarse_stop = true;
      }
      sh.cv.notify_all();
      if (t.joinable()) t.join();
    }
  } join_coarse{coarse_thread, sh};
  std::function<void(bool)> fine_worker;  // set once the fine solves can start (below)

  if (multilevel) {
    coarse_thread = std::thread([&] {
      const auto tc = std::chrono::steady_clock::now();
      try {
        single_threaded_numerics();
        const CholmodBlockCacheScope release;
        CoarseLevel level;
        if (build_coarse_level(V, T, b, bc, level, opts.multilevel_min_vertices)) {
          {
            std::lock_guard<std::mutex> lock(sh.mu);
            sh.level = std::move(level);
            sh.Wc = Eigen::MatrixXd::Zero(sh.level.V.rows(), m);
          }
          BbwOptions co;
          co.normalize_rows = false;
          co.qp.tolerance = std::max(opts.qp.tolerance, 1e-5);  // a start, not the answer
          co.threads = 1;                                 // the other core assembles and orders meanwhile
          co.qp.cancel = &sh.coarse_stop;
          co.multilevel_min_vertices = 0;
          co.handle_solved = [&](int j, const Eigen::VectorXd& w) {
            {
              std::lock_guard<std::mutex> lock(sh.mu);
              sh.Wc.col(j) = w;
              sh.coarse_solved.push_back(j);
            }
            sh.cv.notify_all();
          };
          bbw_weights(sh.level.V, sh.level.T, sh.level.b, sh.level.bc, co);
        }
      } catch (const std::exception&) {
        // Stopped, or failed: the handles without coarse weights start from the bound-free solution.
      }
      {
        std::lock_guard<std::mutex> lock(sh.mu);
        sh.coarse_done = true;
        sh.coarse_seconds = seconds_since(tc);
      }
      sh.cv.notify_all();
      malloc_trim(0);  // the coarse solve's memory, back to the system before the fine solves peak
      // Then one of the fine solvers.
      std::unique_lock<std::mutex> lock(sh.mu);
      sh.cv.wait(lock, [&] { return sh.fine_ready || sh.abandon; });
      if (sh.abandon || opts.threads < 2) return;
      lock.unlock();
      fine_worker(/*smallest_first=*/true);
    });
  }

  // ---- assembly
  progress("assembly", 0.0);
  auto t0 = std::chrono::steady_clock::now();
  // Both cores, unless the coarse level's thread has the other one.
  Eigen::SparseMatrix<double> Q = bbw_energy_matrix(V, T, opts.shape_mask, multilevel ? 1 : opts.threads);
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
  Q = Eigen::SparseMatrix<double>();  // only Q_ff from here on: less at the bind's peak
  stats.assembly_seconds = seconds_since(t0);

  // ---- a fill-reducing ordering of Q_ff, restricted to every face of every handle; without a coarse
  // level also one factorization shared by every handle: the bound-free biharmonic solutions start the
  // bounded solves (often nearly feasible).
  progress("factorization", 0.1);
  t0 = std::chrono::steady_clock::now();
  Eigen::MatrixXd X0;
  std::vector<int> perm;
  // From here on the free variables are renumbered in the factorization's (nested-dissection) order:
  // a vertex's neighbours then sit close to it in memory, which makes the Gauss-Seidel sweeps and
  // products with Q_ff (most of the bounded solve's time outside the factorizations) 2x faster than in
  // TetGen's order, and every face is already in elimination order.
  Eigen::SparseMatrix<double> Q_renumbered;
  {
    SpdSolver chol;
    chol.analyze(Qff);
    stats.factor_nonzeros = chol.factor_nonzeros();
    perm = chol.permutation();
    progress("factorization", 0.2);
    const Eigen::VectorXi p = Eigen::Map<const Eigen::VectorXi>(perm.data(), nf);
    if (!multilevel && opts.threads > 1) {
      // The renumbered copy is made on the idle core while this one factorizes.
      std::exception_ptr failed;
      std::thread renumber([&] {
        try {
          Q_renumbered = principal_submatrix(Qff, p);
        } catch (...) {
          failed = std::current_exception();
        }
      });
      try {
        chol.factorize(Qff);
        X0 = chol.solve(-G);
      } catch (...) {
        renumber.join();
        throw;
      }
      renumber.join();
      if (failed) std::rethrow_exception(failed);
    } else {
      if (!multilevel) {
        chol.factorize(Qff);
        X0 = chol.solve(-G);
      }
      Q_renumbered = principal_submatrix(Qff, p);
    }
  }
  release_cholmod_block_cache();  // the whole-matrix factor's blocks: faces are smaller
  Qff = std::move(Q_renumbered);
  {
    Eigen::MatrixXd tmp(nf, m);
    for (int k = 0; k < nf; ++k) tmp.row(k) = G.row(perm[k]);
    G.swap(tmp);
    if (X0.size()) {
      for (int k = 0; k < nf; ++k) tmp.row(k) = X0.row(perm[k]);
      X0.swap(tmp);
    }
  }
  // The ordering's workspace and the matrix before renumbering are free again, but the C library keeps
  // them mapped: on large meshes, hand them back before the face solves reach the bind's peak. Small
  // meshes reuse them (trimming would cost more in page faults than it saves).
  if (multilevel) malloc_trim(0);
  stats.factorization_seconds = seconds_since(t0);

  // ---- bounded solves
  progress("solve", 0.3);
  t0 = std::chrono::steady_clock::now();
  Eigen::MatrixXd X(nf, m), start(nf, m);  // start: each handle's starting point (row fallback below)
  if (opts.exact_partition_of_unity) {
    ExactPouResult r = solve_exact_pou(Qff, G, X0, opts.qp.tolerance, opts.qp.cancel);
    X = r.X;
    start = X0;
    stats.iterations_total = stats.iterations_max = r.iterations;
    stats.fallback_iterations = r.fallback_iterations;
    stats.kkt_residual = r.kkt_residual;
    stats.converged = r.converged;
  } else {
    const Eigen::VectorXd lo = Eigen::VectorXd::Zero(nf), hi = Eigen::VectorXd::Ones(nf);
    std::vector<BoxQPResult> results(m);
    std::vector<char> from_coarse(m, 0);
    // Handles started from the bound-free solution go largest first (by its positive support; a face costs
    // ~its size squared), so the last to finish are small ones and neither thread idles long at the end.
    // Coarse-started ones go in the order the coarse level solved them, itself largest first.
    std::vector<int> x0_order;
    auto order_by_support = [&] {
      std::vector<long> support(m, 0);
      x0_order.resize(m);
      for (int j = 0; j < m; ++j) {
        x0_order[j] = j;
        for (int k = 0; k < nf; ++k) support[j] += X0(k, j) > 0.0;
      }
      std::stable_sort(x0_order.begin(), x0_order.end(), [&](int a, int c) { return support[a] > support[c]; });
    };
    if (X0.size()) {
      order_by_support();
      sh.x0_ready = true;
    }
    // A coarse level that has not handed over a handle for this long while this thread had nothing else
    // to do is stopped (a badly shaped coarse mesh can make its QPs slow): the remaining handles then
    // start from the bound-free solution, which costs one numeric factorization.
    const double patience = opts.multilevel_patience_seconds >= 0
                                ? opts.multilevel_patience_seconds
                                : std::max(2.0, 2 * (stats.assembly_seconds + stats.factorization_seconds));
    const std::thread::id main_thread = std::this_thread::get_id();
    BoxQPOptions qo = opts.qp;
    qo.in_elimination_order = true;  // every face is read off Q_ff's lower part, shared by both threads
    auto cancelled = [&] { return opts.qp.cancel && opts.qp.cancel->load(); };
    // The next handle to solve and its start (false: none left, or give up). Called with the lock held.
    auto next_handle = [&](std::unique_lock<std::mutex>& lock, int& j, bool& coarse_start, bool smallest_first) {
      auto first_untaken = [&](const std::vector<int>& order) {
        if (smallest_first) {
          for (auto it = order.rbegin(); it != order.rend(); ++it)
            if (!sh.taken[*it]) return *it;
        } else {
          for (int c : order)
            if (!sh.taken[c]) return c;
        }
        return -1;
      };
      double idle = 0;
      for (;;) {
        if (sh.abandon || !sh.errors.empty()) return false;
        if (cancelled()) {
          sh.errors.push_back("cancelled");
          sh.cv.notify_all();
          return false;
        }
        if ((j = first_untaken(sh.coarse_solved)) >= 0) return coarse_start = true, true;
        if (std::find(sh.taken.begin(), sh.taken.end(), 0) == sh.taken.end()) return false;
        if (sh.x0_ready) {
          if ((j = first_untaken(x0_order)) >= 0) return coarse_start = false, true;
        }
        if (sh.coarse_done && !sh.x0_busy) {
          // The coarse level has no more to give: the bound-free start for the remaining handles. Q_ff is
          // in elimination order already.
          sh.x0_busy = true;
          lock.unlock();
          try {
            SpdSolver chol;
            chol.analyze(Qff, /*in_elimination_order=*/true);
            chol.factorize(Qff);
            X0 = chol.solve(-G);
            order_by_support();
          } catch (const std::exception& e) {
            lock.lock();
            sh.errors.push_back(e.what());
            sh.cv.notify_all();
            return false;
          }
          lock.lock();
          sh.x0_ready = true;
          sh.cv.notify_all();
          continue;
        }
        const auto tw = std::chrono::steady_clock::now();
        sh.cv.wait_for(lock, std::chrono::milliseconds(10));
        if (std::this_thread::get_id() == main_thread && !sh.coarse_done) {
          idle += seconds_since(tw);
          if (idle >= patience) sh.coarse_stop = true;
        }
      }
    };
    // smallest_first: the coarse level's thread, when it joins, takes the remaining handles from the small
    // end, the first thread from the large end, so the largest faces of the two threads do not coincide
    // (on large meshes the peak memory is two faces at once).
    fine_worker = [&](bool smallest_first) {
      try {
        single_threaded_numerics();
        const CholmodBlockCacheScope release_cache;
        Eigen::VectorXd x_start(nf), w;
        for (;;) {
          int j = -1;
          bool coarse_start = false;
          {
            std::unique_lock<std::mutex> lock(sh.mu);
            if (!next_handle(lock, j, coarse_start, smallest_first)) return;
            sh.taken[j] = 1;
          }
          try {
            if (coarse_start) {
              // The coarse weights carried to this mesh. Values under 1e-4 are within the coarse solve's
              // accuracy; starting them at the bound keeps the first faces (and the bind's peak memory)
              // smaller at no extra faces.
              w = sh.level.P * sh.Wc.col(j);
              for (int k = 0; k < nf; ++k) {
                const double v = std::min(std::max(w(f(perm[k])), 0.0), 1.0);
                x_start(k) = v < 1e-4 ? 0.0 : v;
              }
            } else {
              x_start = X0.col(j);
            }
            start.col(j) = x_start;
            // On large meshes the peak is two threads' faces at once on top of everything else: what the
            // last handle freed goes back to the system first (a few ms a handle and some refaults).
            if (multilevel) malloc_trim(0);
            BoxQPResult r = solve_box_qp(Qff, G.col(j), lo, hi, x_start, qo);
            std::lock_guard<std::mutex> lock(sh.mu);
            if (opts.handle_solved) {
              Eigen::VectorXd full(n);
              for (int k = 0; k < nf; ++k) full(f(perm[k])) = r.x(k);
              for (int k = 0; k < b.size(); ++k) full(b(k)) = bc(k, j);
              opts.handle_solved(j, full);
            }
            results[j] = std::move(r);
            from_coarse[j] = coarse_start;
            ++sh.finished;
            if (opts.progress) opts.progress("solve", 0.3 + 0.7 * double(sh.finished) / m);
          } catch (const std::exception& e) {
            std::lock_guard<std::mutex> lock(sh.mu);
            sh.errors.push_back(e.what());
            sh.cv.notify_all();
          }
        }
      } catch (const std::exception& e) {  // outside a handle's solve (memory): leave, reported below
        std::lock_guard<std::mutex> lock(sh.mu);
        sh.errors.push_back(e.what());
        sh.cv.notify_all();
      }
    };
    std::vector<std::thread> pool;
    // With a coarse level, its thread is the second solver once it is done; else a thread of our own.
    if (!multilevel)
      for (int t = 1; t < std::min(opts.threads, m); ++t) pool.emplace_back(fine_worker, false);
    {
      std::lock_guard<std::mutex> lock(sh.mu);
      sh.fine_ready = true;
    }
    sh.cv.notify_all();
    fine_worker(false);
    for (auto& th : pool) th.join();
    if (coarse_thread.joinable()) {
      {
        std::lock_guard<std::mutex> lock(sh.mu);
        if (!sh.errors.empty()) sh.abandon = true;
        sh.coarse_stop = true;  // it has nothing left to start: every handle is taken
      }
      sh.cv.notify_all();
      coarse_thread.join();
    }
    stats.multilevel_seconds = sh.coarse_seconds;
    if (!sh.errors.empty()) {
      const bool was_cancelled = std::find(sh.errors.begin(), sh.errors.end(), "cancelled") != sh.errors.end();
      throw Error(was_cancelled ? "cancelled" : "bind: " + sh.errors.front());
    }
    stats.converged = true;
    for (int j = 0; j < m; ++j) {
      X.col(j) = results[j].x;
      stats.iterations_total += results[j].iterations;
      stats.iterations_max = std::max(stats.iterations_max, results[j].iterations);
      stats.fallback_iterations += results[j].fallback_iterations;
      stats.kkt_residual = std::max(stats.kkt_residual, results[j].kkt_residual);
      stats.converged = stats.converged && results[j].converged;
      stats.multilevel_handles += from_coarse[j];
    }
    stats.multilevel = stats.multilevel_handles > 0;
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
        W.row(i) = start.row(k).cwiseMax(0.0).cwiseMin(1.0);
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

}  // namespace
}  // namespace dfm
