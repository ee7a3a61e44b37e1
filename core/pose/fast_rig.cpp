#include "core/pose/fast_rig.h"

#include <algorithm>
#include <sstream>

#include "core/rig/forward_kinematics.h"
#include "core/util/error.h"

namespace dfm {

Eigen::Vector3d handle_anchor(const Rig& rig, int handle, const Eigen::MatrixXd& surface) {
  const HandleRef ref = handle_ref(rig, handle);
  switch (ref.kind) {
    case HandleKind::Point: return rig.points[ref.index].position;
    case HandleKind::Bone: return rig.skeleton.joints.row(rig.skeleton.bones[ref.index].b).transpose();
    case HandleKind::CageVertex: return rig.cages[ref.cage].mesh.V.row(ref.index).transpose();
    case HandleKind::Region: {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      const auto& verts = rig.regions[ref.index].vertices;
      if (surface.rows() == 0 || verts.empty()) return c;
      for (int v : verts) c += surface.row(v).transpose();
      return c / static_cast<double>(verts.size());
    }
  }
  return Eigen::Vector3d::Zero();
}

std::vector<FastConstraint> default_fast_constraints(const Rig& rig, const std::vector<int>& free_handles) {
  const int n = num_handles(rig);
  std::vector<FastConstraint> c(n);
  for (int h = 0; h < n; ++h) {
    const HandleKind kind = handle_ref(rig, h).kind;
    c[h].anchor = handle_anchor(rig, h);
    if (kind == HandleKind::Point || kind == HandleKind::CageVertex) c[h].state = HandleConstraint::Position;
  }
  for (int h : free_handles) {
    if (h < 0 || h >= n) throw Error("free handle " + std::to_string(h) + " is not in the rig's " + std::to_string(n));
    c[h].state = HandleConstraint::Free;
  }
  return c;
}

std::vector<Eigen::Vector3d> fast_targets(const std::vector<FastConstraint>& constraints, const Pose& pose) {
  std::vector<Eigen::Vector3d> t(constraints.size(), Eigen::Vector3d::Zero());
  for (size_t h = 0; h < constraints.size() && static_cast<int>(h) < pose.size(); ++h)
    t[h] = pose.transforms[h] * constraints[h].anchor;
  return t;
}

std::vector<HandleConstraint> ik_chain_states(const Rig& rig, std::vector<HandleConstraint> states, int bone_handle) {
  if (static_cast<int>(states.size()) != num_handles(rig)) throw Error("IK chain: one state per handle expected");
  if (bone_handle < 0 || bone_handle >= num_handles(rig) || handle_ref(rig, bone_handle).kind != HandleKind::Bone)
    throw Error("IK chain: handle " + std::to_string(bone_handle) + " is not a bone");
  const Skeleton& sk = rig.skeleton;
  const int np = num_point_handles(rig);
  states[bone_handle] = HandleConstraint::Position;
  for (int b = sk.bones[bone_handle - np].parent; b >= 0; b = sk.bones[b].parent)
    states[np + b] = sk.bones[b].parent < 0 ? HandleConstraint::Fixed : HandleConstraint::Free;
  return states;
}

std::vector<FastJoint> fast_joints(const Rig& rig) {
  std::vector<FastJoint> out;
  const Skeleton& sk = rig.skeleton;
  const std::vector<int> to = bone_attachments(sk);
  const int np = num_point_handles(rig);
  for (int b = 0; b < sk.num_bones(); ++b)
    if (to[b] >= 0) out.push_back({np + b, np + to[b], sk.joints.row(sk.bones[b].a).transpose()});
  return out;
}

std::vector<int> parse_handle_list(const Rig& rig, const std::string& list) {
  std::vector<int> out;
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(find_handle(rig, item));
  return out;
}

}  // namespace dfm
