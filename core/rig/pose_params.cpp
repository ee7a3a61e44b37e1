#include "core/rig/pose_params.h"

#include <algorithm>

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

Pose evaluate_handle_parameters(const Rig& rig, const PoseParams& params) {
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

Pose evaluate_pose(const Rig& rig, const PoseParams& params) {
  Pose pose = evaluate_handle_parameters(rig, params);
  const Skeleton& sk = rig.skeleton;
  const int np = num_point_handles(rig), nb = sk.num_bones();
  if (nb == 0 || pose.size() < np + nb) return pose;
  // Which bones need connecting: a solved one, a bone hanging from another (a parent, or a root
  // sharing an earlier root's joint) with a translation, a root sharing a translated root's joint,
  // and whatever hangs off those. The rest is forward kinematics, connected already: it stays bit
  // for bit.
  const std::vector<int> to = bone_attachments(sk);
  auto translated = [&](int b) {
    return b < static_cast<int>(params.bone_translation.size()) && !params.bone_translation[b].isZero(0);
  };
  std::vector<char> only(nb, 0);
  bool any = false;
  for (int b = 0; b < nb; ++b) {
    const bool own = to[b] >= 0 && (translated(b) || (sk.bones[b].parent < 0 && translated(to[b])));
    only[b] = params.solved.count(np + b) > 0 || own;
    any = any || only[b];
  }
  if (!any) return pose;
  // Spread to every bone hanging (transitively) from a flagged one; a chain is at most nb long.
  for (bool grew = true; grew;) {
    grew = false;
    for (int b = 0; b < nb; ++b)
      if (!only[b] && to[b] >= 0 && only[to[b]]) only[b] = 1, grew = true;
  }
  std::vector<Eigen::Affine3d> T(pose.transforms.begin() + np, pose.transforms.begin() + np + nb);
  connect_bones(sk, T, only);
  std::copy(T.begin(), T.end(), pose.transforms.begin() + np);
  return pose;
}

}  // namespace dfm
