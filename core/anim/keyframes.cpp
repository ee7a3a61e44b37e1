#include "core/anim/keyframes.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/util/error.h"

namespace dfm {

void KeyTrack::set(const Keyframe& key) {
  if (!std::isfinite(key.time)) throw Error("keyframe time is not a finite number");
  if (!keys_.empty() && key.pose.size() != keys_.front().pose.size())
    throw Error("keyframe at time " + std::to_string(key.time) + " has " + std::to_string(key.pose.size()) +
                " handle transforms, the track has " + std::to_string(keys_.front().pose.size()));
  auto it = std::lower_bound(keys_.begin(), keys_.end(), key.time,
                             [](const Keyframe& k, double t) { return k.time < t; });
  if (it != keys_.end() && it->time == key.time)
    *it = key;
  else
    keys_.insert(it, key);
}

bool KeyTrack::remove(double time) {
  auto it = std::find_if(keys_.begin(), keys_.end(), [&](const Keyframe& k) { return k.time == time; });
  if (it == keys_.end()) return false;
  keys_.erase(it);
  return true;
}

KeyTrack::Locus KeyTrack::locate(double time) const {
  if (keys_.empty()) throw Error("the key track is empty");
  const int n = size();
  if (n == 1 || time <= keys_.front().time) return {0, 0.0};
  if (time >= keys_.back().time) return {n - 2, 1.0};
  // First key strictly after `time`; the interval starts one before it.
  auto it = std::upper_bound(keys_.begin(), keys_.end(), time,
                             [](double t, const Keyframe& k) { return t < k.time; });
  const int i = static_cast<int>(it - keys_.begin()) - 1;
  const double t0 = keys_[i].time, t1 = keys_[i + 1].time;
  return {i, (time - t0) / (t1 - t0)};
}

}  // namespace dfm
