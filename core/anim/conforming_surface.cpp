#include "core/anim/conforming_surface.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <unordered_map>

#include <Eigen/Geometry>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include "core/bind/winding_bvh.h"
#include "core/util/error.h"

namespace dfm {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, K>;
using Tds = CGAL::Triangulation_data_structure_3<Vb>;
using Delaunay3 = CGAL::Delaunay_triangulation_3<K, Tds>;

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}

// One round: the triangles of s missing from the Delaunay tetrahedralization of s.V. Where a
// missing triangle and its neighbour are coplanar (co-circular points: the Delaunay tetrahedralization
// chose the other diagonal) the surface takes the other diagonal, which changes no geometry;
// elsewhere the triangle's longest edge missing from the tetrahedralization is split (else its
// longest edge). Returns the number of triangles that were missing; with fix false it only counts.
int conform_round(ConformingSurface& s, bool fix, std::vector<int>* missing_rows = nullptr) {
  const int n = static_cast<int>(s.V.rows()), ni = static_cast<int>(s.interior.rows());
  std::vector<std::pair<K::Point_3, int>> pts;
  pts.reserve(n + ni);
  for (int i = 0; i < n; ++i) pts.push_back({K::Point_3(s.V(i, 0), s.V(i, 1), s.V(i, 2)), i});
  for (int i = 0; i < ni; ++i) pts.push_back({K::Point_3(s.interior(i, 0), s.interior(i, 1), s.interior(i, 2)), n + i});
  Delaunay3 dt(pts.begin(), pts.end());
  std::vector<Delaunay3::Vertex_handle> vh(n + ni);
  int found = 0;
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v, ++found) vh[v->info()] = v;
  if (found != n + ni) throw Error("two surface vertices are at the same position");
  std::unordered_map<std::uint64_t, std::vector<int>> faces_of;
  for (int f = 0; f < s.F.rows(); ++f)
    for (int j = 0; j < 3; ++j) faces_of[edge_key(s.F(f, j), s.F(f, (j + 1) % 3))].push_back(f);
  Delaunay3::Cell_handle c;
  int i, j, k;
  auto is_edge = [&](int a, int b) { return dt.is_edge(vh[a], vh[b], c, i, j); };
  auto point = [&](int v) { return pts[v].first; };
  std::vector<char> changed(s.F.rows(), 0);
  std::vector<std::pair<int, int>> split;
  int missing = 0;
  for (int f = 0; f < s.F.rows(); ++f) {
    if (dt.is_facet(vh[s.F(f, 0)], vh[s.F(f, 1)], vh[s.F(f, 2)], c, i, j, k)) continue;
    ++missing;
    if (missing_rows) missing_rows->push_back(f);
    if (!fix || changed[f]) continue;
    bool flipped = false;
    for (int e = 0; e < 3 && !flipped; ++e) {
      const int a = s.F(f, e), b = s.F(f, (e + 1) % 3), cc = s.F(f, (e + 2) % 3);
      const auto& around = faces_of[edge_key(a, b)];
      if (around.size() != 2) continue;
      const int g = around[0] == f ? around[1] : around[0];
      if (changed[g]) continue;
      int d = -1;
      for (int t = 0; t < 3; ++t)
        if (s.F(g, t) != a && s.F(g, t) != b) d = s.F(g, t);
      if (CGAL::orientation(point(a), point(b), point(cc), point(d)) != CGAL::COPLANAR || !is_edge(cc, d)) continue;
      s.F.row(f) << a, d, cc;  // the quad a d b cc, split by cc -- d
      s.F.row(g) << d, b, cc;
      changed[f] = changed[g] = 1;
      flipped = true;
    }
    if (flipped) continue;
    int best = -1, best_missing = -1;
    double len = -1, len_missing = -1;
    for (int e = 0; e < 3; ++e) {
      const int a = s.F(f, e), b = s.F(f, (e + 1) % 3);
      const double l = (s.V.row(a) - s.V.row(b)).squaredNorm();
      if (l > len) len = l, best = e;
      if (!is_edge(a, b) && l > len_missing) len_missing = l, best_missing = e;
    }
    split.push_back({f, best_missing >= 0 ? best_missing : best});
  }
  // Splits of triangles a flip has rewritten in this round wait for the next one.
  std::vector<std::pair<int, int>> todo;
  for (const auto& fe : split)
    if (!changed[fe.first]) todo.push_back(fe);
  if (!todo.empty()) split_edges(s, todo);
  return missing;
}

}  // namespace

void add_interior_points(ConformingSurface& s, double h) {
  if (!(h > 0)) return;
  const Eigen::RowVector3d lo = s.V.colwise().minCoeff(), hi = s.V.colwise().maxCoeff();
  const Eigen::Array3i n = (((hi - lo) / h).array().floor().cast<int>() + 1).transpose();
  if (static_cast<double>(n.prod()) > 2e6) return;  // a spacing far below the shape's size: no fill
  std::vector<Eigen::RowVector3d> grid;
  for (int x = 0; x < n[0]; ++x)
    for (int y = 0; y < n[1]; ++y)
      for (int z = 0; z < n[2]; ++z)
        grid.push_back(lo + 0.5 * ((hi - lo) - (n.cast<double>() - 1).matrix().transpose() * h) +
                       Eigen::RowVector3d(x, y, z) * h);
  Eigen::MatrixXd G(grid.size(), 3);
  for (size_t i = 0; i < grid.size(); ++i) G.row(static_cast<Eigen::Index>(i)) = grid[i];
  const Eigen::VectorXd w = winding_numbers(build_winding_tree(s.V, s.F), G);
  std::vector<Eigen::RowVector3d> inside;
  for (Eigen::Index i = 0; i < G.rows(); ++i)
    if (w[i] > 0.75) inside.push_back(G.row(i));  // clearly inside: points near the surface would crowd it
  auto store = [&]() {
    s.interior.resize(static_cast<Eigen::Index>(inside.size()), 3);
    for (size_t i = 0; i < inside.size(); ++i) s.interior.row(static_cast<Eigen::Index>(i)) = inside[i];
  };
  store();
  for (int round = 0; round < 6 && !inside.empty(); ++round) {
    std::vector<int> lost;
    ConformingSurface probe = s;
    conform_round(probe, false, &lost);
    if (static_cast<int>(lost.size()) <= s.missing) return;  // no worse than without the points
    // Drop the points in the diametral spheres of the lost triangles.
    std::vector<char> drop(inside.size(), 0);
    for (int f : lost) {
      const Eigen::RowVector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
      const Eigen::RowVector3d ab = b - a, ac = c - a, nrm = ab.cross(ac);
      const Eigen::RowVector3d centre =
          a + (nrm.cross(ab) * ac.squaredNorm() + ac.cross(nrm) * ab.squaredNorm()) / (2 * nrm.squaredNorm());
      const double r2 = (centre - a).squaredNorm() * 1.0001;
      for (size_t i = 0; i < inside.size(); ++i)
        if ((inside[i] - centre).squaredNorm() <= r2) drop[i] = 1;
    }
    std::vector<Eigen::RowVector3d> kept;
    for (size_t i = 0; i < inside.size(); ++i)
      if (!drop[i]) kept.push_back(inside[i]);
    if (kept.size() == inside.size()) break;
    inside.swap(kept);
    store();
  }
  inside.clear();  // the points keep costing the surface triangles: go without them
  store();
}

int split_edges(ConformingSurface& s, const std::vector<std::pair<int, int>>& triangle_edges) {
  std::vector<std::array<int, 3>> F(s.F.rows());
  for (int f = 0; f < s.F.rows(); ++f) F[f] = {s.F(f, 0), s.F(f, 1), s.F(f, 2)};
  std::vector<Eigen::RowVector3d> V(s.V.rows());
  for (int v = 0; v < s.V.rows(); ++v) V[v] = s.V.row(v);
  std::unordered_map<std::uint64_t, std::vector<int>> faces_of;
  for (int f = 0; f < static_cast<int>(F.size()); ++f)
    for (int j = 0; j < 3; ++j) faces_of[edge_key(F[f][j], F[f][(j + 1) % 3])].push_back(f);

  std::vector<std::uint64_t> edges;
  for (const auto& [f, e] : triangle_edges) edges.push_back(edge_key(F[f][e], F[f][(e + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());

  int added = 0;
  for (const std::uint64_t e : edges) {
    auto it = faces_of.find(e);
    if (it == faces_of.end()) continue;  // already split by an earlier edge of this round
    const int a = static_cast<int>(e >> 32), b = static_cast<int>(e & 0xffffffffu);
    const int m = static_cast<int>(V.size());
    V.push_back(0.5 * (V[a] + V[b]));
    ++added;
    const std::vector<int> around = it->second;
    faces_of.erase(it);
    for (const int f : around) {
      // Rotate f so that its edge (a, b) in either direction is (p, q), r the third corner.
      int j = 0;
      while (!((F[f][j] == a && F[f][(j + 1) % 3] == b) || (F[f][j] == b && F[f][(j + 1) % 3] == a))) ++j;
      const int p = F[f][j], q = F[f][(j + 1) % 3], r = F[f][(j + 2) % 3];
      const int g = static_cast<int>(F.size());
      F[f] = {p, m, r};
      F.push_back({m, q, r});
      auto& qr = faces_of[edge_key(q, r)];
      std::replace(qr.begin(), qr.end(), f, g);
      faces_of[edge_key(p, m)].push_back(f);
      faces_of[edge_key(m, q)].push_back(g);
      faces_of[edge_key(m, r)].push_back(f);
      faces_of[edge_key(m, r)].push_back(g);
    }
  }
  s.V.resize(static_cast<Eigen::Index>(V.size()), 3);
  for (size_t v = 0; v < V.size(); ++v) s.V.row(static_cast<Eigen::Index>(v)) = V[v];
  s.F.resize(static_cast<Eigen::Index>(F.size()), 3);
  for (size_t f = 0; f < F.size(); ++f)
    for (int j = 0; j < 3; ++j) s.F(static_cast<Eigen::Index>(f), j) = F[f][j];
  s.steiner += added;
  return added;
}


void make_conforming(ConformingSurface& s, int max_rounds) {
  ConformingSurface best;
  int previous = -1;
  best.missing = -1;
  for (int round = 0;; ++round) {
    ConformingSurface next = s;
    const int missing = conform_round(next, round < max_rounds);  // counts s's missing triangles
    if (best.missing < 0 || missing < best.missing) {
      best = s;
      best.missing = missing;
    }
    if (missing == 0 || round >= max_rounds || (previous >= 0 && missing >= previous)) break;
    previous = missing;
    s = std::move(next);
    ++s.rounds;
  }
  s = std::move(best);
}

ConformingSurface conforming_delaunay_surface(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int max_rounds) {
  ConformingSurface s;
  s.V = V;
  s.F = F;
  make_conforming(s, max_rounds);
  return s;
}

}  // namespace dfm
