#pragma once
// Stretchable, twistable bones over dual quaternions (Jacobson 2013, 6.2.1: STBS "works with any
// underlying skinning method"). An active bone (stbs.h) moves vertex p by the rigid motion
//   M_b(p) = T'_b( Rot(u_b, e theta_b) (p - a_b) + a_b + e (sigma_b - 1)(b_b - a_b) ),
// e = e_b(p) its endpoint weight, T'_b = T_b W_b^-1 the bone without its twist and stretch: a unit dual
// quaternion per vertex and bone, blended as DQS blends handles (dqs.h: the sign fix against the
// vertex's largest-weight handle, normalized). Other handles take their DQS terms, so at zero twist
// and unit stretch this is DQS bit for bit; a vertex on one bone only moves as STBS over LBS moves it.
#include <vector>

#include <Eigen/Core>

#include "core/rig/pose.h"
#include "core/skin/influences.h"
#include "core/skin/stbs.h"

namespace dfm {

// E: #V x k endpoint weights in influence order, as stbs() takes them.
void stbs_dqs(const Eigen::MatrixXd& V, const Eigen::MatrixXd& N, const Influences& inf, const Eigen::MatrixXd& E,
              const Pose& pose, const std::vector<StbsHandle>& handles, Eigen::MatrixXd& U, Eigen::MatrixXd* NU = nullptr);

}  // namespace dfm
