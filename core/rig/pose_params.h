#pragma once
// What an artist edits, per handle kind; evaluate_pose() turns it into one affine per handle.
//   bones:  a rotation relative to the parent, about the bone's first joint (forward kinematics),
//           plus a translation (a root's translation moves its whole chain);
//   points: a translation, plus a rotation inferred from pseudo-edges (Jacobson 2013, 4.3.4) or,
//           for a point with no pseudo-edge, the explicit rotation given here (about the point);
//   cage vertices: a translation;  regions: a full affine.
// All vectors are sized by resize_pose_params(); missing entries mean identity.
#include <map>
#include <vector>

#include <Eigen/Geometry>

#include "core/rig/pose.h"
#include "core/rig/rig.h"

namespace dfm {

// Stretchable, twistable bones (Jacobson 2013 ch. 6): per bone, a twist about its own axis that goes
// from `twist_start` at the first joint to `twist` at the second ((1 - e) theta_a + e theta_b, Eq. 6.5),
// and a length factor (1 = rest length). The bone's frame (and its children's) carries `twist`;
// `twist_start` only spreads the twist along the bone's own skin.
struct BoneTwistStretch {
  double twist = 0.0;        // radians, right-handed about (b - a), at the second joint
  double stretch = 1.0;      // posed length / rest length
  double twist_start = 0.0;  // radians, at the first joint
};

struct PoseParams {
  std::vector<Eigen::Quaterniond> bone_rotation;
  std::vector<Eigen::Vector3d> bone_translation;
  std::vector<Eigen::Vector3d> point_translation;
  std::vector<Eigen::Quaterniond> point_rotation;
  std::vector<Eigen::Vector3d> cage_translation;  // one per cage vertex, cages concatenated
  std::vector<Eigen::Affine3d> region_transform;
  // Twist/stretch per bone: in the bone transforms (children follow); STBS spreads them along the bone.
  std::vector<BoneTwistStretch> bone_twist_stretch;
  // Transforms solved by FAST (core/pose/fast_posing.h), keyed by handle (rig.h order): each replaces
  // the transform the fields above give that handle, so a key holds exactly what the solver found.
  std::map<int, Eigen::Affine3d> solved;
};

// Bone b's twist and stretch (rest where the params hold none for it).
inline BoneTwistStretch twist_stretch_of(const PoseParams& p, int bone) {
  return bone >= 0 && bone < static_cast<int>(p.bone_twist_stretch.size()) ? p.bone_twist_stretch[bone] : BoneTwistStretch{};
}

// Sizes every vector to the rig, identity entries.
PoseParams rest_pose_params(const Rig& rig);
// Forward kinematics + pseudo-edge rotation inference -> one affine per handle (rig.h order), then the
// solved transforms in place of theirs (entries past the rig's handles are ignored), then the bones
// connected (connect_bones): every bone starts where its parent ends, whatever a solve or a
// translation of a bone with a parent gave it (such a translation is projected out).
Pose evaluate_pose(const Rig& rig, const PoseParams& params);
// evaluate_pose before the bones are connected: each handle where its own parameters put it. FAST
// reads position targets from it (a dragged bone's tip target is its translated tip, fast_posing.h).
Pose evaluate_handle_parameters(const Rig& rig, const PoseParams& params);

}  // namespace dfm
