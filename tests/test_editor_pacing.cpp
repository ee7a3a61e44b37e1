// The editor loop's pacing (when to draw, how long to sleep) and the HUD's frame figures, on a
// simulated clock: an idle editor draws nothing and sleeps; input draws at once and settles; playback
// draws every frame; a running job draws when its progress changes (or a heartbeat), at most 30 a
// second, input and playback included.
#include <catch2/catch.hpp>

#include "app/editor/frame_pacing.h"

using namespace dfm::editor;

namespace {

double g_clock = 100.0;  // the simulated glfwGetTime, running on across simulate() calls

// Runs the loop for `seconds` of simulated time: each frame costs `frame_s`, a wait sleeps the full
// time asked (no event arrives unless `input_every_s` > 0). Returns the frames drawn.
int simulate(FramePacer& p, LoopActivity a, double seconds, double frame_s, double input_every_s = 0,
             double* slept = nullptr) {
  double t = g_clock, next_input = input_every_s > 0 ? t : 1e300;
  const double end = t + seconds;
  int frames = 0;
  double sleep_sum = 0;
  while (t < end) {
    LoopActivity now = a;
    now.input = a.input || t >= next_input;
    if (t >= next_input) next_input += input_every_s;
    const double wait = p.next(now, t);
    if (wait > 0) {
      const double w = std::min(wait, next_input - t);  // an event ends the wait early
      t += std::max(w, 1e-9);
      sleep_sum += std::max(w, 1e-9);
      continue;
    }
    p.drew(t);
    t += frame_s;
    ++frames;
  }
  g_clock = t;
  if (slept) *slept = sleep_sum;
  return frames;
}

}  // namespace

TEST_CASE("an idle editor draws its first frames, then only sleeps", "[editor][pacing]") {
  FramePacer p;
  double slept = 0;
  const int frames = simulate(p, {}, 10.0, 0.02, 0, &slept);
  CHECK(frames == 1 + p.options().settle_frames);  // the first frame and its settling, then none
  CHECK(slept > 9.9);
  // Each wait is bounded (timers such as the autosave still run) but long: few wake-ups a second.
  CHECK(p.next({}, g_clock) == Approx(p.options().idle_wait_s));
  CHECK(p.options().idle_wait_s >= 0.1);
}

TEST_CASE("input draws at once, plus a few settling frames, then sleeps again", "[editor][pacing]") {
  FramePacer p;
  simulate(p, {}, 1.0, 0.01);  // settle the start-up frames
  LoopActivity in;
  in.input = true;
  const double t = g_clock;
  CHECK(p.next(in, t) == 0.0);
  p.drew(t);
  for (int i = 0; i < p.options().settle_frames; ++i) {
    CHECK(p.next({}, t + 0.02 * (i + 1)) == 0.0);
    p.drew(t + 0.02 * (i + 1));
  }
  CHECK(p.next({}, t + 1.0) > 0.0);
  g_clock = t + 1.0;
  // Continuous input (a drag): a frame per event, as fast as the events come.
  CHECK(simulate(p, {}, 1.0, 0.005, 1.0 / 120) >= 110);
}

TEST_CASE("playback draws every frame; a job's progress at most 30 Hz, input and playback included", "[editor][pacing]") {
  FramePacer p;
  LoopActivity play;
  play.playing = true;
  CHECK(simulate(p, play, 1.0, 0.004) >= 240);  // no sleeping while playing: as fast as frames draw
  LoopActivity job;
  job.job_running = true;
  job.job_progress = true;  // its progress changes all the time: progress_hz
  double slept = 0;
  const int job_frames = simulate(p, job, 2.0, 0.004, 0, &slept);
  CHECK(job_frames >= 2.0 * p.options().progress_hz - 2);
  CHECK(job_frames <= 2.0 * p.options().progress_hz + 1);
  CHECK(slept > 1.7);  // the job's threads get the CPU between frames
  CHECK(p.options().progress_hz <= p.options().job_hz);
  CHECK(simulate(p, job, 2.0, 0.004, 1.0 / 200) >= 55);  // a drag during a bind: 30 Hz...
  CHECK(simulate(p, job, 2.0, 0.004, 1.0 / 200) <= 61);  // ...not the 200 Hz of its events
  // A job whose display does not change: the heartbeat only (its result is collected by a frame),
  // polled at 30 Hz.
  LoopActivity quiet;
  quiet.job_running = true;
  const int quiet_frames = simulate(p, quiet, 2.0, 0.004, 0, &slept);
  CHECK(quiet_frames >= 2.0 / p.options().job_heartbeat_s - 1);
  CHECK(quiet_frames <= 2.0 / p.options().job_heartbeat_s + 2);
  CHECK(p.next(quiet, g_clock + 0.001) <= 1.0 / p.options().job_hz);
  job.playing = true;
  CHECK(simulate(p, job, 2.0, 0.004, 1.0 / 200) <= 61);  // a drag and playback during a bind: still 30 Hz
  // The job ends: one frame (and its settling) shows the result without waiting for input.
  CHECK(p.next({}, g_clock) == 0.0);
}

// Issue 38: the HUD read "6 fps 37.8 ms" after a transition built (frames paced at 5 Hz while the job
// ran): two figures that cannot both describe one frame. Both now come from the same frames' drawing
// times, so fps * ms = 1000 whatever the gaps between frames were.
TEST_CASE("the HUD's fps and ms describe the same frames: fps = 1000 / ms, gaps not counted", "[editor][pacing]") {
  FrameStats s;
  CHECK(s.fps() == 0.0);
  CHECK(s.ms() == 0.0);
  // A script: each frame follows a command that ran for a second, 20 ms to draw: 50 fps, 20 ms.
  double t = 10.0;
  for (int i = 0; i < 5; ++i) {
    s.pause();
    t += 1.0;
    s.begin(t);
    t += 0.020;
    s.end(t);
  }
  CHECK(s.ms() == Approx(20.0));
  CHECK(s.fps() == Approx(50.0));
  // A job's progress paced at 5 Hz, 37.8 ms a frame (the figures): 26.5 fps, not 5.
  FrameStats j;
  for (int i = 0; i < 40; ++i) {
    j.begin(200.0 + 0.2 * i);
    j.end(200.0 + 0.2 * i + 0.0378);
  }
  CHECK(j.ms() == Approx(37.8));
  CHECK(j.fps() == Approx(1000.0 / 37.8));
  // Frames of mixed cost over a window of 10: only the last 10 count, for both figures.
  FrameStats c(10);
  for (int i = 0; i < 30; ++i) {
    const double cost = i < 20 ? 0.050 : 0.010;
    c.begin(100.0 + 0.1 * i);
    c.end(100.0 + 0.1 * i + cost);
  }
  CHECK(c.ms() == Approx(10.0));
  CHECK(c.fps() * c.ms() == Approx(1000.0));
  CHECK(c.frames() == 30);
  CHECK(c.last_ms() == Approx(10.0));
  // An end without a begin is ignored.
  c.end(500.0);
  CHECK(c.frames() == 30);
}
