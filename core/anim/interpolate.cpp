#include "core/anim/interpolate.h"

#include <string>

#include <Eigen/SVD>

#include "core/rig/additional_handles.h"
#include "core/util/error.h"

namespace dfm {

PolarDecomposition polar_decompose(const Eigen::Matrix3d& A, const std::string& what) {
  const double det = A.determinant();
  if (!(det > 0.0))
    throw Error(what + ": linear part has determinant " + std::to_string(det) +
                " <= 0 (a reflection or collapse); it cannot be interpolated rotation-aware");
  // A = U Sigma V^T  ->  R = U V^T, S = V Sigma V^T. det(A) > 0 makes det(U V^T) = +1.
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  PolarDecomposition pd;
  pd.R = svd.matrixU() * svd.matrixV().transpose();
  pd.S = svd.matrixV() * svd.singularValues().asDiagonal() * svd.matrixV().transpose();
  pd.S = (0.5 * (pd.S + pd.S.transpose())).eval();  // exactly symmetric (eval: no aliasing)
  return pd;
}

Eigen::Affine3d interpolate_affine(const Eigen::Affine3d& a, const Eigen::Affine3d& b, double u) {
  const PolarDecomposition pa = polar_decompose(a.linear(), "first transform");
  const PolarDecomposition pb = polar_decompose(b.linear(), "second transform");
  const Eigen::Quaterniond qa(pa.R), qb(pb.R);
  const Eigen::Matrix3d R = qa.slerp(u, qb).toRotationMatrix();  // Eigen's slerp takes the short arc
  const Eigen::Matrix3d S = (1.0 - u) * pa.S + u * pb.S;
  Eigen::Affine3d out = Eigen::Affine3d::Identity();
  out.linear() = R * S;
  out.translation() = (1.0 - u) * a.translation() + u * b.translation();
  return out;
}

Pose interpolate_pose(const Pose& a, const Pose& b, double u) {
  if (a.size() != b.size())
    throw Error("cannot interpolate poses with " + std::to_string(a.size()) + " and " +
                std::to_string(b.size()) + " handle transforms");
  Pose out;
  out.transforms.reserve(a.size());
  for (int h = 0; h < a.size(); ++h) {
    try {
      out.transforms.push_back(interpolate_affine(a.transforms[h], b.transforms[h], u));
    } catch (const Error& e) {
      throw Error("handle " + std::to_string(h) + ": " + e.what());
    }
  }
  return out;
}

namespace {

template <class T, class Blend>
std::vector<T> blend_each(const std::vector<T>& a, const std::vector<T>& b, const char* what, Blend blend) {
  if (a.size() != b.size())
    throw Error(std::string("cannot interpolate pose parameters: ") + what + " " + std::to_string(a.size()) +
                " and " + std::to_string(b.size()));
  std::vector<T> out;
  out.reserve(a.size());
  for (size_t i = 0; i < a.size(); ++i) out.push_back(blend(a[i], b[i]));
  return out;
}

}  // namespace

PoseParams interpolate_pose_params(const Rig& rig, const PoseParams& a, const PoseParams& b, double u) {
  const auto slerp = [u](const Eigen::Quaterniond& p, const Eigen::Quaterniond& q) {
    return p.normalized().slerp(u, q.normalized());  // the short arc
  };
  const auto lerp = [u](const Eigen::Vector3d& p, const Eigen::Vector3d& q) -> Eigen::Vector3d {
    return (1.0 - u) * p + u * q;
  };
  const auto affine = [u](const Eigen::Affine3d& p, const Eigen::Affine3d& q) { return interpolate_affine(p, q, u); };
  PoseParams out;
  out.bone_rotation = blend_each(a.bone_rotation, b.bone_rotation, "bone rotations", slerp);
  out.bone_translation = blend_each(a.bone_translation, b.bone_translation, "bone translations", lerp);
  out.point_translation = blend_each(a.point_translation, b.point_translation, "point translations", lerp);
  out.point_rotation = blend_each(a.point_rotation, b.point_rotation, "point rotations", slerp);
  out.cage_translation = blend_each(a.cage_translation, b.cage_translation, "cage translations", lerp);
  out.region_transform = blend_each(a.region_transform, b.region_transform, "region transforms", affine);
  if (!a.bone_twist_stretch.empty() || !b.bone_twist_stretch.empty()) {
    const std::vector<BoneTwistStretch> rest(rig.skeleton.num_bones());
    out.bone_twist_stretch =
        blend_each(a.bone_twist_stretch.empty() ? rest : a.bone_twist_stretch,
                   b.bone_twist_stretch.empty() ? rest : b.bone_twist_stretch, "bone twists",
                   [u](const BoneTwistStretch& p, const BoneTwistStretch& q) {
                     return BoneTwistStretch{(1.0 - u) * p.twist + u * q.twist, (1.0 - u) * p.stretch + u * q.stretch,
                                             (1.0 - u) * p.twist_start + u * q.twist_start};
                   });
  }
  if (!a.solved.empty() || !b.solved.empty()) {
    const Pose own_a = evaluate_handle_parameters(rig, a), own_b = evaluate_handle_parameters(rig, b);
    std::map<int, Eigen::Affine3d> ends;
    for (const auto* m : {&a.solved, &b.solved})
      for (const auto& [h, T] : *m) ends[h] = T;
    for (const auto& [h, unused] : ends) {
      if (h < 0) continue;
      if (h >= own_a.size() || h >= own_b.size()) {
        // An additional handle (additional_handles.h): its transforms blend linearly, as the
        // subspace does (a rotation-aware blend of a zero matrix means nothing); unsolved is zero.
        const auto at = [h = h](const PoseParams& p) {
          const auto it = p.solved.find(h);
          return it == p.solved.end() ? zero_transform() : it->second;
        };
        Eigen::Affine3d T = zero_transform();
        T.matrix() = (1.0 - u) * at(a).matrix() + u * at(b).matrix();
        out.solved[h] = T;
        continue;
      }
      out.solved[h] = affine(own_a.transforms[h], own_b.transforms[h]);
    }
  }
  return out;
}

Pose sample_track(const KeyTrack& track, double time) {
  const KeyTrack::Locus at = track.locate(time);
  const auto& keys = track.keys();
  if (track.size() == 1) return keys[0].pose;
  const Keyframe& k0 = keys[at.interval];
  const Keyframe& k1 = keys[at.interval + 1];
  // Exactly at a key: return it unchanged (no SVD round-off), but still refuse reflections so
  // scrubbing does not accept a key it cannot blend.
  try {
    if (at.u == 0.0 || at.u == 1.0) {
      const Keyframe& k = at.u == 0.0 ? k0 : k1;
      for (int h = 0; h < k.pose.size(); ++h)
        polar_decompose(k.pose.transforms[h].linear(), "handle " + std::to_string(h));
      return k.pose;
    }
    return interpolate_pose(k0.pose, k1.pose, at.u);
  } catch (const Error& e) {
    throw Error("keys at times " + std::to_string(k0.time) + " and " + std::to_string(k1.time) + ": " +
                e.what());
  }
}

}  // namespace dfm
