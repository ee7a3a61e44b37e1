#pragma once
// The local step of ARAP (Sorkine & Alexa 2007; Jacobson 2013, 7.3.1): the rotation maximizing
// tr(R S). With S = U Sigma V^T, R = V U^T, the column of V with the smallest singular value negated
// when that would be a reflection, so det R = +1.
#include <Eigen/Core>

namespace dfm {

Eigen::Matrix3d best_rotation(const Eigen::Matrix3d& S);

}  // namespace dfm
