#pragma once
// A flat strip that is mirror-symmetric across x = 0 (vertices and triangles), with five point handles
// on its vertices and smooth weights made here, for the weight tools' tests. Every triangle is a right
// isosceles one, so the cotangent weights are >= 0 (the clamp in surface_laplacian.h changes nothing).
#include <algorithm>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "core/mesh/mesh.h"
#include "core/rig/rig.h"

namespace dfm::test {

constexpr int kStripNx = 20, kStripNy = 6;  // intervals; spacing 0.1 over [-1, 1] x [0, 0.6]
inline int strip_vertex(int i, int j) { return i + (kStripNx + 1) * j; }
// The vertex at the mirror position (x -> -x).
inline int strip_mirror_vertex(int v) { return strip_vertex(kStripNx - v % (kStripNx + 1), v / (kStripNx + 1)); }

inline TriMesh mirror_strip() {
  TriMesh m;
  m.V.resize((kStripNx + 1) * (kStripNy + 1), 3);
  for (int j = 0; j <= kStripNy; ++j)
    for (int i = 0; i <= kStripNx; ++i) m.V.row(strip_vertex(i, j)) << 0.1 * (i - kStripNx / 2), 0.1 * j, 0;  // x exactly odd in i
  m.F.resize(2 * kStripNx * kStripNy, 3);
  int f = 0;
  for (int j = 0; j < kStripNy; ++j)
    for (int i = 0; i < kStripNx; ++i) {
      const int a = strip_vertex(i, j), b = strip_vertex(i + 1, j), c = strip_vertex(i, j + 1), d = strip_vertex(i + 1, j + 1);
      // The left half's diagonals mirror the right half's.
      if (i < kStripNx / 2) {
        m.F.row(f++) << a, b, d;
        m.F.row(f++) << a, d, c;
      } else {
        m.F.row(f++) << a, b, c;
        m.F.row(f++) << b, d, c;
      }
    }
  return m;
}

// Five point handles on strip vertices (x = -0.8 -0.4 0 0.4 0.8, y = 0.3): 0 and 4 are mirrors by
// name, 1 and 3 by position only, 2 lies on the plane.
inline Rig strip_rig() {
  Rig r;
  const double xs[5] = {-0.8, -0.4, 0, 0.4, 0.8};
  const char* names[5] = {"r_outer", "", "center", "", "l_outer"};
  for (int h = 0; h < 5; ++h) r.points.push_back({Eigen::Vector3d(xs[h], 0.3, 0), names[h]});
  return r;
}
inline int strip_handle_vertex(int h) { return strip_vertex(2 + 4 * h, 3); }
inline const int kStripHandleMirror[5] = {4, 3, 2, 1, 0};

// Weights that fall off with distance from each handle (up to 5 nonzeros per row), 1 at the own
// handle's vertex (as a bind fixes them), rows summing to 1. asymmetry > 0 tilts them so they are no
// longer mirror-symmetric.
inline Eigen::MatrixXd strip_weights(const TriMesh& m, const Rig& rig, double asymmetry = 0) {
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(m.num_vertices(), rig.points.size());
  for (int v = 0; v < m.num_vertices(); ++v) {
    const Eigen::Vector3d p = m.V.row(v).transpose();
    for (size_t h = 0; h < rig.points.size(); ++h) {
      const Eigen::Vector3d d = p - rig.points[h].position;
      const double r = std::sqrt(d.x() * d.x() + 0.5 * d.y() * d.y());
      const double f = std::max(0.0, 1 - r / 0.9);
      W(v, h) = f * f * (1 + asymmetry * std::sin(3 * p.x() + 1 + h));
    }
    W.row(v) /= W.row(v).sum();
  }
  for (size_t h = 0; h < rig.points.size(); ++h) {
    W.row(strip_handle_vertex(static_cast<int>(h))).setZero();
    W(strip_handle_vertex(static_cast<int>(h)), h) = 1;
  }
  return W;
}

// Independent references, written from the definitions.
// Dirichlet energy sum_j integral |grad w_j|^2 of piecewise-linear columns (Jacobson 2013, 2.1).
inline double dirichlet_energy(const TriMesh& m, const Eigen::MatrixXd& W) {
  double e = 0;
  for (int f = 0; f < m.num_faces(); ++f) {
    Eigen::Matrix<double, 3, 2> E;
    E.col(0) = (m.V.row(m.F(f, 1)) - m.V.row(m.F(f, 0))).transpose();
    E.col(1) = (m.V.row(m.F(f, 2)) - m.V.row(m.F(f, 0))).transpose();
    const Eigen::Matrix2d G = E.transpose() * E;
    const double area = 0.5 * std::sqrt(G.determinant());
    for (int j = 0; j < W.cols(); ++j) {
      const Eigen::Vector2d dw(W(m.F(f, 1), j) - W(m.F(f, 0), j), W(m.F(f, 2), j) - W(m.F(f, 0), j));
      const Eigen::Vector3d grad = E * G.inverse() * dw;
      e += area * grad.squaredNorm();
    }
  }
  return e;
}

// Sum over the mesh's edges (each once) of |w_a - w_b|^2, over every column.
inline double edge_energy(const TriMesh& m, const Eigen::MatrixXd& W) {
  std::set<std::pair<int, int>> edges;
  for (int f = 0; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = m.F(f, k), b = m.F(f, (k + 1) % 3);
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  double e = 0;
  for (auto [a, b] : edges) e += (W.row(a) - W.row(b)).squaredNorm();
  return e;
}

}  // namespace dfm::test
