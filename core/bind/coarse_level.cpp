#include "core/bind/coarse_level.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include <Eigen/LU>

#include "core/bind/tetrahedralize.h"
#include "core/bind/winding_bvh.h"
#include "core/mesh/mesh_info.h"

namespace dfm {
namespace {

// Vertex neighbours in the tet graph as compressed rows (sorted, without duplicates).
void tet_graph(int n, const Eigen::MatrixXi& T, std::vector<int>& ptr, std::vector<int>& adj) {
  const std::vector<std::vector<int>> nb = vertex_neighbours(T, n);
  ptr.assign(n + 1, 0);
  adj.clear();
  for (int v = 0; v < n; ++v) {
    adj.insert(adj.end(), nb[v].begin(), nb[v].end());
    ptr[v + 1] = static_cast<int>(adj.size());
  }
}

int find_root(std::vector<int>& parent, int v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

// Constrained vertices first (all of them), then a maximal independent set of the rest: the fine index
// of each coarse point, increasing.
std::vector<int> select_coarse_points(int n, const Eigen::VectorXi& b, const std::vector<int>& ptr,
                                      const std::vector<int>& adj) {
  std::vector<char> selected(n, 0);
  for (int k = 0; k < b.size(); ++k) selected[b(k)] = 1;
  for (int v = 0; v < n; ++v) {
    if (selected[v]) continue;
    bool free_of_selected = true;
    for (int p = ptr[v]; p < ptr[v + 1] && free_of_selected; ++p) free_of_selected = !selected[adj[p]];
    if (free_of_selected) selected[v] = 1;
  }
  std::vector<int> points;
  for (int v = 0; v < n; ++v)
    if (selected[v]) points.push_back(v);
  return points;
}

// TetGen's Delaunay tetrahedralization of the points (fine indices); false when TetGen fails.
bool delaunay(const Eigen::MatrixXd& V, const std::vector<int>& points, TetgenResult& del) {
  Plc plc;
  plc.V.resize(static_cast<int>(points.size()), 3);
  for (size_t k = 0; k < points.size(); ++k) plc.V.row(static_cast<int>(k)) = V.row(points[k]);
  try {
    del = tetrahedralize(plc, "Q");
  } catch (const std::exception&) {
    return false;
  }
  return true;
}

// Carve: keep the well-shaped Delaunay tets whose centroid is inside the fine domain (V, T).
std::vector<char> carve_to_domain(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, const TetMesh& del) {
  const Eigen::MatrixXd& Vd = del.V;
  const Eigen::MatrixXi& Td = del.T;
  const Eigen::MatrixXi boundary = tet_boundary_faces(T);
  const WindingTree tree = build_winding_tree(V, boundary);
  Eigen::MatrixXd centroids(Td.rows(), 3);
  for (int t = 0; t < Td.rows(); ++t)
    centroids.row(t) = 0.25 * (Vd.row(Td(t, 0)) + Vd.row(Td(t, 1)) + Vd.row(Td(t, 2)) + Vd.row(Td(t, 3)));
  WindingAccuracy acc;
  acc.node_tolerance = 1e-2;  // only |w| > 1/2 matters: far looser (and faster) than the default
  const Eigen::VectorXd wn = winding_numbers(tree, centroids, acc);
  std::vector<char> keep(Td.rows(), 0);
  for (int t = 0; t < Td.rows(); ++t) {
    Eigen::Matrix3d J;
    for (int c = 0; c < 3; ++c) J.col(c) = (Vd.row(Td(t, c + 1)) - Vd.row(Td(t, 0))).transpose();
    const double scale = J.colwise().norm().maxCoeff();
    // Slivers would make the coarse stiffness matrix needlessly ill-conditioned; a hole is harmless here.
    keep[t] = std::abs(wn(t)) > 0.5 && J.determinant() > 1e-6 * scale * scale * scale;
  }
  return keep;
}

// Drops the kept tets of every part of the carved mesh without a constrained vertex: such a part would
// leave the coarse energy singular. fine_of: Delaunay vertex -> fine vertex (-1: none).
void drop_unanchored_parts(const Eigen::MatrixXi& Td, const std::vector<int>& fine_of, const Eigen::VectorXi& b,
                           int n, std::vector<char>& keep) {
  const int nd = static_cast<int>(fine_of.size());
  std::vector<int> bc_row(n, -1);
  for (int k = 0; k < b.size(); ++k) bc_row[b(k)] = k;
  std::vector<int> parent(nd);
  std::iota(parent.begin(), parent.end(), 0);
  for (int t = 0; t < Td.rows(); ++t)
    if (keep[t])
      for (int c = 1; c < 4; ++c) parent[find_root(parent, Td(t, c))] = find_root(parent, Td(t, 0));
  std::vector<char> anchored(nd, 0), used(nd, 0);
  for (int t = 0; t < Td.rows(); ++t)
    if (keep[t])
      for (int c = 0; c < 4; ++c) used[Td(t, c)] = 1;
  for (int d = 0; d < nd; ++d)
    if (used[d] && fine_of[d] >= 0 && bc_row[fine_of[d]] >= 0) anchored[find_root(parent, d)] = 1;
  for (int t = 0; t < Td.rows(); ++t) keep[t] = keep[t] && anchored[find_root(parent, Td(t, 0))];
}

// The kept tets and the vertices they use, numbered in tet order, into cl.V and cl.T; coarse_of:
// Delaunay vertex -> coarse vertex (-1: unused). False when no tet is kept.
bool compact_kept_tets(const TetMesh& del, const std::vector<char>& keep, CoarseLevel& cl,
                       std::vector<int>& coarse_of) {
  const Eigen::MatrixXi& Td = del.T;
  const int nd = static_cast<int>(del.V.rows());
  coarse_of.assign(nd, -1);
  int nc = 0, nt = 0;
  for (int t = 0; t < Td.rows(); ++t) {
    if (!keep[t]) continue;
    ++nt;
    for (int c = 0; c < 4; ++c)
      if (coarse_of[Td(t, c)] < 0) coarse_of[Td(t, c)] = nc++;
  }
  if (nt == 0) return false;
  cl.V.resize(nc, 3);
  for (int d = 0; d < nd; ++d)
    if (coarse_of[d] >= 0) cl.V.row(coarse_of[d]) = del.V.row(d);
  cl.T.resize(nt, 4);
  for (int t = 0, k = 0; t < Td.rows(); ++t)
    if (keep[t]) {
      for (int c = 0; c < 4; ++c) cl.T(k, c) = coarse_of[Td(t, c)];
      ++k;
    }
  return true;
}

// The constraints that survive on the coarse level into cl.b and cl.bc; false when a handle has no
// constrained coarse vertex left. coarse_of_fine: fine vertex -> coarse vertex (-1: none).
bool coarse_constraints(const Eigen::VectorXi& b, const Eigen::MatrixXd& bc, const std::vector<int>& coarse_of_fine,
                        CoarseLevel& cl) {
  std::vector<int> cb;
  std::vector<int> rows;
  for (int k = 0; k < b.size(); ++k)
    if (coarse_of_fine[b(k)] >= 0) cb.push_back(coarse_of_fine[b(k)]), rows.push_back(k);
  cl.b = Eigen::Map<Eigen::VectorXi>(cb.data(), static_cast<int>(cb.size()));
  cl.bc.resize(static_cast<int>(rows.size()), bc.cols());
  for (size_t k = 0; k < rows.size(); ++k) cl.bc.row(static_cast<int>(k)) = bc.row(rows[k]);
  for (int j = 0; j < bc.cols(); ++j)
    if (cl.bc.rows() == 0 || cl.bc.col(j).maxCoeff() <= 0) return false;
  return true;
}

// Interpolation (#fine x #coarse): a coarse vertex is itself; any other vertex has a selected neighbour
// (maximality), unless carving dropped them all (then its row stays empty: a start of 0 there).
Eigen::SparseMatrix<double> interpolation(const Eigen::MatrixXd& V, const std::vector<int>& ptr,
                                          const std::vector<int>& adj, const std::vector<int>& coarse_of_fine,
                                          int nc) {
  const int n = static_cast<int>(V.rows());
  std::vector<Eigen::Triplet<double>> trip;
  for (int v = 0; v < n; ++v) {
    if (coarse_of_fine[v] >= 0) {
      trip.emplace_back(v, coarse_of_fine[v], 1.0);
      continue;
    }
    double wsum = 0;
    const size_t first = trip.size();
    for (int p = ptr[v]; p < ptr[v + 1]; ++p) {
      const int u = adj[p];
      if (coarse_of_fine[u] < 0) continue;
      const double w = 1.0 / std::max((V.row(v) - V.row(u)).norm(), 1e-300);
      trip.emplace_back(v, coarse_of_fine[u], w);
      wsum += w;
    }
    for (size_t k = first; k < trip.size(); ++k) trip[k] = Eigen::Triplet<double>(v, trip[k].col(), trip[k].value() / wsum);
  }
  Eigen::SparseMatrix<double> P(n, nc);
  P.setFromTriplets(trip.begin(), trip.end());
  return P;
}

}  // namespace

bool build_coarse_level(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, const Eigen::VectorXi& b,
                        const Eigen::MatrixXd& bc, CoarseLevel& out, int min_vertices) {
  const int n = static_cast<int>(V.rows());
  if (n < min_vertices || T.rows() == 0 || b.size() == 0) return false;
  std::vector<int> ptr, adj;
  tet_graph(n, T, ptr, adj);
  const std::vector<int> points = select_coarse_points(n, b, ptr, adj);  // fine index of each TetGen point
  if (static_cast<int>(points.size()) < 8 || 4 * points.size() > static_cast<size_t>(n)) return false;
  TetgenResult del;
  if (!delaunay(V, points, del)) return false;

  std::vector<char> keep = carve_to_domain(V, T, del.mesh);
  const int nd = static_cast<int>(del.mesh.V.rows());
  std::vector<int> fine_of(nd, -1);  // Delaunay vertex -> fine vertex
  for (size_t k = 0; k < points.size(); ++k)
    if (del.input_to_tet(static_cast<int>(k)) >= 0) fine_of[del.input_to_tet(static_cast<int>(k))] = points[k];
  drop_unanchored_parts(del.mesh.T, fine_of, b, n, keep);

  CoarseLevel cl;
  std::vector<int> coarse_of;  // Delaunay vertex -> coarse vertex
  if (!compact_kept_tets(del.mesh, keep, cl, coarse_of)) return false;
  std::vector<int> coarse_of_fine(n, -1);
  for (int d = 0; d < nd; ++d)
    if (coarse_of[d] >= 0 && fine_of[d] >= 0) coarse_of_fine[fine_of[d]] = coarse_of[d];
  if (!coarse_constraints(b, bc, coarse_of_fine, cl)) return false;  // a handle lost on this level
  cl.P = interpolation(V, ptr, adj, coarse_of_fine, static_cast<int>(cl.V.rows()));
  out = std::move(cl);
  return true;
}

}  // namespace dfm
