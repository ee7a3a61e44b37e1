#pragma once
// Regular tet grids for the weights tests: boxes of cubes, each cube split into the 6 tets around its
// main diagonal (Freudenthal/Kuhn), the same way in every cube.
#include <algorithm>
#include <array>

#include <Eigen/Dense>

#include "core/mesh/mesh.h"

namespace dfm::test {

// nx x ny x nz cubes of side h starting at the origin. Vertex (i,j,k) has index i + (nx+1)*(j + (ny+1)*k).
inline TetMesh cube_grid(int nx, int ny, int nz, double h) {
  TetMesh m;
  auto id = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  m.V.resize((nx + 1) * (ny + 1) * (nz + 1), 3);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) m.V.row(id(i, j, k)) << i * h, j * h, k * h;
  m.T.resize(6 * nx * ny * nz, 4);
  int t = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        std::array<int, 3> p = {0, 1, 2};
        do {
          std::array<int, 3> c = {i, j, k};
          int v[4];
          v[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            v[s + 1] = id(c[0], c[1], c[2]);
          }
          Eigen::Matrix3d J;
          for (int s = 0; s < 3; ++s) J.col(s) = (m.V.row(v[s + 1]) - m.V.row(v[0])).transpose();
          if (J.determinant() < 0) std::swap(v[1], v[2]);
          m.T.row(t++) << v[0], v[1], v[2], v[3];
        } while (std::next_permutation(p.begin(), p.end()));
      }
  return m;
}

}  // namespace dfm::test
