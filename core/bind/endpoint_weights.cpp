#include "core/bind/endpoint_weights.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace dfm {

namespace {


// Row r of bc on bone i's two joints: the hat functions at where the vertex projects onto the bone.
void add_bone_hats(const Skeleton& sk, int i, const Eigen::RowVector3d& p, double mass, Eigen::MatrixXd& bc,
                   Eigen::Index row) {
  const Bone& bone = sk.bones[i];
  const Eigen::RowVector3d a = sk.joints.row(bone.a), d = sk.joints.row(bone.b) - a;
  const double s = d.squaredNorm() > 0 ? std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  bc(row, bone.a) += mass * (1 - s);
  bc(row, bone.b) += mass * s;
}

}  // namespace

JointConstraints joint_constraints(const BindVolume& volume, const Rig& rig) {
  const Skeleton& sk = rig.skeleton;
  const int np = num_point_handles(rig), nb = sk.num_bones();
  JointConstraints c;
  if (nb == 0 || volume.bc.cols() < np + nb) return c;
  // Rows held by bones alone (a joint two bones share splits its row between them).
  std::vector<int> rows;
  for (Eigen::Index r = 0; r < volume.b.size(); ++r)
    if (std::abs(volume.bc.row(r).segment(np, nb).sum() - 1.0) < 1e-12) rows.push_back(static_cast<int>(r));
  c.b.resize(static_cast<Eigen::Index>(rows.size()));
  c.bc = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(rows.size()), sk.joints.rows());
  for (size_t k = 0; k < rows.size(); ++k) {
    const int r = rows[k];
    const Eigen::Index row = static_cast<Eigen::Index>(k);
    c.b[row] = volume.b[r];
    for (int i = 0; i < nb; ++i)
      if (volume.bc(r, np + i) > 0) add_bone_hats(sk, i, volume.tets.V.row(volume.b[r]), volume.bc(r, np + i), c.bc, row);
  }
  return c;
}

Eigen::MatrixXd endpoint_weights_from_joints(const Skeleton& skeleton, const Eigen::MatrixXd& J) {
  Eigen::MatrixXd E(J.rows(), skeleton.num_bones());
  for (int i = 0; i < skeleton.num_bones(); ++i) {
    const Bone& bone = skeleton.bones[i];
    E.col(i) = (0.5 * ((1.0 - J.col(bone.a).array()) + J.col(bone.b).array())).cwiseMax(0.0).cwiseMin(1.0);
  }
  return E;
}

Eigen::MatrixXd bind_endpoint_weights(const BindVolume& volume, const Rig& rig, const BbwOptions& opts) {
  const JointConstraints c = joint_constraints(volume, rig);
  if (c.b.size() == 0) return Eigen::MatrixXd(volume.tets.num_vertices(), 0);
  const Eigen::MatrixXd J = bbw_weights(volume.tets.V, volume.tets.T, c.b, c.bc, opts);
  return endpoint_weights_from_joints(rig.skeleton, J);
}

}  // namespace dfm
