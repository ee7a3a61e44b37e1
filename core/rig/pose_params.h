#pragma once
// What an artist edits, per handle kind; evaluate_pose() turns it into one affine per handle.
//   bones:  a rotation relative to the parent, about the bone's first joint (forward kinematics),
//           plus a translation (a root's translation moves its whole chain);
//   points: a translation, plus a rotation inferred from pseudo-edges (Jacobson 2013, 4.3.4) or,
//           for a point with no pseudo-edge, the explicit rotation given here (about the point);
//   cage vertices: a translation;  regions: a full affine.
// All vectors are sized by resize_pose_params(); missing entries mean identity.
#include <vector>

#include <Eigen/Geometry>

#include "core/rig/pose.h"
#include "core/rig/rig.h"

namespace dfm {

struct PoseParams {
  std::vector<Eigen::Quaterniond> bone_rotation;
  std::vector<Eigen::Vector3d> bone_translation;
  std::vector<Eigen::Vector3d> point_translation;
  std::vector<Eigen::Quaterniond> point_rotation;
  std::vector<Eigen::Vector3d> cage_translation;  // one per cage vertex, cages concatenated
  std::vector<Eigen::Affine3d> region_transform;
};

// Sizes every vector to the rig, identity entries.
PoseParams rest_pose_params(const Rig& rig);
// Forward kinematics + pseudo-edge rotation inference -> one affine per handle (rig.h order).
Pose evaluate_pose(const Rig& rig, const PoseParams& params);

}  // namespace dfm
