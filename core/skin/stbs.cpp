#include "core/skin/stbs.h"

#include <algorithm>
#include <string>

#include "core/rig/forward_kinematics.h"
#include "core/skin/lbs.h"
#include "core/util/error.h"

namespace dfm {

std::vector<StbsHandle> stbs_handles(const Rig& rig, const std::vector<BoneTwistStretch>& ts) {
  std::vector<StbsHandle> out(num_handles(rig));
  const int base = num_point_handles(rig);
  const Skeleton& s = rig.skeleton;
  for (int b = 0; b < s.num_bones() && b < static_cast<int>(ts.size()); ++b) {
    if (is_rest_twist_stretch(ts[b])) continue;
    StbsHandle& h = out[base + b];
    const Eigen::Vector3d a = s.joints.row(s.bones[b].a).transpose(), e = s.joints.row(s.bones[b].b).transpose();
    h.active = true;
    h.origin = a;
    h.axis = (e - a).normalized();
    h.twist = ts[b].twist;
    h.twist_start = ts[b].twist_start;
    h.stretch = (ts[b].stretch - 1.0) * (e - a);
    h.unstretched = twist_stretch_transform(a, e, ts[b]).inverse();
  }
  return out;
}

Eigen::MatrixXd bone_endpoint_weights(const Eigen::MatrixXd& V, const Rig& rig) {
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(V.rows(), num_handles(rig));
  const int base = num_point_handles(rig);
  const Skeleton& s = rig.skeleton;
  for (int b = 0; b < s.num_bones(); ++b) {
    const Eigen::RowVector3d a = s.joints.row(s.bones[b].a), d = s.joints.row(s.bones[b].b) - a;
    const double len2 = d.squaredNorm();
    if (len2 == 0) continue;
    for (int i = 0; i < V.rows(); ++i) {
      const double t = std::clamp((V.row(i) - a).dot(d) / len2, 0.0, 1.0);
      E(i, base + b) = t * t * (3.0 - 2.0 * t);
    }
  }
  return E;
}

// Rodrigues: v rotated by angle about unit axis u.
static Eigen::Vector3d rotate(const Eigen::Vector3d& u, double angle, const Eigen::Vector3d& v) {
  const double c = std::cos(angle), s = std::sin(angle);
  return v * c + u.cross(v) * s + u * (u.dot(v) * (1.0 - c));
}

void check_stbs_inputs(const Eigen::MatrixXd& V, const Eigen::MatrixXd& N, const Influences& inf, const Eigen::MatrixXd& E,
                       const Pose& pose, const std::vector<StbsHandle>& handles) {
  check_skin_inputs(V, N, inf, pose);
  if (static_cast<int>(handles.size()) != pose.size())
    throw Error("stretchable-twistable skinning: " + std::to_string(handles.size()) + " handle records for " +
                std::to_string(pose.size()) + " transforms");
  if (E.rows() != V.rows() || E.cols() != inf.k())
    throw Error("stretchable-twistable skinning: endpoint weights must be #V x k");
}

void stbs(const Eigen::MatrixXd& V, const Eigen::MatrixXd& N, const Influences& inf, const Eigen::MatrixXd& E,
          const Pose& pose, const std::vector<StbsHandle>& handles, Eigen::MatrixXd& U, Eigen::MatrixXd* NU) {
  check_stbs_inputs(V, N, inf, E, pose, handles);
  // T'_b = T_b W_b^-1 for active bones.
  std::vector<Eigen::Affine3d> Tp(pose.transforms);
  for (int h = 0; h < pose.size(); ++h)
    if (handles[h].active) Tp[h] = pose.transforms[h] * handles[h].unstretched;
  const int n = static_cast<int>(V.rows()), k = inf.k();
  const bool normals = NU && N.size();
  U.resize(n, 3);
  if (normals) NU->resize(n, 3);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d p = V.row(i).transpose();
    Eigen::Vector3d q = Eigen::Vector3d::Zero();
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    for (int j = 0; j < k; ++j) {
      const double w = inf.weight(i, j);
      if (w == 0) continue;
      const int hi = inf.index(i, j);
      const Eigen::Affine3d& T = Tp[hi];
      const StbsHandle& h = handles[hi];
      if (!h.active) {  // the LBS term, computed exactly as lbs() does
        q += w * (T.linear() * p + T.translation());
        if (normals) A += w * T.linear();
        continue;
      }
      const double e = E(i, j), angle = (1.0 - e) * h.twist_start + e * h.twist;  // Eq. 6.5
      const Eigen::Vector3d r = p - h.origin;
      const Eigen::Vector3d pp = p + (rotate(h.axis, angle, r) - r) + e * h.stretch;
      q += w * (T.linear() * pp + T.translation());
      if (normals) A += w * T.linear() * Eigen::AngleAxisd(angle, h.axis).toRotationMatrix();
    }
    U.row(i) = q.transpose();
    if (normals) NU->row(i) = transform_normal(A, N.row(i).transpose()).transpose();
  }
}

}  // namespace dfm
