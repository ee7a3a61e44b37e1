#pragma once
// Meshes for the sculpt tests: a flat disk of concentric rings (ring k at radius k h holds 6k vertices,
// neighbouring rings zipped by angle), so every multiple of h is a ring of vertices at exactly that radius
// and region boundaries r = a, r = b fall on rings at every resolution.
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "core/mesh/mesh.h"

namespace dfm::test {

inline TriMesh ring_disk(double h, int rings) {
  std::vector<Eigen::RowVector3d> P{Eigen::RowVector3d::Zero()};
  std::vector<int> first{0};  // index of each ring's first vertex
  for (int k = 1; k <= rings; ++k) {
    first.push_back(static_cast<int>(P.size()));
    for (int j = 0; j < 6 * k; ++j) {
      const double th = 2 * M_PI * j / (6 * k);
      P.emplace_back(k * h * std::cos(th), k * h * std::sin(th), 0.0);
    }
  }
  std::vector<Eigen::RowVector3i> T;
  for (int j = 0; j < 6; ++j) T.emplace_back(0, 1 + j, 1 + (j + 1) % 6);
  for (int k = 1; k < rings; ++k) {
    const int n1 = 6 * k, n2 = 6 * (k + 1);
    auto A = [&](int i) { return first[k] + i % n1; };
    auto B = [&](int j) { return first[k + 1] + j % n2; };
    int i = 0, j = 0;
    while (i < n1 || j < n2) {
      const double a = double(i + 1) / n1, b = double(j + 1) / n2;  // next angles, in turns
      if (j >= n2 || (i < n1 && a < b)) T.emplace_back(A(i), B(j), A(i + 1)), ++i;
      else T.emplace_back(A(i), B(j), B(j + 1)), ++j;
    }
  }
  TriMesh m;
  m.V.resize(static_cast<Eigen::Index>(P.size()), 3);
  for (size_t i = 0; i < P.size(); ++i) m.V.row(static_cast<Eigen::Index>(i)) = P[i];
  m.F.resize(static_cast<Eigen::Index>(T.size()), 3);
  for (size_t f = 0; f < T.size(); ++f) m.F.row(static_cast<Eigen::Index>(f)) = T[f];
  return m;
}

// Vertices with radius in [lo, hi] (a half-step tolerance so ring radii count exactly).
inline std::vector<int> ring_band(const TriMesh& m, double lo, double hi, double h) {
  std::vector<int> out;
  for (int i = 0; i < m.V.rows(); ++i) {
    const double r = m.V.row(i).head<2>().norm();
    if (r > lo - 0.25 * h && r < hi + 0.25 * h) out.push_back(i);
  }
  return out;
}

}  // namespace dfm::test
