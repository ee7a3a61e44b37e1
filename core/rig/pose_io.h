#pragma once
// Pose files for `deform pose` and the editor:
//   Q.dmat  one rotation per bone relative to its parent, quaternion coefficients (x, y, z, w), as a
//           4*#bones x 1 column (the layout of ../shared/data/hand-pose.dmat) or a #bones x 4 matrix;
//   P.txt   one translation per point handle, "x y z" per line (core/mesh/io.h read_points);
//   TS.dmat one row per bone: its twist in degrees (at its second joint), its stretch factor, and
//           optionally its twist in degrees at its first joint (Eq. 6.5's theta_a).
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/rig/pose_params.h"

namespace dfm {

// Throws dfm::Error naming the file when the count differs from expected_bones (if >= 0) or a
// quaternion is zero or not finite. Quaternions are normalized.
std::vector<Eigen::Quaterniond> read_bone_rotations(const std::string& path, int expected_bones = -1);
void write_bone_rotations(const std::string& path, const std::vector<Eigen::Quaterniond>& q);

std::vector<Eigen::Vector3d> read_point_translations(const std::string& path, int expected_points = -1);

// Throws dfm::Error naming the file: not #bones x 2 or 3, a value not finite, a stretch not positive
// (naming the bone). Twists come back in radians.
std::vector<BoneTwistStretch> read_bone_twist_stretch(const std::string& path, int bones);
void write_point_translations(const std::string& path, const std::vector<Eigen::Vector3d>& t);

}  // namespace dfm
