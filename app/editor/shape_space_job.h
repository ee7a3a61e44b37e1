#pragma once
// The Shape space panel's ARAP synthesis (Alexa 2002, 5.5.1) off the UI thread: the product's rule is
// no UI frame over 100 ms, and an ARAP shape takes seconds (TetGen and factorizations per base, built
// once, then about a second a shape on the teddy). The UI thread posts requests; one worker thread runs
// them one at a time. Only the newest request is wanted: posting replaces a request still waiting,
// and a running request that is no longer wanted (superseded or cancelled) runs to its end (core's
// synthesis has no cancel hook) but its result is dropped, never handed out. What it built into the
// shape space's cache (core's ShapeSpace keeps each base's ArapSource) serves the next request.
//
// Thread safety: a request is a closure over copies (a shared ShapeSpace built from copies of the
// keys' vertices and faces, the weights): the worker never reads the Document. The worker is the only
// thread that runs the closures, so a ShapeSpace's cache is filled by one thread at a time.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <Eigen/Core>

namespace dfm::editor {

class ShapeSpaceJob {
 public:
  // Runs on the worker thread; returns the synthesized vertices (throws dfm::Error on failure).
  using Synthesize = std::function<Eigen::MatrixXd()>;
  struct Result {
    std::uint64_t id = 0;     // post()'s id
    Eigen::MatrixXd V;        // empty on error
    std::string error;        // the exception's message
    double seconds = 0;       // the closure's run time on the worker
  };

  ShapeSpaceJob();
  ~ShapeSpaceJob();  // cancels, then waits for a running request to end
  ShapeSpaceJob(const ShapeSpaceJob&) = delete;
  ShapeSpaceJob& operator=(const ShapeSpaceJob&) = delete;

  // Makes f the wanted request (any earlier one is superseded); returns its id (1, 2, ...).
  std::uint64_t post(Synthesize f);
  // Nothing is wanted: a waiting request never runs, a running one's result is dropped.
  void cancel();
  // The wanted request's id, 0 when none is wanted or its result was taken.
  std::uint64_t wanted() const;
  // A wanted request has not been taken yet (waiting, running, or its result ready).
  bool waiting() const { return wanted() != 0; }
  // The worker is running a request (maybe one no longer wanted).
  bool running() const { return running_.load(); }
  // The wanted request's result, once it is ready; then nothing is wanted until the next post().
  std::optional<Result> take();
  // Seconds since the wanted request was posted (0 when none is).
  double elapsed_seconds() const;
  // Blocks until the worker has nothing to do (no request waiting, none running) or timeout_s passes;
  // true when idle. For tests; the editor draws frames instead (Editor::wait_for_shape_space).
  bool wait_idle(double timeout_s) const;

 private:
  void loop();

  mutable std::mutex mutex_;
  mutable std::condition_variable cv_;  // a request was posted, the job is ending, or the worker went idle
  std::uint64_t next_id_ = 1;
  std::uint64_t wanted_ = 0;              // 0: none
  std::optional<std::uint64_t> queued_;   // the request waiting to run (its id)
  Synthesize queued_fn_;
  std::optional<Result> ready_;           // the wanted request's result
  std::chrono::steady_clock::time_point posted_;
  bool stop_ = false;
  std::atomic<bool> running_{false};
  std::thread thread_;  // last: starts after the members above exist
};

}  // namespace dfm::editor
