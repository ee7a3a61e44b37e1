#pragma once
// A pose: one affine transform per handle (same order as the rig's handles, see rig.h).
#include <vector>

#include <Eigen/Geometry>

#include "core/rig/rig.h"

namespace dfm {

struct Pose {
  std::vector<Eigen::Affine3d> transforms;
  int size() const { return static_cast<int>(transforms.size()); }
};

inline Pose identity_pose(int num_handles) {
  Pose p;
  p.transforms.assign(num_handles, Eigen::Affine3d::Identity());
  return p;
}

}  // namespace dfm
