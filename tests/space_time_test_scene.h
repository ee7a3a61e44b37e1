#pragma once
// The keyed scene the space-time edit tests share (test_space_time_script, test_scene_view): an
// ellipsoid with two point handles, keyed at rest (0) and with its +x end lifted (2).
#include <algorithm>
#include <map>
#include <vector>

#include "core/scene/document.h"
#include "core/scene/script.h"

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

// Two points at the ends, weights a smoothstep in x; keys: rest at 0, the +x end lifted 0.6 at 2.
inline void make_keyed(Document& d) {
  const TriMesh m = ellipsoid();
  d.set_surface(m, "ellipsoid");
  d.add_point({-1.5, 0, 0});
  d.add_point({1.5, 0, 0});
  Eigen::MatrixXd W(m.V.rows(), 2);
  for (int i = 0; i < m.V.rows(); ++i) {
    const double s = std::clamp((m.V(i, 0) + 2) / 4, 0.0, 1.0), w = s * s * (3 - 2 * s);
    W.row(i) << 1 - w, w;
  }
  d.set_weights(W, {});
  run_script(d, parse_script("set-key 0\nselect 1\ntranslate 0 0.6 0\nset-key 2\nreset-pose\n", "k.txt"), "k.txt");
}

}  // namespace dfm::test
