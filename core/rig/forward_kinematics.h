#pragma once
// Forward kinematics: world transforms of bones from rotations relative to their parents.
// A bone rotates about its first joint (rest position a); its transform is composed after its
// parent's:  T_b = T_parent * Translate(a + t_b) * R_b * Translate(-a),
// so a root's translation t moves its whole chain and a child's translation is in its parent's frame
// (the convention of libigl's forward_kinematics and of ../shared/data/hand-pose.dmat).
// A bone's twist/stretch (pose_params.h) acts in its rest frame before its rotation:
//   T_b = C_parent * Translate(a + t_b) * R_b * Translate(-a) * W_b,   W_b = twist_stretch_transform,
// while children compose with the rigid chain transform
//   C_b = C_parent * Translate(a + t_b) * R_b * Translate(-a) * Translate((stretch - 1)(b - a)) * Twist_b,
// so they follow the full twist and the moved second joint without being scaled (C_b = T_b at rest
// twist/stretch). STBS skinning (core/skin/stbs.h) undoes W_b on the bone itself and spreads it
// along the bone instead.
#include <vector>

#include <Eigen/Geometry>

#include "core/rig/pose_params.h"
#include "core/rig/rig.h"

namespace dfm {

// rotation / translation: one per bone (shorter vectors: missing entries are identity).
// Bone::parent must be filled (compute_bone_parents). Throws dfm::Error on a bad parent index.
std::vector<Eigen::Affine3d> forward_kinematics(const Skeleton& skeleton,
                                                const std::vector<Eigen::Quaterniond>& rotation,
                                                const std::vector<Eigen::Vector3d>& translation = {},
                                                const std::vector<BoneTwistStretch>& twist_stretch = {});

// W_b: rotation by `twist` about the rest axis through joint a, after scaling by `stretch` along that
// axis about a. Exactly the identity for twist 0 and stretch 1.
Eigen::Affine3d twist_stretch_transform(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const BoneTwistStretch& ts);
inline bool is_rest_twist_stretch(const BoneTwistStretch& ts) {
  return ts.twist == 0.0 && ts.stretch == 1.0 && ts.twist_start == 0.0;
}

// World rotation of a bone's parent chain (FK composes T_parent * R_b): the product of the parents'
// rotations, root first. A world-space offset or turn of the bone maps into its parent's frame by it.
Eigen::Quaterniond parent_world_rotation(const Skeleton& skeleton, const std::vector<Eigen::Quaterniond>& rotation,
                                         int bone);

// Posed joint positions (#J x 3) under bone transforms from forward_kinematics: each joint moves with
// a bone it ends (its b), or else with a bone it starts (its a); a joint on no bone stays at rest.
// With connected transforms (connect_bones) every bone at a joint puts it at this one point.
Eigen::MatrixXd posed_joints(const Skeleton& skeleton, const std::vector<Eigen::Affine3d>& bone_transforms);

// Per bone, the bone that places its first joint when posed: its parent (which ends there), else the
// first bone in index order starting at the same joint (roots sharing a joint move as one); -1 when
// the bone places that joint itself. Needs Bone::parent (compute_bone_parents).
std::vector<int> bone_attachments(const Skeleton& skeleton);

// The skeleton's one rule: every bone starts where the bone it is attached to (bone_attachments)
// puts that joint (Jacobson 2013, 4.3: bones sharing a joint transform it to the same point). Moves
// each attached bone's transform by a translation (its linear part kept), parents first, so a posed
// start equals its parent's posed end to rounding. `only` (one flag per bone, or empty for all):
// the bones to move; plain forward kinematics is connected already and is left bit for bit.
void connect_bones(const Skeleton& skeleton, std::vector<Eigen::Affine3d>& bone_transforms,
                   const std::vector<char>& only = {});

}  // namespace dfm
