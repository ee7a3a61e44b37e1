#include "core/anim/interpolate.h"

#include <string>

#include <Eigen/SVD>

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
