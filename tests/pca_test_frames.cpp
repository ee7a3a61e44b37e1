// The PCA tests' independent references (declared in pca_test_frames.h), compiled once: the Jacobi SVD
// and the 4x4 eigen solver cost each test file that included them seconds of compile time.
#include "tests/pca_test_frames.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

namespace dfm::test {

// Horn (1987): the unit quaternion of the rotation M maximizing sum_v q_v . (M p_v) is the eigenvector
// of the largest eigenvalue of the symmetric 4x4 matrix built from S = sum_v p_v q_v^T. P, Q centred.
Eigen::Matrix3d horn_rotation(const Eigen::MatrixXd& P, const Eigen::MatrixXd& Q) {
  const Eigen::Matrix3d S = P.transpose() * Q;
  const double xx = S(0, 0), xy = S(0, 1), xz = S(0, 2), yx = S(1, 0), yy = S(1, 1), yz = S(1, 2), zx = S(2, 0),
               zy = S(2, 1), zz = S(2, 2);
  Eigen::Matrix4d N;
  N << xx + yy + zz, yz - zy, zx - xz, xy - yx,  //
      yz - zy, xx - yy - zz, xy + yx, zx + xz,   //
      zx - xz, xy + yx, -xx + yy - zz, yz + zy,  //
      xy - yx, zx + xz, yz + zy, -xx - yy + zz;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(N);
  const Eigen::Vector4d q = eig.eigenvectors().col(3);  // (w, x, y, z)
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
}

ReferencePca reference_pca(const std::vector<Eigen::MatrixXd>& frames) {
  ReferencePca r;
  const Eigen::Index nv = frames[0].rows();
  const int n = static_cast<int>(frames.size());
  const Eigen::MatrixXd ref = frames[0].rowwise() - frames[0].colwise().mean();
  std::vector<Eigen::MatrixXd> aligned;
  for (const auto& f : frames) {
    const Eigen::RowVector3d c = f.colwise().mean();
    const Eigen::MatrixXd P = f.rowwise() - c;
    const Eigen::Matrix3d M = horn_rotation(P, ref);  // P -> ref
    aligned.push_back(P * M.transpose());
    r.rotation.push_back(M.transpose());
    r.centroid.push_back(c.transpose());
  }
  Eigen::MatrixXd mean = Eigen::MatrixXd::Zero(nv, 3);
  for (const auto& a : aligned) mean += a / n;
  r.X.resize(3 * nv, n);
  for (int i = 0; i < n; ++i)
    for (Eigen::Index v = 0; v < nv; ++v)
      for (int c = 0; c < 3; ++c) r.X(3 * v + c, i) = aligned[i](v, c) - mean(v, c);
  r.sigma = Eigen::JacobiSVD<Eigen::MatrixXd>(r.X).singularValues();
  return r;
}

}  // namespace dfm::test
