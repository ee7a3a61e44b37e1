#include "core/rig/pose_params.h"

#include "core/rig/forward_kinematics.h"
#include "core/rig/pseudo_edges.h"

namespace dfm {

PoseParams rest_pose_params(const Rig& rig) {
  PoseParams p;
  const int nb = rig.skeleton.num_bones(), np = num_point_handles(rig);
  p.bone_rotation.assign(nb, Eigen::Quaterniond::Identity());
  p.bone_translation.assign(nb, Eigen::Vector3d::Zero());
  p.point_translation.assign(np, Eigen::Vector3d::Zero());
  p.point_rotation.assign(np, Eigen::Quaterniond::Identity());
  p.cage_translation.assign(num_cage_vertices(rig), Eigen::Vector3d::Zero());
  p.region_transform.assign(rig.regions.size(), Eigen::Affine3d::Identity());
  p.bone_twist_stretch.assign(nb, BoneTwistStretch{});
  return p;
}

namespace {
template <class T>
T at_or(const std::vector<T>& v, int i, const T& fallback) {
  return i < static_cast<int>(v.size()) ? v[i] : fallback;
}
}  // namespace

Pose evaluate_pose(const Rig& rig, const PoseParams& params) {
  Pose pose;
  pose.transforms.reserve(num_handles(rig));

  // Point handles: translation, rotation about the point from pseudo-edges (else the explicit one).
  const int np = num_point_handles(rig);
  Eigen::MatrixXd rest(np, 3), posed(np, 3);
  for (int i = 0; i < np; ++i) {
    rest.row(i) = rig.points[i].position.transpose();
    posed.row(i) = (rig.points[i].position + at_or(params.point_translation, i, Eigen::Vector3d::Zero().eval())).transpose();
  }
  std::vector<bool> has_edge;
  const auto inferred = pseudo_edge_rotations(rest, posed, rig.pseudo_edges, &has_edge);
  for (int i = 0; i < np; ++i) {
    const Eigen::Quaterniond q =
        has_edge[i] ? inferred[i] : at_or(params.point_rotation, i, Eigen::Quaterniond::Identity()).normalized();
    const Eigen::Vector3d p0 = rest.row(i).transpose(), p1 = posed.row(i).transpose();
    pose.transforms.push_back(Eigen::Translation3d(p1) * q * Eigen::Translation3d(-p0));
  }

  for (const auto& T : forward_kinematics(rig.skeleton, params.bone_rotation, params.bone_translation,
                                             params.bone_twist_stretch))
    pose.transforms.push_back(T);

  const int nc = num_cage_vertices(rig);
  for (int i = 0; i < nc; ++i) {
    Eigen::Affine3d T = Eigen::Affine3d::Identity();
    T.translation() = at_or(params.cage_translation, i, Eigen::Vector3d::Zero().eval());
    pose.transforms.push_back(T);
  }
  for (int i = 0; i < static_cast<int>(rig.regions.size()); ++i)
    pose.transforms.push_back(at_or(params.region_transform, i, Eigen::Affine3d::Identity()));
  for (const auto& [h, T] : params.solved)
    if (h >= 0 && h < pose.size()) pose.transforms[h] = T;
  return pose;
}

}  // namespace dfm
