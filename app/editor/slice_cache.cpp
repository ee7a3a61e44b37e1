#include "app/editor/slice_cache.h"

#include <algorithm>
#include <cmath>

#include "core/anim/interval_slice.h"
#include "core/anim/manifold_frame.h"

namespace dfm::editor {

IntervalCachePolicy::IntervalCachePolicy(int capacity) : slots_(std::max(capacity, 1)) {}

void IntervalCachePolicy::reset(std::vector<double> vertex_times, std::vector<bool> prism) {
  times_ = std::move(vertex_times);
  prism_ = std::move(prism);
  prism_.resize(times_.empty() ? 0 : times_.size() - 1, false);
  for (Slot& s : slots_) s = Slot{};
  clock_ = 0;
  builds_ = 0;
}

SliceDecision IntervalCachePolicy::choose(bool time_axis, double t, double frame_step) {
  SliceDecision d;
  if (!time_axis || times_.size() < 2) return d;
  const int i = open_interval_of(times_, t);
  if (i < 0) return on_vertex_time(t);
  ++clock_;
  for (int s = 0; s < capacity(); ++s)
    if (slots_[s].interval == i) {
      slots_[s].used = clock_;
      return {SliceRoute::Cached, i, s};
    }
  if (!worth_building(i, frame_step)) return d;  // gone before a cache pays back
  return build(i);
}

SliceDecision IntervalCachePolicy::build(int interval) {
  int victim = -1;  // the first empty slot, else the least recently used
  for (int s = 0; s < capacity() && victim < 0; ++s)
    if (slots_[s].interval < 0) victim = s;
  if (victim < 0) {
    victim = 0;
    for (int s = 1; s < capacity(); ++s)
      if (slots_[s].used < slots_[victim].used) victim = s;
  }
  slots_[victim] = Slot{interval, ++clock_};
  ++builds_;
  return {SliceRoute::Build, interval, victim};
}

SliceDecision IntervalCachePolicy::on_vertex_time(double t) {
  const auto it = std::lower_bound(times_.begin(), times_.end(), t);
  if (it == times_.end() || *it != t) return {};  // outside the manifold
  const int k = static_cast<int>(it - times_.begin());  // t = times[k]: interval k - 1 ends, k starts
  for (int s = 0; s < capacity(); ++s)
    if (slots_[s].interval >= 0 && (slots_[s].interval == k - 1 || slots_[s].interval == k)) {
      slots_[s].used = ++clock_;
      return {SliceRoute::Cached, slots_[s].interval, s};
    }
  // A prism interval ending (exactly: its upper layer) or starting here draws the layer as a frame.
  for (int i : {k - 1, k})
    if (i >= 0 && i < static_cast<int>(prism_.size()) && prism_[i]) return build(i);
  return {};
}

bool IntervalCachePolicy::cached(int interval) const {
  for (const Slot& s : slots_)
    if (s.interval == interval && interval >= 0) return true;
  return false;
}

bool IntervalCachePolicy::worth_building(int interval, double frame_step) const {
  if (interval < 0 || interval + 1 >= static_cast<int>(times_.size())) return false;
  return prism_[interval] || times_[interval + 1] - times_[interval] >= std::abs(frame_step);
}

int IntervalCachePolicy::next_interval(int interval, double frame_step) const {
  const int n = static_cast<int>(times_.size()) - 1;
  if (n <= 0) return -1;
  const int next = frame_step < 0 ? interval - 1 : interval + 1;
  return next < 0 ? n - 1 : next >= n ? 0 : next;
}

void IntervalCachePolicy::grow(int capacity) {
  if (capacity > this->capacity()) slots_.resize(capacity);
}

void IntervalCachePolicy::forget(int slot) {
  if (slot >= 0 && slot < capacity()) slots_[slot] = Slot{};
}

std::vector<bool> prism_intervals(const AnimationManifold& m, const std::vector<double>& times) {
  std::vector<bool> out(times.empty() ? 0 : times.size() - 1, false);
  for (size_t i = 0; i < out.size(); ++i) out[i] = prism_slab_at(m, 0.5 * (times[i] + times[i + 1])) >= 0;
  return out;
}

}  // namespace dfm::editor
