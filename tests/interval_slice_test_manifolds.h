#pragma once
// Manifolds for the interval-slice tests: a prism manifold of a sphere that moves and deforms over
// three keys (vertex times = the key times), and a transition between a sphere and a box (very many
// distinct vertex times inside its slabs).
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "core/anim/manifold.h"
#include "core/anim/transition.h"
#include "tests/volume_test_meshes.h"

namespace dfm::test {

inline AnimationManifold deforming_sphere_manifold() {
  const TriMesh s = icosphere(Eigen::Vector3d(0.1, -0.2, 0.3), 1.0, 2);
  std::vector<Eigen::MatrixXd> keys(3, s.V);
  for (int i = 0; i < s.V.rows(); ++i) {
    const Eigen::Vector3d p = s.V.row(i);
    // A twist about y and a bulge, then a shear and a shift: every edge moves differently.
    const double a = 0.9 * p.y();
    keys[1].row(i) << std::cos(a) * p.x() - std::sin(a) * p.z() + 0.3, 1.2 * p.y(),
        std::sin(a) * p.x() + std::cos(a) * p.z() + 0.1 * p.x() * p.x();
    keys[2].row(i) << p.x() + 0.4 * p.y(), 0.8 * p.y() - 0.5, 1.3 * p.z() + 0.2 * std::sin(3 * p.x());
  }
  return build_manifold(keys, s.F, {0.0, 1.0, 2.5});
}

// The same tetrahedra without the prism build's records, as a manifold made otherwise: its frames and
// interval topologies are the per-tetrahedron slice's (the path transitions take).
inline AnimationManifold without_prism_records(AnimationManifold m) {
  m.prism_slabs.clear();
  m.layer_faces.clear();
  return m;
}

inline AnimationManifold sphere_to_box_transition() {
  const TriMesh a = icosphere(Eigen::Vector3d(0, 0, 0), 0.6, 1);
  const TriMesh b = box_mesh(Eigen::Vector3d(-0.3, -0.5, -0.4), Eigen::Vector3d(0.5, 0.4, 0.3));
  return build_transition(a, 0.0, b, 1.0);
}

}  // namespace dfm::test
