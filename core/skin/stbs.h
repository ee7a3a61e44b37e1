#pragma once
// Stretchable, twistable bones (Jacobson & Sorkine 2011; Jacobson 2013 ch. 6), CPU reference.
// A bone's pose transform T_b includes its twist/stretch W_b (core/rig/forward_kinematics.h). LBS
// applies all of it to every vertex the bone influences, which collapses the skin near the joint
// (candy wrapper). STBS instead uses the bone's transform without W_b, T'_b = T_b W_b^-1, and spreads
// the twist and stretch along the bone by an endpoint weight e(p) in [0,1] (0 at the first joint,
// 1 at the second):
//   p' = sum_j w_j T'_j ( p + [Rot(u_j, theta_j(p))(p - a_j) - (p - a_j)] + e_j(p) (sigma_j - 1)(b_j - a_j) ),
//   theta_j(p) = (1 - e_j(p)) theta_a + e_j(p) theta_b   (Eq. 6.5: the twists at the first and second joint)
// Non-bone handles (and bones at zero twist, unit stretch) take T_j p: then STBS equals LBS exactly.
// Normals: cof(sum_j w_j A'_j Rot_j) n, normalized (the derivative of e is ignored).
#include <vector>

#include <Eigen/Geometry>

#include "core/rig/pose.h"
#include "core/rig/pose_params.h"
#include "core/rig/rig.h"
#include "core/skin/influences.h"

namespace dfm {

// Per handle (rig.h order): what STBS needs beyond the pose.
struct StbsHandle {
  bool active = false;  // a bone with a twist (at either end) or stretch != 1
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();   // rest first joint a
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();     // unit rest direction of b - a
  double twist = 0.0;                                 // radians, at the second joint (e = 1)
  double twist_start = 0.0;                           // radians, at the first joint (e = 0)
  Eigen::Vector3d stretch = Eigen::Vector3d::Zero();  // (sigma - 1)(b - a)
  Eigen::Affine3d unstretched = Eigen::Affine3d::Identity();  // W_b^-1, to turn T_b into T'_b
};

// One per handle of the rig; twist_stretch has one entry per bone (missing: rest).
std::vector<StbsHandle> stbs_handles(const Rig& rig, const std::vector<BoneTwistStretch>& twist_stretch);

// e(p) per vertex and handle (#V x #handles; 0 for non-bone handles): t = clamp of the projection
// parameter of p onto the bone's segment, smoothed by 3t^2 - 2t^3 so the twist starts and ends
// without a kink.
Eigen::MatrixXd bone_endpoint_weights(const Eigen::MatrixXd& V, const Rig& rig);

// Throws dfm::Error unless the inputs fit (check_skin_inputs, one record a handle, E #V x k).
void check_stbs_inputs(const Eigen::MatrixXd& V, const Eigen::MatrixXd& N, const Influences& inf, const Eigen::MatrixXd& E,
                       const Pose& pose, const std::vector<StbsHandle>& handles);

// E: #V x k endpoint weights in influence order (gather_by_influence(inf, bone_endpoint_weights(...))).
void stbs(const Eigen::MatrixXd& V, const Eigen::MatrixXd& N, const Influences& inf, const Eigen::MatrixXd& E,
          const Pose& pose, const std::vector<StbsHandle>& handles, Eigen::MatrixXd& U, Eigen::MatrixXd* NU = nullptr);

}  // namespace dfm
