#pragma once
// When the editor draws, and what its frames cost. All CPU (no window): the loop asks the pacer
// whether to draw now or how long it may sleep in glfwWaitEventsTimeout, and reports each frame
// drawn to FrameStats, whose figures the HUD shows.
//   - input (or a window event): draw now, then a few more frames so ImGui settles its layout;
//   - playing: every frame;
//   - a running job (bind, manifold build): a frame when what it shows changes (stage, percent,
//     elapsed tenths of a second) or every `job_heartbeat_s`, at most `progress_hz`; while a job
//     runs every frame, input and playback included, keeps to `job_hz`, so the job's threads get
//     the CPU (on software GL a frame of the default scene costs 20-30 ms of a core);
//   - otherwise idle: sleep until an event (waking every `idle_wait_s` to run timers such as the
//     autosave, without drawing).
#include <deque>

namespace dfm::editor {

struct PacingOptions {
  double job_hz = 30.0;       // at most this many frames a second while a job runs (input, playback)
  double progress_hz = 5.0;   // ...and this many when only its progress changed
  double idle_wait_s = 0.5;   // the longest sleep (timers are checked at least this often)
  double job_heartbeat_s = 0.25;  // while a job runs, a frame at least this often (collects its result)
  int settle_frames = 2;      // frames drawn after the last input (ImGui sizes windows a frame late)
};

// What the loop knows now.
struct LoopActivity {
  bool input = false;        // an event arrived since the last decision
  bool playing = false;      // the timeline is playing
  bool job_running = false;  // a bind or a manifold build is running
  bool job_progress = false;  // what the running job shows changed since the last decision
};

class FramePacer {
 public:
  explicit FramePacer(const PacingOptions& o = {}) : opts_(o), settle_left_(1 + o.settle_frames) {}
  // 0: draw a frame now; else the seconds to wait for events before asking again. Records the
  // input (it asks for settle frames) and a job that just ended (one more frame shows its result).
  double next(const LoopActivity& a, double now);
  // Call after each frame drawn, with the time it started (a job's frames keep to job_hz start to start).
  void drew(double frame_start);
  const PacingOptions& options() const { return opts_; }

 private:
  PacingOptions opts_;
  double last_frame_ = -1e300;
  int settle_left_;  // frames still to draw after input (or the first frame)
  bool job_was_running_ = false;
  bool progress_pending_ = false;  // a job's progress changed and is not drawn yet
};

// The HUD's figures over the last `window` frames, both from the same frames: ms = the mean time to
// draw a frame (UI, scene, swap), fps = 1000 / ms, the rate the editor draws at while it draws on (a
// playback, a drag). The time between frames is not counted: an idle editor sleeps, and while a job
// runs frames are paced on purpose (FramePacer), which says nothing about the drawing's speed.
class FrameStats {
 public:
  explicit FrameStats(int window = 60) : window_(window) {}
  void begin(double now);
  void end(double now);
  // The next frame does not follow on from the last one (kept for the loop's calls: the figures
  // count drawing time only, so a pause changes nothing).
  void pause() {}
  double ms() const;
  double fps() const;
  int frames() const { return frames_; }
  double last_ms() const { return cost_.empty() ? 0.0 : cost_.back(); }
  double last_start() const { return start_; }

 private:
  int window_;
  std::deque<double> cost_;  // milliseconds
  double start_ = 0;
  bool open_ = false;
  int frames_ = 0;
};

}  // namespace dfm::editor
