#pragma once
// The bounded weight solves, one box QP per handle, scheduled over the solver threads.
//
// On large meshes a coarse level of the same domain (coarse_level.h) is built and solved on a thread of
// its own, from construction on, while the calling thread assembles and orders Q: its weights, carried
// to the fine mesh, start the bounded solves. Each handle's coarse weights are handed over as soon as
// they are solved, so the fine solves begin right after the ordering instead of after the last coarse
// handle; the coarse thread joins the fine solves when it is done. It is only an accelerator: handles it
// has no weights for (it could not be built, failed, or was too slow) start from the bound-free solution.
#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <Eigen/Core>

#include "core/bind/bbw.h"
#include "core/bind/bbw_system.h"
#include "core/bind/coarse_level.h"
#include "core/bind/qp.h"

namespace dfm {

class BoundedSolves {
 public:
  // V, T, b, bc and opts must outlive this object. multilevel: start the coarse level's thread now.
  BoundedSolves(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, const Eigen::VectorXi& b,
                const Eigen::MatrixXd& bc, const BbwOptions& opts, bool multilevel);
  ~BoundedSolves();  // stops and joins the coarse thread on every path (errors and cancel included)
  BoundedSolves(const BoundedSolves&) = delete;
  BoundedSolves& operator=(const BoundedSolves&) = delete;

  // Solves 0 <= x_j <= 1 for every handle on sys (renumbered by order_free_system). X0: the bound-free
  // solutions, or empty when a coarse level runs (computed here if it ends before every handle started).
  // Returns #free x #handles; start: each handle's starting point. Fills stats' solve fields; throws
  // dfm::Cancelled or the first solve's error.
  Eigen::MatrixXd run(const FreeSystem& sys, Eigen::MatrixXd X0, Eigen::MatrixXd& start, BbwStats& stats);

 private:
  void coarse_main();
  void solver_main(bool smallest_first);
  bool next_handle(std::unique_lock<std::mutex>& lock, int& j, bool& coarse_start, bool smallest_first);
  void order_by_support();
  Eigen::VectorXd coarse_start(int j) const;
  void solve_one(int j, bool coarse_start, Eigen::VectorXd& x_start);
  bool cancelled() const { return opts_.qp.cancel && opts_.qp.cancel->load(); }

  const Eigen::MatrixXd& V_;
  const Eigen::MatrixXi& T_;
  const Eigen::VectorXi& b_;
  const Eigen::MatrixXd& bc_;
  const BbwOptions& opts_;
  const bool multilevel_;
  const int m_;
  std::thread coarse_thread_;

  std::mutex mu_;
  std::condition_variable cv_;
  // Coarse level (written by the coarse thread; P before the first handle is handed over).
  CoarseLevel level_;
  Eigen::MatrixXd Wc_;               // coarse weights, a column per handle as it is solved
  std::vector<int> coarse_solved_;   // handles in the order their coarse weights arrived
  bool coarse_done_ = false;         // the coarse thread will hand over nothing more
  double coarse_seconds_ = 0;
  std::atomic<bool> coarse_stop_{false};
  // Fine solves (set by run()).
  const FreeSystem* sys_ = nullptr;
  Eigen::MatrixXd X0_, start_;
  std::vector<int> x0_order_;
  BoxQPOptions qp_;
  Eigen::VectorXd lo_, hi_;  // the box 0 <= x <= 1
  double patience_ = 0;
  std::thread::id run_thread_;
  std::vector<BoxQPResult> results_;
  std::vector<char> from_coarse_;
  bool fine_ready_ = false;          // run() has its data in place: the coarse thread may join
  bool abandon_ = false;             // an error or cancel: every thread leaves
  std::vector<char> taken_;
  bool x0_ready_ = false, x0_busy_ = false;
  std::vector<std::string> errors_;
  bool cancelled_ = false;           // one of errors_ is a Cancelled
  void fail(const std::exception& e);
  int finished_ = 0;
};

}  // namespace dfm
