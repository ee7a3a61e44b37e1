#pragma once
// Shape-aware endpoint weights for stretchable, twistable bones (Jacobson 2013, 6.2.3). Joint weights
// j_k are bounded biharmonic weights on the bind volume whose constraints are each bone's sample
// vertices, held to the hat functions of its two joints (1 - s at joint a, s at joint b, s the
// vertex's place along the bone: linear along it, the 2D property of 6.2.2); then per bone
//   e_i = ((1 - j_a) + j_b) / 2                                                  (Eq. 6.7),
// 0 at a, 1 at b, in [0, 1], smooth and shape-aware. STBS reads them where the bone has weight;
// core/skin's projection onto the bone stays the fallback for weights that did not come from a bind.
#include <Eigen/Core>

#include "core/bind/bbw.h"
#include "core/bind/bind_volume.h"
#include "core/rig/rig.h"

namespace dfm {

// The joint weights' constraints on `volume`: its rows constrained to a bone (a 1 in that bone's
// column of volume.bc, rig.h handle order), each split between the bone's two joints by where it
// projects onto the bone. #b x #joints. Empty when the rig has no bones.
struct JointConstraints {
  Eigen::VectorXi b;
  Eigen::MatrixXd bc;
};
JointConstraints joint_constraints(const BindVolume& volume, const Rig& rig);

// Eq. 6.7 per bone from joint weights J (#V x #joints): #V x #bones, clamped to [0, 1].
Eigen::MatrixXd endpoint_weights_from_joints(const Skeleton& skeleton, const Eigen::MatrixXd& J);

// Both, with the joint weights solved on the volume (bbw_weights with `opts`): #tet vertices x #bones.
Eigen::MatrixXd bind_endpoint_weights(const BindVolume& volume, const Rig& rig, const BbwOptions& opts);

}  // namespace dfm
