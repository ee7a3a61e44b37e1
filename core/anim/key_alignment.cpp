#include "core/anim/key_alignment.h"

#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

namespace dfm {

namespace {

// Moments apart by less than this fraction of the trace count as repeated (their axes are then
// whatever rounding makes them).
constexpr double kDistinct = 0.02;

}  // namespace

SolidMoments solid_moments(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  // Tetrahedra (o, a, b, c) from o, a vertex, keep the sums well conditioned far from the origin.
  // For a tetrahedron with corners p_i (relative to o, p_0 = 0) and signed volume v:
  //   integral of y = v (sum p_i) / 4,  integral of y y^T = v / 20 (sum p_i p_i^T + (sum p_i)(sum p_i)^T).
  SolidMoments m;
  if (V.rows() == 0) return m;
  const Eigen::Vector3d o = V.row(0).transpose();
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)).transpose() - o, b = V.row(F(f, 1)).transpose() - o,
                          c = V.row(F(f, 2)).transpose() - o;
    const double v = a.dot(b.cross(c)) / 6;
    const Eigen::Vector3d s = a + b + c;
    m.volume += v;
    first += v * s / 4;
    second += v / 20 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  const Eigen::Vector3d g = first / m.volume;  // centroid relative to o
  m.centroid = o + g;
  m.second = second - m.volume * g * g.transpose();
  return m;
}

Eigen::Matrix3d principal_rotation(const Eigen::Matrix3d& M0, const Eigen::Matrix3d& M1) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> e0(M0 / M0.trace()), e1(M1 / M1.trace());
  const Eigen::Vector3d l0 = e0.eigenvalues(), l1 = e1.eigenvalues();  // ascending
  const Eigen::Matrix3d E0 = e0.eigenvectors(), E1 = e1.eigenvectors();
  const bool low = std::min(l0[1] - l0[0], l1[1] - l1[0]) > kDistinct;   // the smallest moment is alone
  const bool high = std::min(l0[2] - l0[1], l1[2] - l1[1]) > kDistinct;  // the largest is alone
  if (low && high) {
    // E1 diag(s) E0^T over the sign choices that make a rotation: the one of largest trace turns least.
    Eigen::Matrix3d best = Eigen::Matrix3d::Identity();
    double best_trace = -1e300;
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector3d s(k & 1 ? -1 : 1, k & 2 ? -1 : 1, k & 4 ? -1 : 1);
      const Eigen::Matrix3d R = E1 * s.asDiagonal() * E0.transpose();
      if (R.determinant() < 0) continue;
      if (R.trace() > best_trace) best_trace = R.trace(), best = R;
    }
    return best;
  }
  if (low || high) {
    const int i = low ? 0 : 2;
    const Eigen::Vector3d a = E0.col(i);
    Eigen::Vector3d b = E1.col(i);
    if (a.dot(b) < 0) b = -b;
    return Eigen::Quaterniond::FromTwoVectors(a, b).toRotationMatrix();
  }
  return Eigen::Matrix3d::Identity();
}

KeyPlacement key_placement(const SolidMoments& key0, const SolidMoments& key1) {
  KeyPlacement p;
  p.c0 = key0.centroid;
  p.c1 = key1.centroid;
  p.scale = std::sqrt((key1.second.trace() / key1.volume) / (key0.second.trace() / key0.volume));
  p.R = principal_rotation(key0.second, key1.second);
  return p;
}

Eigen::MatrixXd to_source_frame(const KeyPlacement& p, const Eigen::MatrixXd& X) {
  // Row form of c0 + R^T (x - c1) / scale.
  return ((X.rowwise() - p.c1.transpose()) * p.R / p.scale).rowwise() + p.c0.transpose();
}

Eigen::RowVector3d placed_at(const KeyPlacement& p, double u, const Eigen::RowVector3d& x) {
  if (u == 0) return x;
  if (u == 1) return p.c1.transpose() + p.scale * (x - p.c0.transpose()) * p.R.transpose();
  const Eigen::AngleAxisd turn(p.R);
  const Eigen::Matrix3d Ru = Eigen::AngleAxisd(u * turn.angle(), turn.axis()).toRotationMatrix();
  const double s = (1 - u) + u * p.scale;
  return (p.c0 + u * (p.c1 - p.c0)).transpose() + s * (x - p.c0.transpose()) * Ru.transpose();
}

}  // namespace dfm
