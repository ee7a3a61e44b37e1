#include "core/bind/bbw_schedule.h"

#include <algorithm>
#include <chrono>
#include <exception>

#include "core/bind/cholesky.h"
#include "core/bind/cholmod_memory.h"
#include "core/util/error.h"

namespace dfm {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

BoundedSolves::BoundedSolves(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, const Eigen::VectorXi& b,
                             const Eigen::MatrixXd& bc, const BbwOptions& opts, bool multilevel)
    : V_(V), T_(T), b_(b), bc_(bc), opts_(opts), multilevel_(multilevel), m_(static_cast<int>(bc.cols())) {
  taken_.assign(m_, 0);
  results_.resize(m_);
  from_coarse_.assign(m_, 0);
  if (multilevel_) coarse_thread_ = std::thread([this] { coarse_main(); });
}

BoundedSolves::~BoundedSolves() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    abandon_ = true;
    coarse_stop_ = true;
  }
  cv_.notify_all();
  if (coarse_thread_.joinable()) coarse_thread_.join();
}

void BoundedSolves::coarse_main() {
  const auto tc = std::chrono::steady_clock::now();
  try {
    const CholmodBlockCacheScope release;
    CoarseLevel level;
    if (build_coarse_level(V_, T_, b_, bc_, level, opts_.multilevel_min_vertices)) {
      {
        std::lock_guard<std::mutex> lock(mu_);
        level_ = std::move(level);
        Wc_ = Eigen::MatrixXd::Zero(level_.V.rows(), m_);
      }
      BbwOptions co;
      co.normalize_rows = false;
      co.qp.tolerance = std::max(opts_.qp.tolerance, 1e-5);  // a start, not the answer
      co.threads = 1;                                         // the other core assembles and orders meanwhile
      co.qp.cancel = &coarse_stop_;
      co.multilevel_min_vertices = 0;
      co.handle_solved = [&](int j, const Eigen::VectorXd& w) {
        {
          std::lock_guard<std::mutex> lock(mu_);
          Wc_.col(j) = w;
          coarse_solved_.push_back(j);
        }
        cv_.notify_all();
      };
      bbw_weights(level_.V, level_.T, level_.b, level_.bc, co);
    }
  } catch (const std::exception&) {
    // Stopped, or failed: the handles without coarse weights start from the bound-free solution.
  }
  {
    std::lock_guard<std::mutex> lock(mu_);
    coarse_done_ = true;
    coarse_seconds_ = seconds_since(tc);
  }
  cv_.notify_all();
  trim_heap();  // the coarse solve's memory, back to the system before the fine solves peak
  // Then one of the fine solvers.
  std::unique_lock<std::mutex> lock(mu_);
  cv_.wait(lock, [&] { return fine_ready_ || abandon_; });
  if (abandon_ || opts_.threads < 2) return;
  lock.unlock();
  solver_main(/*smallest_first=*/true);
}

// Handles started from the bound-free solution go largest first (by its positive support; a face costs
// ~its size squared), so the last to finish are small ones and neither thread idles long at the end.
// Coarse-started ones go in the order the coarse level solved them, itself largest first.
void BoundedSolves::order_by_support() {
  std::vector<long> support(m_, 0);
  x0_order_.resize(m_);
  for (int j = 0; j < m_; ++j) {
    x0_order_[j] = j;
    for (int k = 0; k < X0_.rows(); ++k) support[j] += X0_(k, j) > 0.0;
  }
  std::stable_sort(x0_order_.begin(), x0_order_.end(), [&](int a, int c) { return support[a] > support[c]; });
}

// Records a thread's error (a cancellation by its type) and wakes the others. Called with the lock held.
void BoundedSolves::fail(const std::exception& e) {
  if (dynamic_cast<const Cancelled*>(&e)) cancelled_ = true;
  errors_.push_back(e.what());
  cv_.notify_all();
}

// The next handle to solve and its start (false: none left, or give up). Called with the lock held.
bool BoundedSolves::next_handle(std::unique_lock<std::mutex>& lock, int& j, bool& coarse_start, bool smallest_first) {
  auto first_untaken = [&](const std::vector<int>& order) {
    if (smallest_first) {
      for (auto it = order.rbegin(); it != order.rend(); ++it)
        if (!taken_[*it]) return *it;
    } else {
      for (int c : order)
        if (!taken_[c]) return c;
    }
    return -1;
  };
  double idle = 0;
  for (;;) {
    if (abandon_ || !errors_.empty()) return false;
    if (cancelled()) {
      fail(Cancelled());
      return false;
    }
    if ((j = first_untaken(coarse_solved_)) >= 0) return coarse_start = true, true;
    if (std::find(taken_.begin(), taken_.end(), 0) == taken_.end()) return false;
    if (x0_ready_ && (j = first_untaken(x0_order_)) >= 0) return coarse_start = false, true;
    if (coarse_done_ && !x0_busy_) {
      // The coarse level has no more to give: the bound-free start for the remaining handles (one
      // numeric factorization). Q_ff is in elimination order already.
      x0_busy_ = true;
      lock.unlock();
      try {
        SpdSolver chol;
        chol.analyze(sys_->Qff, /*in_elimination_order=*/true);
        chol.factorize(sys_->Qff);
        X0_ = chol.solve(-sys_->G);
        order_by_support();
      } catch (const std::exception& e) {
        lock.lock();
        fail(e);
        return false;
      }
      lock.lock();
      x0_ready_ = true;
      cv_.notify_all();
      continue;
    }
    // A coarse level that has not handed over a handle for `patience` while the first thread had nothing
    // else to do is stopped (a badly shaped coarse mesh can make its QPs slow).
    const auto tw = std::chrono::steady_clock::now();
    cv_.wait_for(lock, std::chrono::milliseconds(10));
    if (std::this_thread::get_id() == run_thread_ && !coarse_done_) {
      idle += seconds_since(tw);
      if (idle >= patience_) coarse_stop_ = true;
    }
  }
}

// The coarse weights carried to this mesh. Values under 1e-4 are within the coarse solve's accuracy;
// starting them at the bound keeps the first faces (and the bind's peak memory) smaller at no extra faces.
Eigen::VectorXd BoundedSolves::coarse_start(int j) const {
  const Eigen::VectorXd w = level_.P * Wc_.col(j);
  Eigen::VectorXd x(sys_->vertex.size());
  for (int k = 0; k < x.size(); ++k) {
    const double v = std::min(std::max(w(sys_->vertex(k)), 0.0), 1.0);
    x(k) = v < 1e-4 ? 0.0 : v;
  }
  return x;
}

void BoundedSolves::solve_one(int j, bool coarse, Eigen::VectorXd& x_start) {
  if (coarse) x_start = coarse_start(j);
  else x_start = X0_.col(j);
  start_.col(j) = x_start;
  // On large meshes the peak is two threads' faces at once on top of everything else: what the last
  // handle freed goes back to the system first (a few ms a handle and some refaults).
  if (multilevel_) trim_heap();
  const int nf = static_cast<int>(x_start.size());
  BoxQPResult r = solve_box_qp(sys_->Qff, sys_->G.col(j), lo_, hi_, x_start, qp_);
  std::lock_guard<std::mutex> lock(mu_);
  if (opts_.handle_solved) {
    Eigen::VectorXd full(V_.rows());
    for (int k = 0; k < nf; ++k) full(sys_->vertex(k)) = r.x(k);
    for (int k = 0; k < b_.size(); ++k) full(b_(k)) = bc_(k, j);
    opts_.handle_solved(j, full);
  }
  results_[j] = std::move(r);
  from_coarse_[j] = coarse;
  ++finished_;
  if (opts_.progress) opts_.progress("solve", 0.3 + 0.7 * double(finished_) / m_);
}

// smallest_first: the coarse level's thread, when it joins, takes the remaining handles from the small
// end, the first thread from the large end, so the largest faces of the two threads do not coincide
// (on large meshes the peak memory is two faces at once).
void BoundedSolves::solver_main(bool smallest_first) {
  try {
    const CholmodBlockCacheScope release_cache;
    Eigen::VectorXd x_start;
    for (;;) {
      int j = -1;
      bool coarse = false;
      {
        std::unique_lock<std::mutex> lock(mu_);
        if (!next_handle(lock, j, coarse, smallest_first)) return;
        taken_[j] = 1;
      }
      try {
        solve_one(j, coarse, x_start);
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(mu_);
        fail(e);
      }
    }
  } catch (const std::exception& e) {  // outside a handle's solve (memory): leave, reported by run()
    std::lock_guard<std::mutex> lock(mu_);
    fail(e);
  }
}

Eigen::MatrixXd BoundedSolves::run(const FreeSystem& sys, Eigen::MatrixXd X0, Eigen::MatrixXd& start, BbwStats& stats) {
  const int nf = static_cast<int>(sys.Qff.rows());
  {
    std::lock_guard<std::mutex> lock(mu_);
    sys_ = &sys;
    X0_ = std::move(X0);
    start_.resize(nf, m_);
    lo_ = Eigen::VectorXd::Zero(nf);
    hi_ = Eigen::VectorXd::Ones(nf);
    if (X0_.size()) {
      order_by_support();
      x0_ready_ = true;
    }
    patience_ = opts_.multilevel_patience_seconds >= 0
                    ? opts_.multilevel_patience_seconds
                    : std::max(2.0, 2 * (stats.assembly_seconds + stats.factorization_seconds));
    run_thread_ = std::this_thread::get_id();
    qp_ = opts_.qp;
    qp_.in_elimination_order = true;  // every face is read off Q_ff's lower part, shared by both threads
  }
  std::vector<std::thread> pool;
  // With a coarse level, its thread is the second solver once it is done; else a thread of our own.
  if (!multilevel_)
    for (int t = 1; t < std::min(opts_.threads, m_); ++t) pool.emplace_back([this] { solver_main(false); });
  {
    std::lock_guard<std::mutex> lock(mu_);
    fine_ready_ = true;
  }
  cv_.notify_all();
  solver_main(false);
  for (auto& th : pool) th.join();
  if (coarse_thread_.joinable()) {
    {
      std::lock_guard<std::mutex> lock(mu_);
      if (!errors_.empty()) abandon_ = true;
      coarse_stop_ = true;  // it has nothing left to start: every handle is taken
    }
    cv_.notify_all();
    coarse_thread_.join();
  }
  stats.multilevel_seconds = coarse_seconds_;
  if (!errors_.empty()) {
    if (cancelled_) throw Cancelled();
    throw Error("bind: " + errors_.front());
  }
  Eigen::MatrixXd X(nf, m_);
  stats.converged = true;
  for (int j = 0; j < m_; ++j) {
    X.col(j) = results_[j].x;
    stats.iterations_total += results_[j].iterations;
    stats.iterations_max = std::max(stats.iterations_max, results_[j].iterations);
    stats.fallback_iterations += results_[j].fallback_iterations;
    stats.kkt_residual = std::max(stats.kkt_residual, results_[j].kkt_residual);
    stats.converged = stats.converged && results_[j].converged;
    stats.multilevel_handles += from_coarse_[j];
  }
  stats.multilevel = stats.multilevel_handles > 0;
  start = std::move(start_);
  return X;
}

}  // namespace dfm
