#pragma once
// Issue 19's acceptance meshes, built in code: many non-manifold pieces, an open mesh with a small hole,
// a quad-dominant mesh (read through the OBJ reader), and separate closed pieces.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/mesh/io.h"
#include "core/mesh/mesh.h"
#include "tests/volume_test_meshes.h"

namespace dfm::test {

// 50 boxes in a 10 x 5 grid, each overlapping its neighbours (interpenetrating, as kitbashed game
// parts are), each with a fin: one triangle hung on a box edge, so that edge has three faces.
inline TriMesh fifty_finned_boxes() {
  TriMesh all;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 5; ++j) {
      const Eigen::Vector3d lo(i * 1.0, j * 1.0, 0.1 * ((i + j) % 3));
      TriMesh b = box_mesh(lo, lo + Eigen::Vector3d(1.15, 1.15, 1.0));
      b.V.conservativeResize(9, 3);
      b.V.row(8) = (lo + Eigen::Vector3d(0.5, -0.3, 0.0)).transpose();  // below the edge v0-v1 (y = lo.y, z = lo.z)
      b.F.conservativeResize(13, 3);
      b.F.row(12) << 0, 1, 8;
      all = all.V.rows() ? concat(all, b) : b;
    }
  return all;
}

// Edges with more than two faces, counted independently of the production surface report.
inline int count_nonmanifold_edges(const Eigen::MatrixXi& F) {
  std::map<std::pair<int, int>, int> n;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      ++n[{std::min(a, b), std::max(a, b)}];
    }
  int bad = 0;
  for (const auto& e : n) bad += e.second > 2;
  return bad;
}

// An icosphere (radius 1, 642 vertices) with the faces around its bottom vertex removed: a small hole
// away from the extremes (min x, max x, max y) that the handles take.
inline TriMesh sphere_with_small_hole() {
  const TriMesh s = icosphere(Eigen::Vector3d::Zero(), 1.0, 3);
  int bottom = 0;
  for (int v = 0; v < s.V.rows(); ++v)
    if (s.V(v, 2) < s.V(bottom, 2)) bottom = v;
  TriMesh m;
  m.V = s.V;
  m.F.resize(s.F.rows(), 3);
  int n = 0;
  for (int f = 0; f < s.F.rows(); ++f)
    if (s.F(f, 0) != bottom && s.F(f, 1) != bottom && s.F(f, 2) != bottom) m.F.row(n++) = s.F.row(f);
  m.F.conservativeResize(n, 3);
  return m;
}

// A bumpy box (2 x 1 x 1, n x n quads per side, non-planar) written as OBJ with quad faces, one side's
// corner quads as two triangles each, and read back through the reader (which splits the quads).
inline TriMesh quad_dominant_box(int n = 6) {
  std::map<std::tuple<int, int, int>, int> index;
  std::vector<Eigen::Vector3d> V;
  auto vertex = [&](int i, int j, int k) {
    const auto key = std::make_tuple(i, j, k);
    auto it = index.find(key);
    if (it != index.end()) return it->second;
    const double x = 2.0 * i / n, y = 1.0 * j / n, z = 1.0 * k / n;
    V.emplace_back(x, y + 0.04 * std::sin(3 * x) * std::sin(M_PI * z), z + 0.03 * std::cos(5 * y));
    return index[key] = static_cast<int>(V.size());  // OBJ is 1-based
  };
  std::ostringstream faces;
  // Side axis a (0: x, 1: y, 2: z) at coordinate s in {0, n}; (u, v) run over the other two axes.
  for (int a = 0; a < 3; ++a)
    for (int s : {0, n}) {
      const int u_ax = (a + 1) % 3, v_ax = (a + 2) % 3;
      for (int u = 0; u < n; ++u)
        for (int v = 0; v < n; ++v) {
          int c[4];
          const int du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
          for (int q = 0; q < 4; ++q) {
            int ijk[3];
            ijk[a] = s, ijk[u_ax] = u + du[q], ijk[v_ax] = v + dv[q];
            c[q] = vertex(ijk[0], ijk[1], ijk[2]);
          }
          if (s == 0) std::swap(c[1], c[3]);  // outward on the low side
          const bool corner = a == 2 && s == n && (u == 0 || u == n - 1) && (v == 0 || v == n - 1);
          if (corner)
            faces << "f " << c[0] << ' ' << c[1] << ' ' << c[2] << "\nf " << c[0] << ' ' << c[2] << ' ' << c[3] << '\n';
          else
            faces << "f " << c[0] << ' ' << c[1] << ' ' << c[2] << ' ' << c[3] << '\n';
        }
    }
  const std::string path = (std::filesystem::temp_directory_path() / "dfm_quad_dominant_box.obj").string();
  {
    std::ofstream f(path);
    for (const Eigen::Vector3d& p : V) f << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    f << faces.str();
  }
  TriMesh m = read_surface(path);
  std::filesystem::remove(path);
  return m;
}

// Three closed spheres (162 vertices each) on the x axis, 3 apart.
inline TriMesh three_spheres() {
  TriMesh m = icosphere(Eigen::Vector3d(0, 0, 0), 1.0, 2);
  m = concat(m, icosphere(Eigen::Vector3d(3, 0, 0), 1.0, 2));
  return concat(m, icosphere(Eigen::Vector3d(6, 0.5, 0), 1.0, 2));
}

}  // namespace dfm::test
