#include "core/anim/conforming_surface.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <unordered_map>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

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

// The triangles of s that are not faces of the Delaunay tetrahedralization of s.V.
std::vector<int> missing_triangles(const ConformingSurface& s) {
  const int n = static_cast<int>(s.V.rows());
  std::vector<std::pair<K::Point_3, int>> pts;
  pts.reserve(n);
  for (int i = 0; i < n; ++i) pts.push_back({K::Point_3(s.V(i, 0), s.V(i, 1), s.V(i, 2)), i});
  Delaunay3 dt(pts.begin(), pts.end());
  std::vector<Delaunay3::Vertex_handle> vh(n);
  int found = 0;
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v, ++found) vh[v->info()] = v;
  if (found != n) throw Error("two surface vertices are at the same position");
  std::vector<int> missing;
  for (int f = 0; f < s.F.rows(); ++f) {
    Delaunay3::Cell_handle c;
    int i, j, k;
    if (!dt.is_facet(vh[s.F(f, 0)], vh[s.F(f, 1)], vh[s.F(f, 2)], c, i, j, k)) missing.push_back(f);
  }
  return missing;
}

}  // namespace

int split_longest_edges(ConformingSurface& s, const std::vector<int>& triangles) {
  std::vector<std::array<int, 3>> F(s.F.rows());
  for (int f = 0; f < s.F.rows(); ++f) F[f] = {s.F(f, 0), s.F(f, 1), s.F(f, 2)};
  std::vector<Eigen::RowVector3d> V(s.V.rows());
  for (int v = 0; v < s.V.rows(); ++v) V[v] = s.V.row(v);
  std::unordered_map<std::uint64_t, std::vector<int>> faces_of;
  for (int f = 0; f < static_cast<int>(F.size()); ++f)
    for (int j = 0; j < 3; ++j) faces_of[edge_key(F[f][j], F[f][(j + 1) % 3])].push_back(f);

  std::vector<std::uint64_t> edges;
  for (int f : triangles) {
    int best = 0;
    double len = -1;
    for (int j = 0; j < 3; ++j) {
      const double l = (V[F[f][j]] - V[F[f][(j + 1) % 3]]).squaredNorm();
      if (l > len) len = l, best = j;
    }
    edges.push_back(edge_key(F[f][best], F[f][(best + 1) % 3]));
  }
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
  for (;;) {
    const std::vector<int> missing = missing_triangles(s);
    if (missing.empty()) return;
    if (s.rounds >= max_rounds)
      throw Error("the surface is not conforming Delaunay after " + std::to_string(s.rounds) + " rounds of " +
                  "splitting (" + std::to_string(missing.size()) + " triangles missing; very thin triangles or " +
                  "nearly touching parts?)");
    split_longest_edges(s, missing);
    ++s.rounds;
  }
}

ConformingSurface conforming_delaunay_surface(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int max_rounds) {
  ConformingSurface s;
  s.V = V;
  s.F = F;
  make_conforming(s, max_rounds);
  return s;
}

}  // namespace dfm
