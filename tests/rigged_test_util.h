#pragma once
// What the rigged-import tests share: matching vertices by rest position, the bounding-box diagonal, and
// a keyed capsule to export and import again.
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/scene/document.h"
#include "core/scene/script.h"
#include "tests/volume_test_meshes.h"

namespace dfm::test {

// Per vertex of `ref`, the nearest vertex of `V` (brute force: an independent matching).
inline std::vector<int> nearest(const Eigen::MatrixXd& ref, const Eigen::MatrixXd& V) {
  std::vector<int> m(ref.rows());
  for (Eigen::Index i = 0; i < ref.rows(); ++i) (V.rowwise() - ref.row(i)).rowwise().squaredNorm().minCoeff(&m[i]);
  return m;
}

inline double diagonal(const Eigen::MatrixXd& V) { return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm(); }

// A capsule along x with a chain of three bones, weights that blend along it, keyed at 0 (rest) and at
// 1 after `turns` (script lines, e.g. "select 1\nrotate 40 0 0 1\n").
inline TriMesh keyed_capsule(Document& d, const std::string& turns) {
  TriMesh m = icosphere(Eigen::Vector3d(1.5, 0, 0), 1.0, 3);
  m.V.col(0) = (m.V.col(0).array() - 1.5) * 1.6 + 1.5;
  m.V.col(1) *= 0.4;
  m.V.col(2) *= 0.4;
  d.set_surface(m, "capsule");
  d.add_bone_chain({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(3, 0, 0)});
  Eigen::MatrixXd W(m.V.rows(), 3);
  for (int i = 0; i < m.V.rows(); ++i) {
    for (int b = 0; b < 3; ++b) W(i, b) = 1.0 / (1e-3 + std::pow(std::abs(m.V(i, 0) - (b + 0.5)), 4));
    W.row(i) /= W.row(i).sum();
  }
  d.set_weights(W, {});
  run_script(d, parse_script("set-key 0\n" + turns + "set-key 1\n", "k.txt"), "k.txt");
  return m;
}

}  // namespace dfm::test
