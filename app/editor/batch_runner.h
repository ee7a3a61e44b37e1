#pragma once
// The editor's batch runs (scripts, --play-frames lives in editor_batch.cpp beside it): a script's
// bind on the worker with the window drawing as an artist would see it, and the tally of those frames
// (each should stay under 100 ms while the bind's threads have the CPU).
#include <functional>

#include "app/editor/bind_worker.h"
#include "core/scene/document.h"

namespace dfm::editor {

// UI frames drawn while a job ran, each timed as the user sees it.
struct FrameTally {
  int frames = 0, over_100 = 0;
  double sum_ms = 0, max_ms = 0;
  void add(double ms);
  double mean_ms() const { return frames ? sum_ms / frames : 0.0; }
};

// What a batch run asks of the window.
struct BatchFrames {
  std::function<void()> draw;            // one frame: rendered, presented, events polled, finished
  std::function<bool()> job_frame_due;   // the job's display changed (at most progress_hz); else sleeps a little
  std::function<double()> seconds;       // a clock
  std::function<void()> after_frame;     // e.g. --bind-screenshot once the bind is far enough (may be empty)
};

// Runs doc's bind on the worker, drawing a frame whenever the progress shown changes, and applies the
// result to doc (one undo step). Prints the frames' count, mean, maximum and how many took over
// 100 ms, then the bind's wall time; throws dfm::Error when the bind fails.
void bind_with_frames(BindWorker& worker, Document& doc, const BatchFrames& frames, FrameTally& tally);

}  // namespace dfm::editor
