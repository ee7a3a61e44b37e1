#pragma once
// Keyframes: a pose (one affine per handle) at a time, kept in a track sorted by time.
#include <vector>

#include "core/rig/pose.h"

namespace dfm {

struct Keyframe {
  double time = 0.0;
  Pose pose;
};

// Keys sorted by strictly increasing time; every key has the same number of handles.
class KeyTrack {
 public:
  // Inserts a key, replacing one at exactly the same time. Throws dfm::Error on a non-finite time
  // or a handle count that differs from the keys already in the track.
  void set(const Keyframe& key);
  // Removes the key at exactly `time`; returns false if there is none.
  bool remove(double time);
  const std::vector<Keyframe>& keys() const { return keys_; }
  int size() const { return static_cast<int>(keys_.size()); }
  bool empty() const { return keys_.empty(); }
  double start() const { return keys_.front().time; }
  double end() const { return keys_.back().time; }

  // The interval holding `time`: index i with keys[i].time <= time <= keys[i+1].time and the local
  // parameter u in [0,1]. Times outside the track clamp to the first/last key (u = 0 or 1).
  // A single-key track gives {0, 0}. Throws dfm::Error on an empty track.
  struct Locus {
    int interval;
    double u;
  };
  Locus locate(double time) const;

 private:
  std::vector<Keyframe> keys_;
};

}  // namespace dfm
