#include "core/rig/additional_handles.h"

#include <string>

#include "core/util/error.h"

namespace dfm {

Eigen::Affine3d zero_transform() {
  Eigen::Affine3d T = Eigen::Affine3d::Identity();
  T.linear().setZero();
  return T;
}

Pose skin_pose(const Rig& rig, const PoseParams& params, int additional) {
  Pose pose = evaluate_pose(rig, params);
  const int nh = num_handles(rig);
  for (int e = 0; e < additional; ++e) {
    const auto it = params.solved.find(nh + e);
    pose.transforms.push_back(it == params.solved.end() ? zero_transform() : it->second);
  }
  return pose;
}

void drop_additional_transforms(PoseParams& params, int num_rig_handles) {
  params.solved.erase(params.solved.lower_bound(num_rig_handles), params.solved.end());
}

Eigen::MatrixXd with_additional_weights(const Eigen::MatrixXd& W, const Eigen::MatrixXd& A) {
  if (A.size() == 0) return W;
  if (A.rows() != W.rows())
    throw Error("additional weights have " + std::to_string(A.rows()) + " rows, the weights " + std::to_string(W.rows()));
  Eigen::MatrixXd out(W.rows(), W.cols() + A.cols());
  out << W, A;
  return out;
}

}  // namespace dfm
