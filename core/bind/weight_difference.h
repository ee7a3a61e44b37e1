#pragma once
// How far one set of skinning weights is from another on the same surface and handles, per vertex:
// the weight view's difference heat map after a Rebind (issue 32: an imported character's own weights
// against bounded biharmonic ones).
#include <Eigen/Core>

namespace dfm {

// W, R: #V x #handles. For handle h >= 0: |W(i, h) - R(i, h)|. For h < 0: the total variation
// 1/2 sum_h |W(i, h) - R(i, h)|, the share of the vertex's weight that moved to other handles (in
// [0, 1] when both rows are partitions of unity). Throws dfm::Error on a shape mismatch or h out of range.
Eigen::VectorXd weight_difference(const Eigen::MatrixXd& W, const Eigen::MatrixXd& R, int handle = -1);

}  // namespace dfm
