#include "app/editor/shape_space_job.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <exception>
#include <utility>

namespace dfm::editor {

ShapeSpaceJob::ShapeSpaceJob() : thread_([this] { loop(); }) {}

ShapeSpaceJob::~ShapeSpaceJob() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    wanted_ = 0;
    queued_.reset();
    queued_fn_ = nullptr;
  }
  cv_.notify_all();
  thread_.join();
}

std::uint64_t ShapeSpaceJob::post(Synthesize f) {
  std::uint64_t id = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    id = next_id_++;
    wanted_ = id;
    queued_ = id;  // replaces a request still waiting: it never runs
    queued_fn_ = std::move(f);
    ready_.reset();
    posted_ = std::chrono::steady_clock::now();
  }
  cv_.notify_all();
  return id;
}

void ShapeSpaceJob::cancel() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    wanted_ = 0;
    queued_.reset();
    queued_fn_ = nullptr;
    ready_.reset();
  }
  cv_.notify_all();
}

std::uint64_t ShapeSpaceJob::wanted() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return wanted_;
}

std::optional<ShapeSpaceJob::Result> ShapeSpaceJob::take() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!ready_) return std::nullopt;
  std::optional<Result> r = std::move(ready_);
  ready_.reset();
  wanted_ = 0;
  return r;
}

double ShapeSpaceJob::elapsed_seconds() const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (wanted_ == 0) return 0.0;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - posted_).count();
}

bool ShapeSpaceJob::wait_idle(double timeout_s) const {
  std::unique_lock<std::mutex> lock(mutex_);
  return cv_.wait_for(lock, std::chrono::duration<double>(timeout_s), [this] { return !queued_ && !running_.load(); });
}

void ShapeSpaceJob::loop() {
  // The UI thread must win the CPU (as the bind and manifold workers do): a lower priority for this
  // thread and the TetGen processes it starts (Linux: per thread).
  setpriority(PRIO_PROCESS, static_cast<id_t>(::syscall(SYS_gettid)), 10);
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    cv_.wait(lock, [this] { return stop_ || queued_.has_value(); });
    if (stop_) return;
    Result r;
    r.id = *queued_;
    Synthesize fn = std::move(queued_fn_);
    queued_.reset();
    queued_fn_ = nullptr;
    running_ = true;
    lock.unlock();
    const auto t0 = std::chrono::steady_clock::now();
    try {
      r.V = fn();
    } catch (const std::exception& e) {
      r.V.resize(0, 3);
      r.error = e.what();
    } catch (...) {
      r.V.resize(0, 3);
      r.error = "the synthesis failed (unknown error)";
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    fn = nullptr;  // drops its copy of the space before the UI can see the result
    lock.lock();
    running_ = false;
    if (r.id == wanted_) ready_ = std::move(r);  // else superseded or cancelled: dropped
    cv_.notify_all();
  }
}

}  // namespace dfm::editor
