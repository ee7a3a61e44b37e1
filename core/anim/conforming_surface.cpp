#include "core/anim/conforming_surface.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <set>
#include <cmath>
#include <functional>
#include <optional>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "core/anim/face_protection.h"
#include "core/anim/surface_delaunay.h"
#include "core/bind/winding_bvh.h"
#include "core/util/error.h"

namespace dfm {

namespace {

using K = DelaunayKernel;

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}

// What one round may do to the triangles missing from the tetrahedralization.
enum class RoundAction {
  count,           // nothing: only count them (missing_rows: every missing row)
  flip,            // take the other diagonal where that mends one (missing_rows: rows no flip mends)
  flip_and_split,  // flip, else split an edge
};

struct RoundOptions {
  RoundAction action = RoundAction::flip_and_split;
  double flip_gap = 0;  // > 0: also flip nearly flat quads whose diagonals pass within this distance
};

// One round: the triangles of s missing from the Delaunay tetrahedralization of s.V. Where a
// missing triangle and its neighbour are coplanar (co-circular points: the Delaunay tetrahedralization
// chose the other diagonal) the surface takes the other diagonal, which changes no geometry;
// elsewhere the triangle's longest edge missing from the tetrahedralization is split (else its
// longest edge). Returns the number of triangles that were missing. `growing`: where to get the
// tetrahedralization (else it is built afresh).
int conform_round(ConformingSurface& s, RoundOptions o, std::vector<int>* missing_rows = nullptr,
                  GrowingSurfaceDelaunay* growing = nullptr) {
  const bool fix = o.action != RoundAction::count;
  const bool allow_split = o.action == RoundAction::flip_and_split;
  const double flip_gap = o.flip_gap;
  std::optional<SurfaceDelaunay> own;
  const SurfaceDelaunay& sd = growing ? growing->of(s) : own.emplace(surface_delaunay(s));
  const Delaunay3& dt = sd.dt;
  const auto& vh = sd.vertex;
  std::unordered_map<std::uint64_t, std::vector<int>> faces_of;
  for (int f = 0; f < s.F.rows(); ++f)
    for (int j = 0; j < 3; ++j) faces_of[edge_key(s.F(f, j), s.F(f, (j + 1) % 3))].push_back(f);
  Delaunay3::Cell_handle c;
  int i, j, k;
  auto is_edge = [&](int a, int b) { return dt.is_edge(vh[a], vh[b], c, i, j); };
  auto point = [&](int v) { return vh[v]->point(); };
  std::vector<char> changed(s.F.rows(), 0);
  std::vector<std::pair<int, int>> split;
  int missing = 0;
  for (int f = 0; f < s.F.rows(); ++f) {
    if (dt.is_facet(vh[s.F(f, 0)], vh[s.F(f, 1)], vh[s.F(f, 2)], c, i, j, k)) continue;
    ++missing;
    // Rows that a flip of this round does not mend (with fix false: every missing row).
    if (missing_rows && !(fix && !allow_split)) missing_rows->push_back(f);
    if (!fix || changed[f]) continue;  // (a row a flip rewrote is mended)
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
      if (!is_edge(cc, d)) continue;
      if (CGAL::orientation(point(a), point(b), point(cc), point(d)) != CGAL::COPLANAR) {
        // Nearly flat: the diagonals pass within flip_gap of each other, the new edge is not on the
        // surface yet, and both new triangles face the way the old ones did.
        if (!(flip_gap > 0) || faces_of.count(edge_key(cc, d))) continue;
        const Eigen::RowVector3d A = s.V.row(a), B = s.V.row(b), C = s.V.row(cc), D = s.V.row(d);
        const Eigen::RowVector3d ncd = (B - A).cross(D - C);
        const double gap = std::abs((C - A).dot(ncd)) / ncd.norm();
        const Eigen::RowVector3d n_old = (B - A).cross(C - A) + (A - B).cross(D - B);
        if (!(gap <= flip_gap) || !((D - A).cross(C - A).dot(n_old) > 0) || !((B - D).cross(C - D).dot(n_old) > 0)) continue;
        s.flipped.push_back(edge_key(cc, d));
      }
      s.F.row(f) << a, d, cc;  // the quad a d b cc, split by cc -- d
      s.F.row(g) << d, b, cc;
      changed[f] = changed[g] = 1;
      flipped = true;
    }
    if (!flipped && !allow_split && missing_rows) missing_rows->push_back(f);
    if (flipped || !allow_split) continue;
    int best = -1, best_missing = -1;
    double len = -1, len_missing = -1;
    for (int e = 0; e < 3; ++e) {
      const int a = s.F(f, e), b = s.F(f, (e + 1) % 3);
      if (std::find(s.flipped.begin(), s.flipped.end(), edge_key(a, b)) != s.flipped.end()) continue;
      const double l = (s.V.row(a) - s.V.row(b)).squaredNorm();
      if (l > len) len = l, best = e;
      if (!is_edge(a, b) && l > len_missing) len_missing = l, best_missing = e;
    }
    if (best >= 0) split.push_back({f, best_missing >= 0 ? best_missing : best});
  }
  // Splits of triangles a flip has rewritten in this round wait for the next one.
  std::vector<std::pair<int, int>> todo;
  for (const auto& fe : split)
    if (!changed[fe.first]) todo.push_back(fe);
  if (!todo.empty()) split_edges(s, todo);
  return missing;
}

}  // namespace

int add_fill_points(ConformingSurface& s, const Eigen::MatrixXd& candidates, FillRule rule,
                    GrowingSurfaceDelaunay* growing) {
  std::vector<std::vector<Eigen::RowVector3d>> groups(static_cast<size_t>(candidates.rows()));
  for (Eigen::Index i = 0; i < candidates.rows(); ++i) groups[static_cast<size_t>(i)] = {candidates.row(i)};
  return add_fill_points(s, groups, rule, {}, growing);
}

int add_fill_points(ConformingSurface& s, const std::vector<std::vector<Eigen::RowVector3d>>& groups, FillRule rule,
                    const std::function<bool(size_t, const Eigen::RowVector3d&)>& accept,
                    GrowingSurfaceDelaunay* growing) {
  if (groups.empty()) return 0;
  const Eigen::MatrixXd before = s.fill;
  // A point (nearly) where the tetrahedralization has one already is not added: it would only make
  // slivers. Near means within 1e-6 of the surface's size, found on a grid of that cell size.
  const double cell = 1e-6 * std::max(1e-300, (s.V.colwise().maxCoeff() - s.V.colwise().minCoeff()).norm());
  std::set<std::array<std::int64_t, 3>> taken;
  auto key_of = [&](const Eigen::RowVector3d& p) {
    std::array<std::int64_t, 3> k;
    for (int d = 0; d < 3; ++d) k[d] = static_cast<std::int64_t>(std::floor(p[d] / cell));
    return k;
  };
  auto fresh = [&](const Eigen::RowVector3d& p) {
    const auto k = key_of(p);
    for (int c = 0; c < 27; ++c)
      if (taken.count({k[0] + c % 3 - 1, k[1] + c / 3 % 3 - 1, k[2] + c / 9 - 1})) return false;
    return true;
  };
  for (Eigen::Index i = 0; i < s.V.rows(); ++i) taken.insert(key_of(s.V.row(i)));
  for (Eigen::Index i = 0; i < s.fill.rows(); ++i) taken.insert(key_of(s.fill.row(i)));
  std::optional<FaceProtection> protection;
  if (rule == FillRule::Protect) protection.emplace(s, surface_delaunay(s));
  std::vector<Eigen::RowVector3d> added;
  for (size_t g = 0; g < groups.size(); ++g)
    for (const Eigen::RowVector3d& p : groups[g])
      if (p.allFinite() && fresh(p) && (!protection || protection->admit(p, false)) && (!accept || accept(g, p))) {
        if (protection) protection->admit(p);
        taken.insert(key_of(p));
        added.push_back(p);
        break;
      }
  auto store = [&]() {
    s.fill.resize(before.rows() + static_cast<Eigen::Index>(added.size()), 3);
    s.fill.topRows(before.rows()) = before;
    for (size_t i = 0; i < added.size(); ++i) s.fill.row(before.rows() + static_cast<Eigen::Index>(i)) = added[i];
  };
  store();
  // The points break ties between co-spherical surface vertices: the surface takes the diagonals
  // the tetrahedralization now has (no change of geometry), then points that still cost a triangle
  // go, those inside its diametral sphere first.
  int lost_before = s.missing;
  for (int round = 0; round < 4 && !added.empty(); ++round) {
    std::vector<int> lost;
    conform_round(s, {RoundAction::flip}, &lost, growing);
    if (static_cast<int>(lost.size()) <= lost_before) {  // no worse than without the points
      s.missing = static_cast<int>(lost.size());
      return static_cast<int>(added.size());
    }
    const double grow = 1.0001 + 0.5 * round;  // widen the net when the diametral spheres do not do
    std::vector<char> drop(added.size(), 0);
    for (int f : lost) {
      const Eigen::RowVector3d a = s.V.row(s.F(f, 0));
      const Eigen::RowVector3d centre = circumcentre(a, s.V.row(s.F(f, 1)), s.V.row(s.F(f, 2)));
      const double r2 = (centre - a).squaredNorm() * grow * grow;
      for (size_t i = 0; i < added.size(); ++i)
        if ((added[i] - centre).squaredNorm() <= r2) drop[i] = 1;
    }
    std::vector<Eigen::RowVector3d> kept;
    for (size_t i = 0; i < added.size(); ++i)
      if (!drop[i]) kept.push_back(added[i]);
    added.swap(kept);
    store();
  }
  ConformingSurface probe = s;
  s.missing = conform_round(probe, {RoundAction::count}, nullptr, growing);  // what the points cost in the end
  return static_cast<int>(added.size());
}

namespace {

// Points that kill a chord tetrahedron (corners p, circumcentre cc, centroid m), in order of
// preference, their side of the surface not checked yet (the caller checks the one it takes: most
// are never needed). For Repair, a point toward the circumcentre (a flat tetrahedron's centroid sits
// in its surface triangles' diametral spheres) at most its longest edge away, then the centroid; for
// Protect, alternatives in its circumball. Each has a small pseudo-random offset
// (hash state h): mirror-symmetric keys would give mirror-image points, and the level set through a
// symmetric configuration has flat pieces (zero-area slice triangles).
std::vector<Eigen::RowVector3d> chord_points(const Eigen::RowVector3d (&p)[4], const Eigen::RowVector3d& cc, bool all_on,
                                             FillRule rule, std::uint64_t& h) {
  const Eigen::RowVector3d m = (p[0] + p[1] + p[2] + p[3]) / 4;
  double edge = 0;
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) edge = std::max(edge, (p[a] - p[b]).norm());
  auto wobble = [&]() {
    Eigen::RowVector3d w;
    for (int d = 0; d < 3; ++d) {
      h ^= h >> 31, h *= 0xBF58476D1CE4E5B9ull, h ^= h >> 27;
      w[d] = static_cast<double>(h >> 11) * 0x1.0p-53 - 0.5;
    }
    return w;
  };
  const double len = (cc - m).norm();
  if (rule == FillRule::Repair) {
    const Eigen::RowVector3d base = m + 0.02 * edge * wobble();
    if (!all_on || !std::isfinite(len) || !(len > 0)) return {base};
    return {base + (cc - m) * std::min(1.0, edge / len), base};
  }
  // Along the normal of the corners' best-fitting plane (both ways) and toward the circumcentre,
  // from near the circumsphere inward: a point far from the surface narrows its triangles' empty
  // spheres least.
  const double r = (cc - p[0]).norm();
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& q : p) cov += (q - m).transpose() * (q - m);
  const Eigen::RowVector3d normal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors().col(0).transpose();
  std::vector<Eigen::RowVector3d> directions = {normal, -normal};
  if (std::isfinite(len) && len > 0) directions.push_back((cc - m) / len);
  std::vector<Eigen::RowVector3d> out;
  for (const Eigen::RowVector3d& u : directions) {
    const double b = u.dot(m - cc), c = (m - cc).squaredNorm() - r * r, disc = b * b - c;
    if (!(disc >= 0) || !std::isfinite(disc)) continue;
    const double t_max = -b + std::sqrt(disc);
    for (const double w : {0.9, 0.7, 0.5, 0.3, 0.1}) {
      const Eigen::RowVector3d q = m + w * t_max * u + 0.02 * std::min(edge, r) * wobble();
      if (q.allFinite() && (q - cc).norm() < r) out.push_back(q);
    }
  }
  // Then just inside the circumsphere all round: for the chord's own surface triangles the least
  // narrowing points, though farther from the chord.
  for (int k = 0; k < 27; ++k) {
    if (k == 13) continue;
    const Eigen::RowVector3d u = Eigen::RowVector3d(k % 3 - 1, k / 3 % 3 - 1, k / 9 - 1).normalized();
    const Eigen::RowVector3d q = cc + 0.95 * r * u + 0.01 * std::min(edge, r) * wobble();
    if (q.allFinite() && (q - cc).norm() < r) out.push_back(q);
  }
  return out;
}

}  // namespace

int cover_outside_chords(ConformingSurface& s, FillRule rule, int rounds, GrowingSurfaceDelaunay* growing) {
  const WindingTree tree = build_winding_tree(s.V, s.F);
  std::unordered_set<std::uint64_t> surface;  // sorted triangle keys (21 bits a vertex)
  auto tri_key = [](int a, int b, int c) {
    int v[3] = {a, b, c};
    std::sort(v, v + 3);
    return static_cast<std::uint64_t>(v[0]) << 42 | static_cast<std::uint64_t>(v[1]) << 21 | static_cast<std::uint64_t>(v[2]);
  };
  for (int f = 0; f < s.F.rows(); ++f) surface.insert(tri_key(s.F(f, 0), s.F(f, 1), s.F(f, 2)));
  const int n = static_cast<int>(s.V.rows());
  int left = 0;
  for (int round = 0; round <= rounds; ++round) {
    const SurfaceDelaunay sd = surface_delaunay(s);
    std::vector<std::vector<Eigen::RowVector3d>> groups;
    std::vector<char> group_outside;
    left = 0;
    std::uint64_t h = 0x9E3779B97F4A7C15ull;
    for (auto c = sd.dt.finite_cells_begin(); c != sd.dt.finite_cells_end(); ++c) {
      int v[4], on = 0;
      for (int j = 0; j < 4; ++j) on += (v[j] = c->vertex(j)->info()) < n;
      if (on < 3) continue;
      bool chord = on == 4;  // no corner off the surface: inside or outside, the field is 0 throughout
      for (int j = 0; j < 4 && !chord; ++j) {
        const int a = v[(j + 1) % 4], b = v[(j + 2) % 4], d = v[(j + 3) % 4];
        chord = a < n && b < n && d < n && !surface.count(tri_key(a, b, d));
      }
      if (!chord) continue;
      Eigen::RowVector3d p[4], m = Eigen::RowVector3d::Zero();
      for (int j = 0; j < 4; ++j) m += (p[j] = v[j] < n ? s.V.row(v[j]) : s.fill.row(v[j] - n)) / 4;
      const bool outside = winding_number(tree, m.transpose()) < 0.5;
      if (on < 4 && !outside) continue;
      ++left;
      const K::Point_3 cc = CGAL::circumcenter(c->vertex(0)->point(), c->vertex(1)->point(), c->vertex(2)->point(),
                                               c->vertex(3)->point());
      auto group = chord_points(p, Eigen::RowVector3d(cc.x(), cc.y(), cc.z()), on == 4, rule, h);
      if (group.empty()) continue;
      groups.push_back(std::move(group));
      group_outside.push_back(outside);
    }
    if (left == 0 || round == rounds || groups.empty()) break;
    const auto on_side = [&](size_t g, const Eigen::RowVector3d& q) {
      return (winding_number(tree, q.transpose()) < 0.5) == static_cast<bool>(group_outside[g]);
    };
    if (add_fill_points(s, groups, rule, on_side, growing) == 0) break;  // every candidate would cost a surface triangle
  }
  return left;
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


int flip_nearly_flat(ConformingSurface& s, double max_gap) {
  const size_t before = s.flipped.size();
  conform_round(s, {RoundAction::flip, max_gap});
  ConformingSurface probe = s;
  s.missing = conform_round(probe, {RoundAction::count});
  return static_cast<int>(s.flipped.size() - before);
}

void make_conforming(ConformingSurface& s, int max_rounds, GrowingSurfaceDelaunay* growing) {
  GrowingSurfaceDelaunay own;  // each round only splits edges: the surface grows
  GrowingSurfaceDelaunay& tetrahedralization = growing ? *growing : own;
  ConformingSurface best;
  int previous = -1;
  best.missing = -1;
  for (int round = 0;; ++round) {
    ConformingSurface next = s;
    // Counts s's missing triangles; the last round only counts.
    const RoundAction act = round < max_rounds ? RoundAction::flip_and_split : RoundAction::count;
    const int missing = conform_round(next, {act}, nullptr, &tetrahedralization);
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
