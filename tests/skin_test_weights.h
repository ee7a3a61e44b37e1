#pragma once
// Test-only smooth weights: normalized inverse fourth power of the distance to each bone segment.
// Stand-in for BBW where a test needs plausible blending across joints without running a bind.
#include <Eigen/Core>

#include "core/rig/rig.h"

namespace dfm::test {

inline Eigen::MatrixXd inverse_distance_bone_weights(const Eigen::MatrixXd& V, const Rig& rig) {
  const Skeleton& s = rig.skeleton;
  const int base = num_point_handles(rig);
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(V.rows(), num_handles(rig));
  for (int i = 0; i < V.rows(); ++i) {
    for (int b = 0; b < s.num_bones(); ++b) {
      const Eigen::RowVector3d a = s.joints.row(s.bones[b].a), d = s.joints.row(s.bones[b].b) - a;
      const double t = std::clamp((V.row(i) - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
      const double dist = (V.row(i) - (a + t * d)).norm();
      W(i, base + b) = 1.0 / std::pow(dist + 1e-9, 4);
    }
    W.row(i) /= W.row(i).sum();
  }
  return W;
}

}  // namespace dfm::test
