#pragma once
// Which way the editor slices the animation manifold this frame (no GL, so it is testable alone):
//   - General: the per-tetrahedron GPU slice pass (render/slice_pass.h), for the x, y, z sweep, a time
//     outside the manifold or on a vertex time with neither neighbouring interval cached, and an
//     interval not cached yet that is shorter than
//     the frame step (playback would leave it before a cache could pay back: a transition between
//     meshes of different connectivity has very many distinct vertex times);
//   - Cached: the interval holding t is in one of the cache's slots: draw it by interpolation
//     (render/interval_slice_pass.h); on a vertex time, a cached interval that ends or starts there
//     (its slice's limit is the slice at that time: the same surface, some triangles collapsed);
//   - Build: the interval is not cached yet and worth it: the caller builds its topology into `slot`
//     (the least recently used one when all are taken), then draws as Cached.
// Intervals are the open ones between consecutive distinct vertex times (core/anim/interval_slice.h).
// An interval inside a prism slab (keys of one connectivity) is always built, on a vertex time at its
// ends too: its frame is the layers' mesh (core/anim/manifold_frame.h), which the general pass (the
// prisms' exact slice, four triangles for each) does not draw, and building it costs a copy.
#include <cstdint>
#include <vector>

#include "core/anim/manifold.h"

namespace dfm::editor {

enum class SliceRoute { General, Cached, Build };

struct SliceDecision {
  SliceRoute route = SliceRoute::General;
  int interval = -1;  // index i of (times[i], times[i + 1]); -1 for General
  int slot = -1;      // the cache slot that holds (Cached) or is to hold (Build) it
};

class IntervalCachePolicy {
 public:
  explicit IntervalCachePolicy(int capacity = 4);
  // A new manifold: its distinct vertex times (increasing) and, per interval, whether it lies in a
  // prism slab (prism_intervals; empty: none does); forgets every cached interval.
  void reset(std::vector<double> vertex_times, std::vector<bool> prism = {});
  // time_axis: slicing along t (false for the x, y, z sweep). frame_step: how far the time moved
  // since the last frame (0 when it did not, or the last frame was not a time slice).
  // Records a Build as cached (the caller must then fill that slot) and a use of the slot.
  SliceDecision choose(bool time_axis, double t, double frame_step);
  // The caller could not build the slot (an error): forget it.
  void forget(int slot);
  // More slots (empty ones appended; existing ones kept); never fewer.
  void grow(int capacity);
  // Interval i is in a slot.
  bool cached(int interval) const;
  // Interval i is a prism slab's, or lasts at least one frame step: a topology built for it pays back.
  bool worth_building(int interval, double frame_step) const;
  // The interval playback reaches after interval i when moving by frame_step (forward when 0),
  // wrapping around as a looping timeline does; -1 without intervals.
  int next_interval(int interval, double frame_step) const;

  int capacity() const { return static_cast<int>(slots_.size()); }
  int slot_interval(int slot) const { return slots_[slot].interval; }  // -1 when empty
  const std::vector<double>& times() const { return times_; }
  int builds() const { return builds_; }  // intervals built since reset

 private:
  SliceDecision on_vertex_time(double t);
  SliceDecision build(int interval);

  struct Slot {
    int interval = -1;
    std::uint64_t used = 0;
  };
  std::vector<double> times_;
  std::vector<bool> prism_;
  std::vector<Slot> slots_;
  std::uint64_t clock_ = 0;
  int builds_ = 0;
};

// Per interval (times[i], times[i + 1]) of m's distinct vertex times: it lies in a prism slab.
std::vector<bool> prism_intervals(const AnimationManifold& m, const std::vector<double>& times);

}  // namespace dfm::editor
