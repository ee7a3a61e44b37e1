#pragma once
// Runs a bind off the UI thread: the window keeps drawing while the job reports its stage and
// progress; Cancel sets a flag the job polls. The result (or the error text) is collected by the UI
// thread, which then stores it in the document as one undo step.
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <Eigen/Core>

#include "core/bind/bind.h"
#include "core/scene/document.h"

namespace dfm::editor {

struct BindProgress {
  std::string stage;
  double fraction = 0;  // 0..1 within the whole bind
};

struct BindOutcome {
  bool ok = false;
  bool cancelled = false;
  std::shared_ptr<const BindResult> result;  // when ok: store with apply_bind_result (UI thread)
  std::string error;  // readable message (names the handle or file)
};

// The work itself: given a progress reporter and the cancel flag, returns weights and stats.
using BindJob = std::function<BindOutcome(const std::function<void(const std::string&, double)>& progress,
                                          const std::atomic<bool>& cancel)>;

class BindWorker {
 public:
  ~BindWorker();
  // Starts the job on a worker thread. Returns false if one is already running.
  bool start(BindJob job);
  bool running() const { return running_.load(); }
  void cancel() { cancel_ = true; }
  bool cancel_requested() const { return cancel_.load(); }
  BindProgress progress() const;
  // The finished job's outcome, once (then empty until the next job finishes).
  std::optional<BindOutcome> take_result();
  double elapsed_seconds() const;

 private:
  void join();
  std::thread thread_;
  std::atomic<bool> running_{false};
  std::atomic<bool> cancel_{false};
  mutable std::mutex mutex_;
  BindProgress progress_;
  std::optional<BindOutcome> result_;
  double started_ = 0;
};

// The bind the editor runs: dfm::bind_surface / bind_tet_mesh with bind_options(doc) (volume settings
// and the painted mask), as the CLI and scripts do. A snapshot of the inputs is taken on the UI
// thread, so the document may change meanwhile (apply_bind_result then refuses a stale result).
BindJob make_document_bind_job(const Document& doc);

}  // namespace dfm::editor
