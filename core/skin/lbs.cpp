#include "core/skin/lbs.h"

#include <string>
#include <vector>

#include "core/util/error.h"

namespace dfm {

Eigen::Vector3d transform_normal(const Eigen::Matrix3d& M, const Eigen::Vector3d& n) {
  Eigen::Matrix3d C;
  C.col(0) = M.col(1).cross(M.col(2));
  C.col(1) = M.col(2).cross(M.col(0));
  C.col(2) = M.col(0).cross(M.col(1));
  Eigen::Vector3d r = C * n;
  const double len = r.norm();
  return len > 0 ? Eigen::Vector3d(r / len) : r;
}

void check_skin_inputs(const Eigen::MatrixXd& V, const Eigen::MatrixXd& N, const Influences& inf, const Pose& pose) {
  if (V.cols() != 3) throw Error("skinning: rest positions must have 3 columns");
  if (inf.num_vertices() != V.rows())
    throw Error("skinning: " + std::to_string(inf.num_vertices()) + " rows of weights for " +
                std::to_string(V.rows()) + " vertices");
  if (N.size() != 0 && (N.rows() != V.rows() || N.cols() != 3))
    throw Error("skinning: normals must be #V x 3");
  if (inf.index.size() && (inf.index.minCoeff() < 0 || inf.index.maxCoeff() >= pose.size()))
    throw Error("skinning: weights name handle " + std::to_string(inf.index.maxCoeff()) + " but the pose has " +
                std::to_string(pose.size()) + " transforms");
}

void lbs(const Eigen::MatrixXd& V, const Eigen::MatrixXd& N, const Influences& inf, const Pose& pose,
         Eigen::MatrixXd& U, Eigen::MatrixXd* NU) {
  check_skin_inputs(V, N, inf, pose);
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
      const Eigen::Affine3d& T = pose.transforms[inf.index(i, j)];
      q += w * (T.linear() * p + T.translation());
      if (normals) A += w * T.linear();
    }
    U.row(i) = q.transpose();
    if (normals) NU->row(i) = transform_normal(A, N.row(i).transpose()).transpose();
  }
}

Eigen::MatrixXd lbs(const Eigen::MatrixXd& V, const Eigen::MatrixXd& W, const Pose& pose) {
  Eigen::MatrixXd U;
  lbs(V, Eigen::MatrixXd(), all_influences(W), pose, U);
  return U;
}

Eigen::MatrixXd lbs_matrix(const Eigen::MatrixXd& V, const Eigen::MatrixXd& W) {
  if (V.rows() != W.rows()) throw Error("lbs_matrix: V and W row counts differ");
  const int n = static_cast<int>(V.rows()), h = static_cast<int>(W.cols());
  Eigen::MatrixXd M(n, 4 * h);
  for (int j = 0; j < h; ++j)
    for (int c = 0; c < 4; ++c)
      M.col(j * 4 + c) = W.col(j).cwiseProduct(c < 3 ? Eigen::VectorXd(V.col(c)) : Eigen::VectorXd::Ones(n));
  return M;
}

Eigen::MatrixXd pose_matrix(const Pose& pose) {
  Eigen::MatrixXd T(4 * pose.size(), 3);
  for (int j = 0; j < pose.size(); ++j) T.block<4, 3>(4 * j, 0) = pose.transforms[j].matrix().topRows<3>().transpose();
  return T;
}

Pose pose_from_matrix(const Eigen::MatrixXd& T) {
  if (T.cols() != 3 || T.rows() % 4) throw Error("pose_from_matrix: T must be 4#H x 3");
  Pose pose = identity_pose(static_cast<int>(T.rows() / 4));
  for (int j = 0; j < pose.size(); ++j) pose.transforms[j].matrix().topRows<3>() = T.block<4, 3>(4 * j, 0).transpose();
  return pose;
}

Eigen::SparseMatrix<double, Eigen::RowMajor> sparse_lbs_matrix(const Eigen::MatrixXd& V, const Eigen::MatrixXd& W) {
  if (V.rows() != W.rows()) throw Error("lbs_matrix: V and W row counts differ");
  std::vector<Eigen::Triplet<double>> trip;
  for (int i = 0; i < W.rows(); ++i)
    for (int j = 0; j < W.cols(); ++j)
      if (W(i, j) != 0.0)
        for (int c = 0; c < 4; ++c) trip.emplace_back(i, 4 * j + c, W(i, j) * (c < 3 ? V(i, c) : 1.0));
  Eigen::SparseMatrix<double, Eigen::RowMajor> M(W.rows(), 4 * W.cols());
  M.setFromTriplets(trip.begin(), trip.end());
  return M;
}

}  // namespace dfm
