#pragma once
// A smooth closed test surface without data files: the ellipsoid the space-time edit tests share
// (space_time_test_scene.h's keyed scene, test_manifold_edit's bending ellipsoid).
#include <algorithm>
#include <map>
#include <vector>

#include <Eigen/Core>

#include "core/mesh/mesh.h"

namespace dfm::test {

// An ellipsoid (x half-axis 2, y and z 1): an octahedron subdivided three times onto the sphere.
inline TriMesh ellipsoid() {
  std::vector<Eigen::Vector3d> V = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::vector<Eigen::Vector3i> F = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int level = 0; level < 3; ++level) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      V.push_back((V[a] + V[b]).normalized());
      return mid[key] = static_cast<int>(V.size()) - 1;
    };
    std::vector<Eigen::Vector3i> G;
    for (const Eigen::Vector3i& f : F) {
      const int a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
      G.push_back({f[0], a, c});
      G.push_back({a, f[1], b});
      G.push_back({c, b, f[2]});
      G.push_back({a, b, c});
    }
    F = std::move(G);
  }
  TriMesh m;
  m.V.resize(V.size(), 3);
  for (size_t i = 0; i < V.size(); ++i) m.V.row(i) = V[i].transpose().cwiseProduct(Eigen::RowVector3d(2, 1, 1));
  m.F.resize(F.size(), 3);
  for (size_t i = 0; i < F.size(); ++i) m.F.row(i) = F[i].transpose();
  return m;
}

}  // namespace dfm::test
