#pragma once
// The keyed scene the space-time edit tests share (test_space_time_script, test_scene_view): an
// ellipsoid with two point handles, keyed at rest (0) and with its +x end lifted (2).
#include <algorithm>

#include "core/scene/document.h"
#include "core/scene/script.h"
#include "tests/ellipsoid_test_mesh.h"

namespace dfm::test {

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
