#pragma once
// A closed capsule (the cigar of Jacobson 2013, Fig. 7.7) for the additional-weights tests.
#include <cmath>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/mesh/mesh.h"

namespace dfm::test {

// A closed capsule along x: cylinder |x| <= a of radius r, hemispherical caps, poles on the axis.
inline TriMesh capsule(double a, double r, int cap_rings, int body_rings, int around) {
  std::vector<std::pair<double, double>> profile;  // (x, radius), pole to pole
  for (int i = 1; i <= cap_rings; ++i) {
    const double t = 0.5 * M_PI * i / cap_rings;
    profile.push_back({-a - r * std::cos(t), r * std::sin(t)});
  }
  for (int i = 1; i < body_rings; ++i) profile.push_back({-a + 2 * a * i / body_rings, r});
  for (int i = cap_rings; i >= 1; --i) {
    const double t = 0.5 * M_PI * i / cap_rings;
    profile.push_back({a + r * std::cos(t), r * std::sin(t)});
  }
  const int rings = static_cast<int>(profile.size());
  TriMesh m;
  m.V.resize(rings * around + 2, 3);
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < around; ++j) {
      const double phi = 2 * M_PI * j / around;
      m.V.row(i * around + j) << profile[i].first, profile[i].second * std::cos(phi), profile[i].second * std::sin(phi);
    }
  const int south = rings * around, north = south + 1;
  m.V.row(south) << -a - r, 0, 0;
  m.V.row(north) << a + r, 0, 0;
  std::vector<Eigen::Vector3i> F;
  for (int j = 0; j < around; ++j) {
    const int j1 = (j + 1) % around;
    F.push_back({south, j1, j});
    for (int i = 0; i + 1 < rings; ++i) {
      const int p = i * around, q = (i + 1) * around;
      F.push_back({p + j, p + j1, q + j1});
      F.push_back({p + j, q + j1, q + j});
    }
    F.push_back({north, (rings - 1) * around + j, (rings - 1) * around + j1});
  }
  m.F.resize(F.size(), 3);
  for (size_t f = 0; f < F.size(); ++f) m.F.row(f) = F[f].transpose();
  return m;
}

}  // namespace dfm::test
