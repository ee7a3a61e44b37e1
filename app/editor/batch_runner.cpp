#include "app/editor/batch_runner.h"

#include <algorithm>
#include <cstdio>

#include "core/scene/bind_document.h"
#include "core/util/error.h"

namespace dfm::editor {

void FrameTally::add(double ms) {
  ++frames;
  sum_ms += ms;
  max_ms = std::max(max_ms, ms);
  over_100 += ms > 100.0;
}

void bind_with_frames(BindWorker& worker, Document& doc, const BatchFrames& frames, FrameTally& tally) {
  // The window as the user sees it before pressing Bind: the first frame ever drawn pays one-off
  // costs (shader compiles, mesh and font uploads) that are not the bind's.
  frames.draw();
  const double bind_t0 = frames.seconds();
  worker.start(make_document_bind_job(doc));
  tally = FrameTally{};
  // Keep drawing (progress bar) while the worker runs, as in the interactive editor: a frame when the
  // progress shown changes, sleeping between them so the bind's threads get the CPU.
  while (worker.running()) {
    if (!frames.job_frame_due()) continue;
    const double t0 = frames.seconds();
    frames.draw();
    tally.add(1000.0 * (frames.seconds() - t0));
    if (frames.after_frame) frames.after_frame();
  }
  const double bind_wall = frames.seconds() - bind_t0;
  std::printf("bind: %d frames drawn while binding, mean %.1f ms, max %.1f ms, %d over 100 ms\n", tally.frames,
              tally.mean_ms(), tally.max_ms, tally.over_100);
  std::fflush(stdout);
  auto r = worker.take_result();
  if (!r || !r->ok) throw Error(r ? r->error : "bind produced no result");
  std::printf("bind: wall time %.2f s (the bind's own stages %.2f s)\n", bind_wall, r->result->report.total_seconds);
  std::fflush(stdout);
  apply_bind_result(doc, *r->result);
}

}  // namespace dfm::editor
