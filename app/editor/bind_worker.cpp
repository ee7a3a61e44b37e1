#include "app/editor/bind_worker.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <chrono>

#include "core/util/error.h"

namespace dfm::editor {
namespace {
double now_seconds() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}
}  // namespace

BindWorker::~BindWorker() {
  cancel_ = true;
  join();
}

void BindWorker::join() {
  if (thread_.joinable()) thread_.join();
}

bool BindWorker::start(BindJob job) {
  if (running_) return false;
  join();
  cancel_ = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    progress_ = {"starting", 0.0};
    result_.reset();
  }
  started_ = now_seconds();
  running_ = true;
  thread_ = std::thread([this, job = std::move(job)] {
    // The UI thread must win the CPU while a bind runs (no frame over 100 ms): this thread, the
    // solver threads it starts and the TetGen process inherit a lower priority (Linux: per thread).
    setpriority(PRIO_PROCESS, static_cast<id_t>(::syscall(SYS_gettid)), 10);
    BindOutcome out;
    try {
      out = job(
          [this](const std::string& stage, double f) {
            std::lock_guard<std::mutex> lock(mutex_);
            progress_ = {stage, f};
          },
          cancel_);
    } catch (const std::exception& e) {
      out = BindOutcome{};
      out.cancelled = cancel_.load();
      out.error = cancel_.load() ? "bind cancelled" : e.what();
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      result_ = std::move(out);
    }
    running_ = false;
  });
  return true;
}

BindProgress BindWorker::progress() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return progress_;
}

std::optional<BindOutcome> BindWorker::take_result() {
  if (running_) return std::nullopt;
  std::lock_guard<std::mutex> lock(mutex_);
  std::optional<BindOutcome> r = std::move(result_);
  result_.reset();
  return r;
}

double BindWorker::elapsed_seconds() const { return running_ ? now_seconds() - started_ : 0.0; }

}  // namespace dfm::editor
