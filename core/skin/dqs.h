#pragma once
// Dual-quaternion skinning (Kavan, Collins, Zara, O'Sullivan 2008), CPU reference in double precision.
// Each handle's affine A = R S (polar decomposition) is split into a rigid part (R, t) -- a unit dual
// quaternion -- and a remaining stretch S. Like Kavan's two-phase scheme, the stretches are blended
// linearly first, S(p) = I + sum_j w_j (S_j - I) (exactly I for rigid poses), then the dual
// quaternions: b = sum_j w_j s_j q_j with s_j = +-1 putting every q_j in the hemisphere of the
// vertex's largest-weight handle (the sign fix), normalized, applied to S(p) p.
// Normals: R_b cof(S(p)) n, normalized.
#include <vector>

#include <Eigen/Geometry>

#include "core/rig/pose.h"
#include "core/skin/influences.h"

namespace dfm {

struct DqsHandle {
  Eigen::Vector4d real;     // rotation quaternion (x, y, z, w), w >= 0 not required
  Eigen::Vector4d dual;     // 0.5 * (0, t) * real
  Eigen::Matrix3d stretch;  // S = R^T A (identity for a rigid transform)
  bool rigid = true;
};

// Throws dfm::Error for a singular or non-finite transform.
DqsHandle dqs_handle(const Eigen::Affine3d& T);
std::vector<DqsHandle> dqs_handles(const Pose& pose);

// The quaternion product a b on (x, y, z, w) coefficient vectors.
Eigen::Vector4d quaternion_product(const Eigen::Vector4d& a, const Eigen::Vector4d& b);

// Applies a unit dual quaternion (real, dual) to p.
Eigen::Vector3d dq_transform_point(const Eigen::Vector4d& real, const Eigen::Vector4d& dual, const Eigen::Vector3d& p);

// Vertex i of V (and of N when NU is set) moved by the blend (br, bd) of its handles' dual quaternions
// (normalized here) after the blended stretch S (when `stretch`); no weight at all (a zero blend)
// leaves it where it is. Shared by dqs() and stbs_dqs().
void apply_dq_blend(Eigen::Vector4d br, Eigen::Vector4d bd, const Eigen::Matrix3d& S, bool stretch, int i,
                    const Eigen::MatrixXd& V, const Eigen::MatrixXd& N, Eigen::MatrixXd& U, Eigen::MatrixXd* NU);

void dqs(const Eigen::MatrixXd& V, const Eigen::MatrixXd& N, const Influences& inf, const Pose& pose,
         Eigen::MatrixXd& U, Eigen::MatrixXd* NU = nullptr);

}  // namespace dfm
