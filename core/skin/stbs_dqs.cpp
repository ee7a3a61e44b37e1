#include "core/skin/stbs_dqs.h"

#include <cmath>
#include <string>

#include "core/skin/dqs.h"
#include "core/skin/lbs.h"
#include "core/util/error.h"

namespace dfm {

namespace {

struct DualQuaternion {
  Eigen::Vector4d real, dual;
};

// T'_b's dual quaternion composed with the bone's twist and stretch at endpoint weight e.
DualQuaternion bone_motion(const DqsHandle& T, const StbsHandle& h, double e) {
  const double angle = (1.0 - e) * h.twist_start + e * h.twist, half = 0.5 * angle;  // Eq. 6.5
  Eigen::Vector4d q;
  q << std::sin(half) * h.axis, std::cos(half);
  const Eigen::Vector3d moved_origin = Eigen::AngleAxisd(angle, h.axis) * h.origin;
  const Eigen::Vector3d t = h.origin - moved_origin + e * h.stretch;
  const Eigen::Vector4d d = 0.5 * quaternion_product(Eigen::Vector4d(t.x(), t.y(), t.z(), 0.0), q);
  return {quaternion_product(T.real, q), quaternion_product(T.real, d) + quaternion_product(T.dual, q)};
}

}  // namespace

void stbs_dqs(const Eigen::MatrixXd& V, const Eigen::MatrixXd& N, const Influences& inf, const Eigen::MatrixXd& E,
              const Pose& pose, const std::vector<StbsHandle>& handles, Eigen::MatrixXd& U, Eigen::MatrixXd* NU) {
  check_stbs_inputs(V, N, inf, E, pose, handles);
  std::vector<DqsHandle> H = dqs_handles(pose);
  for (int h = 0; h < pose.size(); ++h)  // T'_b = T_b W_b^-1 for active bones
    if (handles[h].active) H[h] = dqs_handle(pose.transforms[h] * handles[h].unstretched);
  const int n = static_cast<int>(V.rows()), k = inf.k();
  const bool normals = NU && N.size();
  U.resize(n, 3);
  if (normals) NU->resize(n, 3);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector4d br = Eigen::Vector4d::Zero(), bd = Eigen::Vector4d::Zero(), pivot = Eigen::Vector4d::Zero();
    Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
    bool any_stretch = false;
    for (int j = 0; j < k; ++j) {
      const double w = inf.weight(i, j);
      if (w == 0) continue;
      const int hi = inf.index(i, j);
      const DqsHandle& T = H[hi];
      const DualQuaternion m = handles[hi].active ? bone_motion(T, handles[hi], E(i, j)) : DualQuaternion{T.real, T.dual};
      if (j == 0) pivot = m.real;  // influences are sorted, largest first
      const double sw = m.real.dot(pivot) < 0 ? -w : w;
      br += sw * m.real;
      bd += sw * m.dual;
      if (!T.rigid) S += w * (T.stretch - Eigen::Matrix3d::Identity()), any_stretch = true;
    }
    apply_dq_blend(br, bd, S, any_stretch, i, V, N, U, normals ? NU : nullptr);
  }
}

}  // namespace dfm
