#pragma once
// Rotation-aware interpolation of handle transforms (Alexa 2002, "Linear combination of
// transformations", Eq. 4.5 and the polar-decomposition scheme): each linear part A = R S is split
// into a rotation R and a symmetric stretch S; R is slerped, S and the translation blend linearly.
// A linear blend of the matrices themselves would shrink a 180-degree turn to nothing.
#include <Eigen/Geometry>

#include "core/anim/keyframes.h"
#include "core/rig/pose.h"

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

// The pose of a track at any time (clamped to the first/last key outside the track).
// Throws dfm::Error on an empty track or a reflecting transform in a key used.
Pose sample_track(const KeyTrack& track, double time);

}  // namespace dfm
