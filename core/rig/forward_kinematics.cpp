#include "core/rig/forward_kinematics.h"

#include <algorithm>
#include <functional>
#include <string>

#include "core/util/error.h"

namespace dfm {

std::vector<Eigen::Affine3d> forward_kinematics(const Skeleton& s, const std::vector<Eigen::Quaterniond>& rotation,
                                                const std::vector<Eigen::Vector3d>& translation,
                                                const std::vector<BoneTwistStretch>& twist_stretch) {
  const int nb = s.num_bones();
  for (int i = 0; i < nb; ++i) {
    const Bone& b = s.bones[i];
    if (b.a < 0 || b.a >= s.num_joints() || b.b < 0 || b.b >= s.num_joints())
      throw Error("bone " + std::to_string(i) + " refers to a joint out of range");
    if (b.parent < -1 || b.parent >= nb || b.parent == i)
      throw Error("bone " + std::to_string(i) + " has an invalid parent " + std::to_string(b.parent));
  }
  // T: the bones' own transforms. chain: what children compose with -- the same, except that a
  // stretch only moves the children (a rigid translation) instead of scaling them.
  std::vector<Eigen::Affine3d> T(nb, Eigen::Affine3d::Identity()), chain(nb, Eigen::Affine3d::Identity());
  for (int i : bones_topological_order(s)) {  // parents first
    const Bone& b = s.bones[i];
    const Eigen::Vector3d a = s.joints.row(b.a).transpose();
    Eigen::Quaterniond q = i < static_cast<int>(rotation.size()) ? rotation[i].normalized()
                                                                  : Eigen::Quaterniond::Identity();
    Eigen::Vector3d t = i < static_cast<int>(translation.size()) ? translation[i] : Eigen::Vector3d::Zero();
    const Eigen::Affine3d local = Eigen::Translation3d(a + t) * q * Eigen::Translation3d(-a);
    const Eigen::Affine3d base = b.parent >= 0 ? chain[b.parent] * local : local;
    T[i] = chain[i] = base;
    if (i < static_cast<int>(twist_stretch.size()) && !is_rest_twist_stretch(twist_stretch[i])) {
      const BoneTwistStretch& ts = twist_stretch[i];
      const Eigen::Vector3d e = s.joints.row(b.b).transpose();
      T[i] = base * twist_stretch_transform(a, e, ts);
      chain[i] = base * Eigen::Translation3d((ts.stretch - 1.0) * (e - a)) *
                 twist_stretch_transform(a, e, BoneTwistStretch{ts.twist, 1.0});
    }
  }
  return T;
}

Eigen::Affine3d twist_stretch_transform(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const BoneTwistStretch& ts) {
  if (is_rest_twist_stretch(ts)) return Eigen::Affine3d::Identity();
  const Eigen::Vector3d d = b - a;
  if (d.norm() == 0) throw Error("cannot twist or stretch a bone of zero length");
  const Eigen::Vector3d u = d.normalized();
  Eigen::Matrix3d L = Eigen::AngleAxisd(ts.twist, u).toRotationMatrix() *
                      (Eigen::Matrix3d::Identity() + (ts.stretch - 1.0) * u * u.transpose());
  Eigen::Affine3d W = Eigen::Affine3d::Identity();
  W.linear() = L;
  W.translation() = a - L * a;
  return W;
}

Eigen::MatrixXd posed_joints(const Skeleton& s, const std::vector<Eigen::Affine3d>& T) {
  Eigen::MatrixXd J = s.joints;
  std::vector<int> moved(s.num_joints(), 0);  // 2 = by a bone ending there, 1 = by a bone starting there
  for (int i = 0; i < s.num_bones() && i < static_cast<int>(T.size()); ++i) {
    const Bone& b = s.bones[i];
    if (moved[b.b] < 2) {
      J.row(b.b) = (T[i] * Eigen::Vector3d(s.joints.row(b.b).transpose())).transpose();
      moved[b.b] = 2;
    }
    if (moved[b.a] < 1) {
      J.row(b.a) = (T[i] * Eigen::Vector3d(s.joints.row(b.a).transpose())).transpose();
      moved[b.a] = 1;
    }
  }
  return J;
}

std::vector<int> bone_attachments(const Skeleton& s) {
  const int nb = s.num_bones();
  std::vector<int> to(nb, -1);
  for (int i = 0; i < nb; ++i) {
    if (s.bones[i].parent >= 0) {
      to[i] = s.bones[i].parent;
      continue;
    }
    for (int k = 0; k < i && to[i] < 0; ++k)
      if (s.bones[k].a == s.bones[i].a) to[i] = k;
  }
  return to;
}

void connect_bones(const Skeleton& s, std::vector<Eigen::Affine3d>& T, const std::vector<char>& only) {
  const std::vector<int> to = bone_attachments(s);
  const int n = std::min(s.num_bones(), static_cast<int>(T.size()));
  std::vector<char> done(s.num_bones(), 0);
  // The bone a bone is attached to is connected first (attachments form a forest: parents, or earlier roots).
  std::function<void(int)> connect = [&](int i) {
    if (done[i]) return;
    done[i] = 1;
    if (to[i] < 0 || to[i] >= n) return;
    connect(to[i]);
    if (!only.empty() && (i >= static_cast<int>(only.size()) || !only[i])) return;
    const Eigen::Vector3d a = s.joints.row(s.bones[i].a).transpose();
    // The parent's end is its transform of its rest second joint, which is this bone's rest first joint.
    T[i].pretranslate(T[to[i]] * a - T[i] * a);
  };
  for (int i = 0; i < n; ++i) connect(i);
}

Eigen::Quaterniond parent_world_rotation(const Skeleton& skeleton, const std::vector<Eigen::Quaterniond>& rotation,
                                         int bone) {
  Eigen::Quaterniond R = Eigen::Quaterniond::Identity();
  for (int b = skeleton.bones[bone].parent; b >= 0; b = skeleton.bones[b].parent)
    if (b < static_cast<int>(rotation.size())) R = rotation[b].normalized() * R;
  return R;
}

}  // namespace dfm
