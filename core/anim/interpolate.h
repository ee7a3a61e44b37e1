#pragma once
// Rotation-aware interpolation of handle transforms (Alexa 2002, "Linear combination of
// transformations", Eq. 4.5 and the polar-decomposition scheme): each linear part A = R S is split
// into a rotation R and a symmetric stretch S; R is slerped, S and the translation blend linearly.
// A linear blend of the matrices themselves would shrink a 180-degree turn to nothing.
#include <Eigen/Geometry>

#include "core/anim/keyframes.h"
#include "core/rig/pose.h"
#include "core/rig/pose_params.h"

namespace dfm {

struct PolarDecomposition {
  Eigen::Matrix3d R;  // rotation, det +1
  Eigen::Matrix3d S;  // symmetric positive definite stretch
};

// A = R S. Throws dfm::Error when det(A) <= 0 (a reflection or a collapse has no rotation part
// that can be slerped); `what` names the transform in the message.
PolarDecomposition polar_decompose(const Eigen::Matrix3d& A, const std::string& what = "transform");

// The transform a fraction u in [0,1] of the way from a to b.
Eigen::Affine3d interpolate_affine(const Eigen::Affine3d& a, const Eigen::Affine3d& b, double u);

// Handle by handle; the poses must have the same size (dfm::Error otherwise).
Pose interpolate_pose(const Pose& a, const Pose& b, double u);

// The pose parameters (what a key holds, pose_params.h) a fraction u in [0,1] of the way from a to b:
// each rotation slerped in its own frame (a bone's in its parent's, about its first joint; a point's
// about the point), translations, twist and stretch blended linearly, region transforms and FAST's
// solved transforms by interpolate_affine (a handle solved in one key only takes, in the other, the
// transform its parameters give: evaluate_handle_parameters). evaluate_pose of the result keeps every
// joint joined between keys, which interpolate_pose of the evaluated transforms does not: blending the
// translation part linearly moves the pivot of a rotation, so a bone turning about its first joint
// would leave it. Throws dfm::Error when a and b do not fit the rig.
PoseParams interpolate_pose_params(const Rig& rig, const PoseParams& a, const PoseParams& b, double u);

// The pose of a track at any time (clamped to the first/last key outside the track).
// Throws dfm::Error on an empty track or a reflecting transform in a key used.
Pose sample_track(const KeyTrack& track, double time);

}  // namespace dfm
