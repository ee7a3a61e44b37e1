#include "core/anim/key_time_seal.h"

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <unordered_map>
#include <vector>

#include "core/anim/tet_faces.h"

namespace dfm {

namespace {

// The face of tet t opposite corner i, as its boundary orients it.
Face oriented_face(const MatrixX4iRow& T, int t, int i) { return dfm::oriented_face({T(t, 0), T(t, 1), T(t, 2), T(t, 3)}, i); }

int find(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

// Tetrahedra with a triangle in the plane t = time, clustered: two that give a triangle opposite
// orientations fold along it (a lid and a tetrahedron on its face, or two on a chord) and go in one
// cluster; lids (all four corners in the plane) are in clusters of their own at least.
std::map<int, std::vector<int>> folded_clusters(const MatrixX4dRow& V, const MatrixX4iRow& T, double time) {
  const int nt = static_cast<int>(T.rows());
  auto on = [&](int v) { return V(v, 3) == time; };
  std::unordered_map<Face, std::vector<std::pair<int, int>>, FaceHash> held;  // the orientation each gives
  std::vector<char> bad(nt, 0);
  for (int t = 0; t < nt; ++t) {
    int k = 0;
    for (int c = 0; c < 4; ++c) k += on(T(t, c));
    if (k < 3) continue;
    bad[t] = k == 4;  // a lid
    for (int i = 0; i < 4; ++i)
      if (k == 4 || !on(T(t, i))) {
        const auto [f, sign] = canonical(oriented_face(T, t, i));
        held[f].push_back({t, sign});
      }
  }
  std::vector<int> parent(nt);
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& [f, ts] : held) {
    std::vector<int> up, down;
    for (const auto& [t, sign] : ts) (sign > 0 ? up : down).push_back(t);
    for (size_t k = 0; k < std::min(up.size(), down.size()); ++k) {
      bad[up[k]] = bad[down[k]] = 1;
      parent[find(parent, up[k])] = find(parent, down[k]);
    }
  }
  std::map<int, std::vector<int>> clusters;
  for (int t = 0; t < nt; ++t)
    if (bad[t]) clusters[find(parent, t)].push_back(t);
  return clusters;
}

// The cluster's oriented boundary (faces whose orientations do not cancel); false unless it is a
// closed surface using each directed edge once.
bool closed_boundary(const MatrixX4iRow& T, const std::vector<int>& ts, std::vector<Face>& boundary) {
  std::unordered_map<Face, int, FaceHash> sum;
  for (int t : ts)
    for (int i = 0; i < 4; ++i) {
      const auto [f, s] = canonical(oriented_face(T, t, i));
      sum[f] += s;
    }
  std::map<std::pair<int, int>, int> edge_use;
  bool closed = true;
  for (const auto& [f, s] : sum) {
    if (s == 0) continue;
    if (s != 1 && s != -1) closed = false;
    Face g = f;
    if (s < 0) std::swap(g[1], g[2]);
    boundary.push_back(g);
    for (int j = 0; j < 3; ++j) closed = closed && ++edge_use[{g[j], g[(j + 1) % 3]}] == 1;
  }
  for (const auto& [e, n] : edge_use) closed = closed && edge_use.count({e.second, e.first}) == 1;
  return closed;
}

// The cone point: over the cluster's corners in the plane, nudged toward its corners off it (at the
// plain centroid of a flat quadrilateral it would be in line with a diagonal), at time `inside`.
Eigen::RowVector4d cone_point(const MatrixX4dRow& V, const MatrixX4iRow& T, const std::vector<int>& ts, double time,
                              double inside) {
  Eigen::RowVector4d y = Eigen::RowVector4d::Zero(), off = Eigen::RowVector4d::Zero();
  int n = 0, m = 0;
  for (int t : ts)
    for (int c = 0; c < 4; ++c)
      if (V(T(t, c), 3) == time) y += V.row(T(t, c)), ++n;
      else off += V.row(T(t, c)), ++m;
  y /= n;
  if (m > 0) y += 0.01 * (off / m - y);
  y[3] = inside;
  return y;
}

}  // namespace

int seal_key_time(MatrixX4dRow& V, MatrixX4iRow& T, double time, double inside) {
  const std::map<int, std::vector<int>> clusters = folded_clusters(V, T, time);
  if (clusters.empty()) return 0;
  auto on = [&](int v) { return V(v, 3) == time; };
  std::vector<char> drop(T.rows(), 0);
  std::vector<Eigen::RowVector4d> extra_v;
  std::vector<std::array<int, 4>> extra_t;
  int sealed = 0;
  for (const auto& [root, ts] : clusters) {
    std::vector<Face> boundary;
    const bool closed = closed_boundary(T, ts, boundary);
    bool touches_plane_only = true;  // the cone point must see a boundary that leaves the plane
    for (const Face& g : boundary) touches_plane_only = touches_plane_only && on(g[0]) && on(g[1]) && on(g[2]);
    if (!closed || boundary.empty() || touches_plane_only) continue;
    const int yi = static_cast<int>(V.rows() + extra_v.size());
    extra_v.push_back(cone_point(V, T, ts, time, inside));
    for (const Face& g : boundary) extra_t.push_back({yi, g[0], g[1], g[2]});
    for (int t : ts) drop[t] = 1;
    ++sealed;
  }
  edit_tets(V, T, drop, extra_v, extra_t);
  return sealed;
}

}  // namespace dfm
