#pragma once
// Synthetic frame sequences for the PCA animation tests (Alexa 2003, 7.2), and the independent
// references the tests compare with: Horn's quaternion alignment (not the production Kabsch SVD) and
// the best rank-k error from a Jacobi SVD (not the production BDCSVD).
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "core/mesh/mesh.h"

namespace dfm::test {

// A closed tube along x from -1 to 1 with an elliptic section (0.3 by 0.15): `rings` rings of
// `sides` vertices and one cap centre at each end. Outward oriented.
inline TriMesh pca_bar(int rings = 12, int sides = 6) {
  TriMesh m;
  m.V.resize(rings * sides + 2, 3);
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < sides; ++s) {
      const double a = 2 * M_PI * s / sides;
      m.V.row(r * sides + s) << -1.0 + 2.0 * r / (rings - 1), 0.3 * std::cos(a), 0.15 * std::sin(a);
    }
  const int c0 = rings * sides, c1 = c0 + 1;
  m.V.row(c0) << -1, 0, 0;
  m.V.row(c1) << 1, 0, 0;
  std::vector<Eigen::Vector3i> F;
  for (int r = 0; r + 1 < rings; ++r)
    for (int s = 0; s < sides; ++s) {
      const int a = r * sides + s, b = r * sides + (s + 1) % sides, c = a + sides, d = b + sides;
      F.push_back({a, b, d});
      F.push_back({a, d, c});
    }
  for (int s = 0; s < sides; ++s) {
    F.push_back({c0, (s + 1) % sides, s});
    F.push_back({c1, (rings - 1) * sides + s, (rings - 1) * sides + (s + 1) % sides});
  }
  m.F.resize(F.size(), 3);
  for (size_t f = 0; f < F.size(); ++f) m.F.row(f) = F[f].transpose();
  return m;
}

// The bar twisted by `twist` radians per unit length, then bent in the xy plane with curvature `bend`.
inline Eigen::MatrixXd bend_and_twist(const Eigen::MatrixXd& V, double bend, double twist) {
  Eigen::MatrixXd out(V.rows(), 3);
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    const double x = V(v, 0), ct = std::cos(twist * x), st = std::sin(twist * x);
    const double y = ct * V(v, 1) - st * V(v, 2), z = st * V(v, 1) + ct * V(v, 2);
    if (std::abs(bend) < 1e-12) {
      out.row(v) << x, y, z;
    } else {
      const double rad = 1.0 / bend, phi = bend * x;
      out.row(v) << std::sin(phi) * (rad - y), rad - std::cos(phi) * (rad - y), z;
    }
  }
  return out;
}

inline Eigen::Affine3d random_rigid(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
  Eigen::Affine3d T = Eigen::Affine3d::Identity();
  T.rotate(Eigen::AngleAxisd(2.5 * u(rng), axis));
  T.pretranslate(Eigen::Vector3d(3 * u(rng), 3 * u(rng), 3 * u(rng)));
  return T;
}

inline Eigen::MatrixXd apply(const Eigen::Affine3d& T, const Eigen::MatrixXd& V) {
  return (V * T.linear().transpose()).rowwise() + T.translation().transpose();
}

// n frames of the bar bending and twisting, each moved by its own rigid motion, plus uniform noise
// of amplitude `noise` (so every singular value of the centred, aligned frames is well above rounding).
inline std::vector<Eigen::MatrixXd> bending_bar_frames(const TriMesh& bar, int n, double noise, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::MatrixXd> frames;
  for (int i = 0; i < n; ++i) {
    const double s = static_cast<double>(i) / std::max(1, n - 1);
    Eigen::MatrixXd V = bend_and_twist(bar.V, 1.2 * std::sin(3.0 * s), 0.8 * s * s);
    for (Eigen::Index k = 0; k < V.size(); ++k) V.data()[k] += noise * u(rng);
    frames.push_back(apply(random_rigid(rng), V));
  }
  return frames;
}

// Horn (1987): the unit quaternion of the rotation M maximizing sum_v q_v . (M p_v) is the eigenvector
// of the largest eigenvalue of the symmetric 4x4 matrix built from S = sum_v p_v q_v^T. P, Q centred.
Eigen::Matrix3d horn_rotation(const Eigen::MatrixXd& P, const Eigen::MatrixXd& Q);

// The independent pipeline: each frame centred and turned onto centred frame 0 (Horn), the mean
// subtracted, frames as columns (vertex-major); its singular values by a Jacobi SVD.
struct ReferencePca {
  std::vector<Eigen::Matrix3d> rotation;  // frame i = rotation_i * aligned_i + centroid_i
  std::vector<Eigen::Vector3d> centroid;
  Eigen::MatrixXd X;                      // 3#V x n
  Eigen::VectorXd sigma;
  // sqrt(sum_{j >= k} sigma_j^2): the best rank-k error (Eckart-Young).
  double best_error(int k) const {
    return k >= sigma.size() ? 0.0 : std::sqrt(sigma.tail(sigma.size() - k).squaredNorm());
  }
};

// Defined in pca_test_frames.cpp: its SVD and eigen solver are compiled once, not in every test file.
ReferencePca reference_pca(const std::vector<Eigen::MatrixXd>& frames);

}  // namespace dfm::test
