#pragma once
// Checks of transition slices written independently of the production code (point-to-triangle
// distance, Euler characteristic); the test surfaces come from key_mesh_test_meshes.h.
#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/mesh/mesh.h"
#include "tests/key_mesh_test_meshes.h"
#include "tests/volume_test_meshes.h"

namespace dfm::test {

// V - E + F of a triangle list.
inline int euler_characteristic(const Eigen::MatrixXi& F) {
  std::vector<std::pair<int, int>> edges;
  std::vector<int> verts;
  for (int f = 0; f < F.rows(); ++f)
    for (int j = 0; j < 3; ++j) {
      const int a = F(f, j), b = F(f, (j + 1) % 3);
      edges.push_back({std::min(a, b), std::max(a, b)});
      verts.push_back(a);
    }
  std::sort(edges.begin(), edges.end());
  std::sort(verts.begin(), verts.end());
  const long e = std::unique(edges.begin(), edges.end()) - edges.begin();
  const long v = std::unique(verts.begin(), verts.end()) - verts.begin();
  return static_cast<int>(v - e + F.rows());
}

// Distance from p to triangle (a, b, c) (Ericson, Real-Time Collision Detection, 5.1.5).
inline double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                      const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * vb * denom + ac * vc * denom)).norm();
}

// Largest distance from the points to the surface (a uniform grid of triangle boxes).
inline double max_distance_to_surface(const Eigen::MatrixXd& P, const TriMesh& S) {
  const Eigen::RowVector3d lo = S.V.colwise().minCoeff(), hi = S.V.colwise().maxCoeff();
  const int g = 32;
  const Eigen::RowVector3d cell = (hi - lo) / g;
  auto index = [&](const Eigen::RowVector3d& p, int k) {
    return std::clamp(static_cast<int>(std::floor((p[k] - lo[k]) / cell[k])), 0, g - 1);
  };
  std::vector<std::vector<int>> grid(g * g * g);
  const double pad = 1e-9 * (hi - lo).norm();
  for (int f = 0; f < S.F.rows(); ++f) {
    Eigen::RowVector3d a = S.V.row(S.F(f, 0)), b = a;
    for (int j = 1; j < 3; ++j) a = a.cwiseMin(S.V.row(S.F(f, j))), b = b.cwiseMax(S.V.row(S.F(f, j)));
    a.array() -= pad;
    b.array() += pad;
    for (int x = index(a, 0); x <= index(b, 0); ++x)
      for (int y = index(a, 1); y <= index(b, 1); ++y)
        for (int z = index(a, 2); z <= index(b, 2); ++z) grid[(x * g + y) * g + z].push_back(f);
  }
  double worst = 0;
  for (int i = 0; i < P.rows(); ++i) {
    const Eigen::RowVector3d p = P.row(i);
    double best = 1e300;
    for (int f : grid[(index(p, 0) * g + index(p, 1)) * g + index(p, 2)])
      best = std::min(best, point_triangle_distance(p.transpose(), S.V.row(S.F(f, 0)).transpose(),
                                                    S.V.row(S.F(f, 1)).transpose(), S.V.row(S.F(f, 2)).transpose()));
    worst = std::max(worst, best);
  }
  return worst;
}

// The mesh scaled uniformly and centred into the box [-0.5, 0.5]^3.
inline TriMesh into_unit_box(TriMesh m) {
  const Eigen::RowVector3d lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
  const double s = (hi - lo).maxCoeff();
  m.V = ((m.V.rowwise() - 0.5 * (lo + hi)) / s).eval();
  return m;
}

}  // namespace dfm::test
