#pragma once
// Small analytic meshes for the volume tests (cube, icosphere), built in code, and the references
// measured on them (enclosed volume, area-weighted normals).
#include <array>
#include <cmath>
#include <map>
#include <vector>
#include <utility>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/mesh/mesh.h"

namespace dfm::test {

// Axis-aligned box [lo, hi], 12 outward triangles.
inline TriMesh box_mesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  TriMesh m;
  m.V.resize(8, 3);
  for (int c = 0; c < 8; ++c)
    for (int k = 0; k < 3; ++k) m.V(c, k) = ((c >> k) & 1) ? hi(k) : lo(k);
  m.F.resize(12, 3);
  m.F << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5;
  return m;
}

// Icosphere of radius r around c, `levels` subdivisions, outward.
// Vertices 0..5: +x -x +y -y +z -z; faces outward.
inline TriMesh octahedron() {
  TriMesh m;
  m.V.resize(6, 3);
  m.V << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
  m.F.resize(8, 3);
  m.F << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  return m;
}

inline TriMesh icosphere(const Eigen::Vector3d& c, double r, int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> V = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                    {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> F = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                       {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                       {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (auto& v : V) v.normalize();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      V.push_back((V[a] + V[b]).normalized());
      return mid[key] = static_cast<int>(V.size()) - 1;
    };
    std::vector<std::array<int, 3>> G;
    for (auto& f : F) {
      int a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), cc = midpoint(f[2], f[0]);
      G.push_back({f[0], a, cc});
      G.push_back({f[1], b, a});
      G.push_back({f[2], cc, b});
      G.push_back({a, b, cc});
    }
    F = G;
  }
  TriMesh m;
  m.V.resize(V.size(), 3);
  for (size_t i = 0; i < V.size(); ++i) m.V.row(i) = (c + r * V[i]).transpose();
  m.F.resize(F.size(), 3);
  for (size_t i = 0; i < F.size(); ++i) m.F.row(i) << F[i][0], F[i][1], F[i][2];
  return m;
}

// Signed enclosed volume (divergence theorem).
inline double enclosed_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  double s = 0;
  for (int f = 0; f < F.rows(); ++f)
  {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    s += a.dot(b.cross(c));
  }
  return s / 6.0;
}

inline double tet_mesh_volume(const TetMesh& m, double* min_volume = nullptr) {
  double s = 0, mn = 1e300;
  for (int t = 0; t < m.T.rows(); ++t) {
    Eigen::Vector3d a = m.V.row(m.T(t, 0)), b = m.V.row(m.T(t, 1)), c = m.V.row(m.T(t, 2)), d = m.V.row(m.T(t, 3));
    double v = (b - a).cross(c - a).dot(d - a) / 6.0;
    s += v;
    mn = std::min(mn, v);
  }
  if (min_volume) *min_volume = mn;
  return s;
}

// Two meshes as one (pieces side by side).
inline TriMesh concat(const TriMesh& a, const TriMesh& b) {
  TriMesh m;
  m.V.resize(a.V.rows() + b.V.rows(), 3);
  m.V << a.V, b.V;
  m.F.resize(a.F.rows() + b.F.rows(), 3);
  m.F << a.F, (b.F.array() + static_cast<int>(a.V.rows())).matrix();
  return m;
}

// Area-weighted unit vertex normals of a triangle mesh (the reference the normals tests compare with).
inline Eigen::MatrixXd area_weighted_normals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(V.rows(), 3);
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    for (int j = 0; j < 3; ++j) N.row(F(f, j)) += (b - a).cross(c - a).transpose();
  }
  N.rowwise().normalize();
  return N;
}

}  // namespace dfm::test
