#pragma once
// Closed test surfaces for mesh keys and transitions, built in code: a torus (genus 1) beside the
// icosphere of volume_test_meshes.h, and OBJ writers for hostile variants (open, NaN).
#include <cmath>
#include <fstream>
#include <string>

#include <Eigen/Core>

#include "core/mesh/mesh.h"
#include "tests/volume_test_meshes.h"

namespace dfm::test {

// Torus around the z axis through c: ring radius R, tube radius r, n x m quads split in two, outward.
inline TriMesh torus(const Eigen::Vector3d& c, double R, double r, int n, int m) {
  TriMesh t;
  t.V.resize(n * m, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      t.V.row(i * m + j) << c.x() + (R + r * std::cos(v)) * std::cos(u), c.y() + (R + r * std::cos(v)) * std::sin(u),
          c.z() + r * std::sin(v);
    }
  t.F.resize(2 * n * m, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const int a = i * m + j, b = ((i + 1) % n) * m + j, cc = ((i + 1) % n) * m + (j + 1) % m, d = i * m + (j + 1) % m;
      t.F.row(2 * (i * m + j)) << a, b, cc;
      t.F.row(2 * (i * m + j) + 1) << a, cc, d;
    }
  if (enclosed_volume(t.V, t.F) < 0) t.F.col(1).swap(t.F.col(2));
  return t;
}

// A simple OBJ (no normals), written as given: hostile variants (NaN, open) reach the reader as is.
inline void write_obj_raw(const std::string& path, const TriMesh& m) {
  std::ofstream f(path);
  f.precision(17);
  for (int i = 0; i < m.V.rows(); ++i) f << "v " << m.V(i, 0) << " " << m.V(i, 1) << " " << m.V(i, 2) << "\n";
  for (int i = 0; i < m.F.rows(); ++i) f << "f " << m.F(i, 0) + 1 << " " << m.F(i, 1) + 1 << " " << m.F(i, 2) + 1 << "\n";
}

// The mesh with its last triangle removed: a hole, so not closed.
inline TriMesh open_copy(TriMesh m) {
  m.F.conservativeResize(m.F.rows() - 1, 3);
  return m;
}

}  // namespace dfm::test
