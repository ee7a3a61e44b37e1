#include "app/editor/frame_pacing.h"

#include <algorithm>
#include <numeric>

namespace dfm::editor {

double FramePacer::next(const LoopActivity& a, double now) {
  if (a.input) settle_left_ = std::max(settle_left_, 1 + opts_.settle_frames);
  if (job_was_running_ && !a.job_running) settle_left_ = std::max(settle_left_, 1 + opts_.settle_frames);
  job_was_running_ = a.job_running;
  progress_pending_ =
      a.job_running && (progress_pending_ || a.job_progress || now - last_frame_ >= opts_.job_heartbeat_s);
  const bool interactive = settle_left_ > 0 || a.playing;
  // Nothing to draw: sleep; a running job's progress is polled at job_hz (it sends no events).
  if (!interactive && !progress_pending_)
    return a.job_running ? std::min(1.0 / opts_.job_hz, opts_.idle_wait_s) : opts_.idle_wait_s;
  if (!a.job_running) return 0.0;
  // A job runs: input and playback keep to job_hz, progress alone to progress_hz.
  const double wait = last_frame_ + 1.0 / (interactive ? opts_.job_hz : opts_.progress_hz) - now;
  return wait > 0 ? std::min(wait, 1.0 / opts_.job_hz) : 0.0;
}

void FramePacer::drew(double frame_start) {
  last_frame_ = frame_start;
  if (settle_left_ > 0) --settle_left_;
  progress_pending_ = false;
}

void FrameStats::begin(double now) {
  start_ = now;
  open_ = true;
}

void FrameStats::end(double now) {
  if (!open_) return;
  open_ = false;
  cost_.push_back(1000.0 * (now - start_));
  while (static_cast<int>(cost_.size()) > window_) cost_.pop_front();
  ++frames_;
}

double FrameStats::ms() const {
  return cost_.empty() ? 0.0 : std::accumulate(cost_.begin(), cost_.end(), 0.0) / cost_.size();
}

double FrameStats::fps() const {
  const double m = ms();
  return m > 0 ? 1000.0 / m : 0.0;
}

}  // namespace dfm::editor
