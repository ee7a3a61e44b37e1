#include "core/bind/robust_volume.h"
#include "core/mesh/mesh_info.h"

#include <algorithm>
#include <array>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <unordered_map>

#include "core/bind/parallel_for.h"

namespace dfm {

std::string SurfaceReport::describe() const {
  std::string s;
  auto add = [&](int n, const char* what) {
    if (n) s += (s.empty() ? "" : ", ") + std::to_string(n) + " " + what;
  };
  add(boundary_edges, "boundary edges (open)");
  add(nonmanifold_edges, "non-manifold edges");
  add(inconsistent_edges, "inconsistently oriented edges");
  add(degenerate_faces, "degenerate faces");
  add(duplicate_vertices, "duplicate vertices");
  add(unreferenced_vertices, "unreferenced vertices");
  if (s.empty()) s = "closed manifold";
  return s + "; " + std::to_string(components) + (components == 1 ? " piece" : " pieces");
}

WeldedSurface weld_surface(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  WeldedSurface w;
  const int n = static_cast<int>(V.rows());
  std::map<std::array<double, 3>, int> first;
  w.user_to_welded.resize(n);
  std::vector<int> keep;
  for (int i = 0; i < n; ++i) {
    auto [it, fresh] = first.emplace(std::array<double, 3>{V(i, 0) + 0.0, V(i, 1) + 0.0, V(i, 2) + 0.0},
                                     static_cast<int>(keep.size()));
    if (fresh) keep.push_back(i);
    else ++w.report.duplicate_vertices;
    w.user_to_welded(i) = it->second;
  }
  w.V.resize(keep.size(), 3);
  for (size_t i = 0; i < keep.size(); ++i) w.V.row(i) = V.row(keep[i]);

  std::vector<std::array<int, 3>> faces;
  for (int f = 0; f < F.rows(); ++f) {
    std::array<int, 3> t{w.user_to_welded(F(f, 0)), w.user_to_welded(F(f, 1)), w.user_to_welded(F(f, 2))};
    const Eigen::Vector3d a = w.V.row(t[0]), b = w.V.row(t[1]), c = w.V.row(t[2]);
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || (b - a).cross(c - a).squaredNorm() == 0) {
      ++w.report.degenerate_faces;
      continue;
    }
    faces.push_back(t);
  }
  w.F.resize(faces.size(), 3);
  for (size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) w.F(f, k) = faces[f][k];

  // Edge incidence: count faces per undirected edge, and directed uses for orientation.
  std::map<std::pair<int, int>, std::array<int, 2>> edges;  // (min,max) -> {uses a->b as min->max, other}
  for (const auto& t : faces)
    for (int k = 0; k < 3; ++k) {
      int a = t[k], b = t[(k + 1) % 3];
      auto& e = edges[{std::min(a, b), std::max(a, b)}];
      ++e[a < b ? 0 : 1];
    }
  for (const auto& [key, e] : edges) {
    const int total = e[0] + e[1];
    if (total == 1) ++w.report.boundary_edges;
    else if (total > 2) ++w.report.nonmanifold_edges;
    else if (e[0] != 1) ++w.report.inconsistent_edges;
  }
  // Pieces and unreferenced vertices (union-find over face corners).
  std::vector<int> parent(w.V.rows());
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> root = [&](int x) { return parent[x] == x ? x : parent[x] = root(parent[x]); };
  std::vector<char> used(w.V.rows(), 0);
  for (const auto& t : faces) {
    for (int k = 0; k < 3; ++k) used[t[k]] = 1;
    parent[root(t[1])] = root(t[0]);
    parent[root(t[2])] = root(t[0]);
  }
  for (int i = 0; i < w.V.rows(); ++i) {
    if (!used[i]) ++w.report.unreferenced_vertices;
    else if (root(i) == i) ++w.report.components;
  }
  return w;
}

TetMesh compact_tet_mesh(const TetMesh& tets, Eigen::VectorXi& old_to_new) {
  std::vector<char> used(tets.V.rows(), 0);
  for (int t = 0; t < tets.T.rows(); ++t)
    for (int k = 0; k < 4; ++k) used[tets.T(t, k)] = 1;
  old_to_new = Eigen::VectorXi::Constant(tets.V.rows(), -1);
  int n = 0;
  for (int i = 0; i < tets.V.rows(); ++i)
    if (used[i]) old_to_new(i) = n++;
  TetMesh out;
  out.V.resize(n, 3);
  for (int i = 0; i < tets.V.rows(); ++i)
    if (used[i]) out.V.row(old_to_new(i)) = tets.V.row(i);
  out.T.resize(tets.T.rows(), 4);
  for (int t = 0; t < tets.T.rows(); ++t)
    for (int k = 0; k < 4; ++k) out.T(t, k) = old_to_new(tets.T(t, k));
  return out;
}

Eigen::MatrixXd tet_centroids(const TetMesh& tets) {
  Eigen::MatrixXd C(tets.T.rows(), 3);
  for (int t = 0; t < tets.T.rows(); ++t)
    C.row(t) = 0.25 * (tets.V.row(tets.T(t, 0)) + tets.V.row(tets.T(t, 1)) + tets.V.row(tets.T(t, 2)) + tets.V.row(tets.T(t, 3)));
  return C;
}

namespace {

Eigen::Vector4d barycentric(const TetMesh& m, int t, const Eigen::Vector3d& p) {
  const Eigen::Vector3d a = m.V.row(m.T(t, 0));
  Eigen::Matrix3d E;
  for (int k = 0; k < 3; ++k) E.col(k) = m.V.row(m.T(t, k + 1)).transpose() - a;
  const Eigen::Vector3d l = E.partialPivLu().solve(p - a);
  return Eigen::Vector4d(1 - l.sum(), l(0), l(1), l(2));
}

// Closest point of a tet to p, as clamped barycentric coordinates (projection onto faces approximated
// by clamping and renormalizing, then refined by the true distance below).
double distance_to_tet(const TetMesh& m, int t, const Eigen::Vector3d& p, Eigen::Vector4d& bary) {
  bary = barycentric(m, t, p);
  if (!bary.allFinite()) bary = Eigen::Vector4d::Constant(0.25);
  if (bary.minCoeff() >= -1e-12) return 0;
  Eigen::Vector4d c = bary.cwiseMax(0.0);
  c /= c.sum();
  Eigen::Vector3d q = Eigen::Vector3d::Zero();
  for (int k = 0; k < 4; ++k) q += c(k) * m.V.row(m.T(t, k)).transpose();
  bary = c;
  return (q - p).norm();
}

}  // namespace

Eigen::SparseMatrix<double> tet_interpolation(const TetMesh& m, const Eigen::MatrixXd& P) {
  // A uniform grid over the tets' boxes; each query scans cells outward until nothing closer can exist.
  const int nt = static_cast<int>(m.T.rows());
  Eigen::SparseMatrix<double> W(P.rows(), m.V.rows());
  if (nt == 0 || P.rows() == 0) return W;
  const Eigen::RowVector3d lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
  const double cells = std::max(1.0, std::cbrt(static_cast<double>(nt)));
  const double h = std::max((hi - lo).maxCoeff() / cells, 1e-300);
  const Eigen::Array3i dims = (((hi - lo).array() / h).floor().cast<int>() + 1).transpose();
  std::vector<std::vector<int>> grid(static_cast<size_t>(dims.prod()));
  auto cell_of = [&](const Eigen::Vector3d& x) {
    Eigen::Array3i c = ((x.transpose() - lo).array() / h).floor().cast<int>().transpose();
    return c.max(0).min(dims - 1).eval();
  };
  auto id = [&](const Eigen::Array3i& c) { return (static_cast<size_t>(c(2)) * dims(1) + c(1)) * dims(0) + c(0); };
  for (int t = 0; t < nt; ++t) {
    Eigen::Vector3d tl = m.V.row(m.T(t, 0)).transpose(), th = tl;
    for (int k = 1; k < 4; ++k) {
      tl = tl.cwiseMin(m.V.row(m.T(t, k)).transpose());
      th = th.cwiseMax(m.V.row(m.T(t, k)).transpose());
    }
    const Eigen::Array3i a = cell_of(tl), b = cell_of(th);
    for (int z = a(2); z <= b(2); ++z)
      for (int y = a(1); y <= b(1); ++y)
        for (int x = a(0); x <= b(0); ++x) grid[id({x, y, z})].push_back(t);
  }
  std::vector<std::array<std::pair<int, double>, 4>> rows(P.rows());
  parallel_for(static_cast<int>(P.rows()), 0, [&](int i) {
    const Eigen::Vector3d p = P.row(i).transpose();
    const Eigen::Array3i c = cell_of(p);
    // Distance from p to the clamped cell grid: rings closer than the best distance must be searched.
    double best = std::numeric_limits<double>::infinity();
    int best_t = -1;
    Eigen::Vector4d best_b;
    const int max_ring = dims.maxCoeff();
    for (int r = 0; r <= max_ring; ++r) {
      for (int z = c(2) - r; z <= c(2) + r; ++z)
        for (int y = c(1) - r; y <= c(1) + r; ++y)
          for (int x = c(0) - r; x <= c(0) + r; ++x) {
            if (std::max({std::abs(x - c(0)), std::abs(y - c(1)), std::abs(z - c(2))}) != r) continue;
            if (x < 0 || y < 0 || z < 0 || x >= dims(0) || y >= dims(1) || z >= dims(2)) continue;
            for (int t : grid[id({x, y, z})]) {
              Eigen::Vector4d bb;
              const double d = distance_to_tet(m, t, p, bb);
              if (d < best || (d == best && bb.minCoeff() > best_b.minCoeff())) best = d, best_t = t, best_b = bb;
            }
          }
      // Points within ring r of p's (clamped) cell are all searched once r * h exceeds the best distance
      // measured from the cell box; outside the grid the offset adds at most the distance to the box.
      const Eigen::Vector3d clamped = p.cwiseMax(lo.transpose()).cwiseMin(hi.transpose());
      if (best_t >= 0 && r * h >= best + (p - clamped).norm()) break;
    }
    for (int k = 0; k < 4; ++k) rows[i][k] = {m.T(best_t, k), best_b(k)};
  });
  std::vector<Eigen::Triplet<double>> trip;
  for (int i = 0; i < P.rows(); ++i)
    for (const auto& [v, w] : rows[i])
      if (w > 0) trip.emplace_back(i, v, w);
  W.setFromTriplets(trip.begin(), trip.end());
  return W;
}

int tet_vertex_components(const TetMesh& tets, Eigen::VectorXi& comp) {
  std::vector<int> parent(tets.V.rows());
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> root = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  comp = Eigen::VectorXi::Constant(tets.V.rows(), -1);
  for (int t = 0; t < tets.T.rows(); ++t)
    for (int k = 1; k < 4; ++k) parent[root(tets.T(t, k))] = root(tets.T(t, 0));
  std::vector<char> used(tets.V.rows(), 0);
  for (int t = 0; t < tets.T.rows(); ++t)
    for (int k = 0; k < 4; ++k) used[tets.T(t, k)] = 1;
  std::unordered_map<int, int> ids;
  for (int i = 0; i < tets.V.rows(); ++i)
    if (used[i]) comp(i) = ids.emplace(root(i), static_cast<int>(ids.size())).first->second;
  return static_cast<int>(ids.size());
}

}  // namespace dfm
