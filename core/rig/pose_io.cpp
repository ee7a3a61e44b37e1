#include "core/rig/pose_io.h"

#include <cmath>

#include "core/mesh/io.h"
#include "core/util/error.h"

namespace dfm {

std::vector<Eigen::Quaterniond> read_bone_rotations(const std::string& path, int expected_bones) {
  const Eigen::MatrixXd Q = read_dmat(path);
  int n = 0;
  bool column = false;
  if (Q.cols() == 1 && Q.rows() % 4 == 0) {
    n = static_cast<int>(Q.rows() / 4);
    column = true;
  } else if (Q.cols() == 4) {
    n = static_cast<int>(Q.rows());
  } else {
    throw file_error(path, 0, "expected a 4*#bones x 1 column or a #bones x 4 matrix of quaternions (x y z w), got " +
                                  std::to_string(Q.rows()) + " x " + std::to_string(Q.cols()));
  }
  if (expected_bones >= 0 && n != expected_bones)
    throw file_error(path, 0, "holds " + std::to_string(n) + " bone rotations but the skeleton has " +
                                  std::to_string(expected_bones) + " bones");
  std::vector<Eigen::Quaterniond> out(n);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector4d c = column ? Eigen::Vector4d(Q.block<4, 1>(4 * i, 0)) : Eigen::Vector4d(Q.row(i).transpose());
    if (!c.allFinite() || c.norm() < 1e-12)
      throw file_error(path, 0, "bone " + std::to_string(i) + ": quaternion is zero or not finite");
    out[i].coeffs() = c.normalized();  // Eigen stores (x, y, z, w) too
  }
  return out;
}

void write_bone_rotations(const std::string& path, const std::vector<Eigen::Quaterniond>& q) {
  Eigen::MatrixXd Q(4 * q.size(), 1);
  for (size_t i = 0; i < q.size(); ++i) Q.block<4, 1>(4 * i, 0) = q[i].coeffs();
  write_dmat(path, Q);
}

std::vector<Eigen::Vector3d> read_point_translations(const std::string& path, int expected_points) {
  const Eigen::MatrixXd P = read_points(path);
  if (expected_points >= 0 && P.rows() != expected_points)
    throw file_error(path, 0, "holds " + std::to_string(P.rows()) + " translations but the rig has " +
                                  std::to_string(expected_points) + " point handles");
  std::vector<Eigen::Vector3d> out(P.rows());
  for (int i = 0; i < P.rows(); ++i) out[i] = P.row(i).transpose();
  return out;
}

void write_point_translations(const std::string& path, const std::vector<Eigen::Vector3d>& t) {
  Eigen::MatrixXd P(t.size(), 3);
  for (size_t i = 0; i < t.size(); ++i) P.row(i) = t[i].transpose();
  write_points(path, P);
}


std::vector<BoneTwistStretch> read_bone_twist_stretch(const std::string& path, int bones) {
  const Eigen::MatrixXd M = read_dmat(path);
  if (M.rows() != bones || (M.cols() != 2 && M.cols() != 3))
    throw file_error(path, 0, "expected " + std::to_string(bones) + " x 2 or 3 (a row per bone: twist in degrees, stretch, " +
                                  "optionally the twist at its first joint), got " + std::to_string(M.rows()) + " x " +
                                  std::to_string(M.cols()));
  std::vector<BoneTwistStretch> out(bones);
  for (int i = 0; i < bones; ++i) {
    if (!M.row(i).allFinite()) throw file_error(path, 0, "bone " + std::to_string(i) + ": a value is not finite");
    if (!(M(i, 1) > 0)) throw file_error(path, 0, "bone " + std::to_string(i) + ": the stretch must be positive");
    out[i] = {M(i, 0) * M_PI / 180.0, M(i, 1), M.cols() == 3 ? M(i, 2) * M_PI / 180.0 : 0.0};
  }
  return out;
}
}  // namespace dfm
