#include "core/skin/dqs.h"

#include <Eigen/SVD>

#include "core/skin/lbs.h"
#include "core/util/error.h"

namespace dfm {

Eigen::Vector4d quaternion_product(const Eigen::Vector4d& a, const Eigen::Vector4d& b) {
  const Eigen::Vector3d av = a.head<3>(), bv = b.head<3>();
  Eigen::Vector4d r;
  r.head<3>() = a[3] * bv + b[3] * av + av.cross(bv);
  r[3] = a[3] * b[3] - av.dot(bv);
  return r;
}

DqsHandle dqs_handle(const Eigen::Affine3d& T) {
  const Eigen::Matrix3d A = T.linear();
  if (!T.matrix().allFinite()) throw Error("dual-quaternion skinning: a handle transform is not finite");
  DqsHandle h;
  Eigen::Matrix3d R;
  if ((A.transpose() * A - Eigen::Matrix3d::Identity()).norm() < 1e-10 && A.determinant() > 0) {
    R = A;  // already a rotation: no decomposition, so the identity stays exactly the identity
    h.stretch.setIdentity();
  } else {
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::Vector3d sv = svd.singularValues();
    if (!(sv[2] > 1e-12 * std::max(1.0, sv[0])))
      throw Error("dual-quaternion skinning: a handle transform is singular");
    Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
    D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1 : 1;
    R = svd.matrixU() * D * svd.matrixV().transpose();
    h.stretch = R.transpose() * A;
    h.rigid = false;
  }
  h.real = Eigen::Quaterniond(R).normalized().coeffs();
  Eigen::Vector4d t(T.translation().x(), T.translation().y(), T.translation().z(), 0.0);
  h.dual = 0.5 * quaternion_product(t, h.real);
  return h;
}

std::vector<DqsHandle> dqs_handles(const Pose& pose) {
  std::vector<DqsHandle> out;
  out.reserve(pose.size());
  for (const auto& T : pose.transforms) out.push_back(dqs_handle(T));
  return out;
}

Eigen::Vector3d dq_transform_point(const Eigen::Vector4d& real, const Eigen::Vector4d& dual, const Eigen::Vector3d& p) {
  // Kavan et al. 2008, Algorithm 1 (for a unit dual quaternion).
  const Eigen::Vector3d r = real.head<3>(), d = dual.head<3>();
  const double rw = real[3], dw = dual[3];
  return p + 2.0 * r.cross(r.cross(p) + rw * p) + 2.0 * (rw * d - dw * r + r.cross(d));
}

void dqs(const Eigen::MatrixXd& V, const Eigen::MatrixXd& N, const Influences& inf, const Pose& pose,
         Eigen::MatrixXd& U, Eigen::MatrixXd* NU) {
  check_skin_inputs(V, N, inf, pose);
  const std::vector<DqsHandle> H = dqs_handles(pose);
  bool any_stretch = false;
  for (const auto& h : H) any_stretch |= !h.rigid;
  const int n = static_cast<int>(V.rows()), k = inf.k();
  const bool normals = NU && N.size();
  U.resize(n, 3);
  if (normals) NU->resize(n, 3);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector4d br = Eigen::Vector4d::Zero(), bd = Eigen::Vector4d::Zero();
    Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
    const Eigen::Vector4d& pivot = H[inf.index(i, 0)].real;  // influences are sorted, largest first
    for (int j = 0; j < k; ++j) {
      const double w = inf.weight(i, j);
      if (w == 0) continue;
      const DqsHandle& h = H[inf.index(i, j)];
      const double sw = h.real.dot(pivot) < 0 ? -w : w;
      br += sw * h.real;
      bd += sw * h.dual;
      if (any_stretch) S += w * (h.stretch - Eigen::Matrix3d::Identity());
    }
    apply_dq_blend(br, bd, S, any_stretch, i, V, N, U, normals ? NU : nullptr);
  }
}

void apply_dq_blend(Eigen::Vector4d br, Eigen::Vector4d bd, const Eigen::Matrix3d& S, bool stretch, int i,
                    const Eigen::MatrixXd& V, const Eigen::MatrixXd& N, Eigen::MatrixXd& U, Eigen::MatrixXd* NU) {
  const double len = br.norm();
  if (len == 0) {  // no weight at all: leave the vertex where it is
    U.row(i) = V.row(i);
    if (NU) NU->row(i) = N.row(i);
    return;
  }
  br /= len;
  bd /= len;
  const Eigen::Vector3d p = stretch ? Eigen::Vector3d(S * V.row(i).transpose()) : Eigen::Vector3d(V.row(i).transpose());
  U.row(i) = dq_transform_point(br, bd, p).transpose();
  if (NU) {
    const Eigen::Vector3d sn = transform_normal(S, N.row(i).transpose());
    // Rotation only: the dual quaternion with zero dual part.
    NU->row(i) = dq_transform_point(br, Eigen::Vector4d::Zero(), sn).transpose();
  }
}

}  // namespace dfm
