#include "core/anim/transition.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <unordered_map>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include "core/anim/conforming_surface.h"
#include "core/anim/delaunay_4d.h"
#include "core/anim/key_solid.h"
#include "core/anim/surface_checks.h"
#include "core/util/error.h"

namespace dfm {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

bool self_intersects(const TriMesh& key) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<K::Point_3>;
  Mesh mesh;
  std::vector<Mesh::Vertex_index> vi;
  for (int v = 0; v < key.V.rows(); ++v) vi.push_back(mesh.add_vertex(K::Point_3(key.V(v, 0), key.V(v, 1), key.V(v, 2))));
  for (int f = 0; f < key.F.rows(); ++f)
    if (mesh.add_face(vi[key.F(f, 0)], vi[key.F(f, 1)], vi[key.F(f, 2)]) == Mesh::null_face())
      throw Error("triangle " + std::to_string(f) + " makes a non-manifold vertex");
  return CGAL::Polygon_mesh_processing::does_self_intersect(mesh);
}

// The key's referenced vertices only, in their order.
TriMesh compacted(const TriMesh& key) {
  std::vector<int> map(key.V.rows(), -1);
  int n = 0;
  for (int f = 0; f < key.F.rows(); ++f)
    for (int j = 0; j < 3; ++j)
      if (map[key.F(f, j)] < 0) map[key.F(f, j)] = n++;
  TriMesh out;
  out.V.resize(n, 3);
  for (int v = 0; v < key.V.rows(); ++v)
    if (map[v] >= 0) out.V.row(map[v]) = key.V.row(v);
  out.F.resize(key.F.rows(), 3);
  for (int f = 0; f < key.F.rows(); ++f)
    for (int j = 0; j < 3; ++j) out.F(f, j) = map[key.F(f, j)];
  return out;
}

double mean_edge_length(const ConformingSurface& s) {
  double sum = 0;
  for (int f = 0; f < s.F.rows(); ++f)
    for (int j = 0; j < 3; ++j) sum += (s.V.row(s.F(f, j)) - s.V.row(s.F(f, (j + 1) % 3))).norm();
  return s.F.rows() > 0 ? sum / (3.0 * s.F.rows()) : 0.0;
}

// ---- classification (which 4-simplices are kept in which layer) ---------------------------------

enum Layer { kEarly = 0, kMiddle = 1, kLate = 2 };

// The key tetrahedra (all corners on one key) that are facets of the 4D triangulation.
std::vector<std::array<int, 4>> key_tets(const Delaunay4& D, int first, int last) {
  std::vector<std::array<int, 4>> tets;
  for (int s = 0; s < D.simplices.rows(); ++s)
    for (int i = 0; i < 5; ++i) {
      std::array<int, 4> t;
      int k = 0;
      for (int j = 0; j < 5; ++j)
        if (j != i) t[k++] = D.simplices(s, j);
      if (std::all_of(t.begin(), t.end(), [&](int v) { return v >= first && v < last; })) tets.push_back(t);
    }
  return tets;
}

// kept[s] bit L: simplex s belongs to the morph in layer L.
// kept[s] bit L: simplex s belongs to the morph in layer L.
std::vector<unsigned char> classify(const Delaunay4& D, int n0, const KeySolid& source, const KeySolid& target) {
  std::vector<unsigned char> kept(D.simplices.rows(), 0);
  for (int s = 0; s < D.simplices.rows(); ++s) {
    int lo[5], hi[5], nl = 0, nh = 0;
    for (int j = 0; j < 5; ++j) {
      const int v = D.simplices(s, j);
      if (v < n0) lo[nl++] = v; else hi[nh++] = v;
    }
    const bool in_s = source.contains(lo, nl), in_t = target.contains(hi, nh);
    kept[s] = static_cast<unsigned char>((in_s ? 1 << kEarly : 0) | (in_s && in_t ? 1 << kMiddle : 0) |
                                         (in_t ? 1 << kLate : 0));
  }
  return kept;
}

// ---- manifold repair: a triangle of the boundary held by more than two boundary facets --------

// The simplices around the triangle g of simplex s in ring order; `closed` false when the ring ends
// on the hull at both ends.
std::vector<int> ring_around(const Delaunay4& D, int s, const std::array<int, 3>& g, bool* closed) {
  auto others = [&](int x, int* out) {  // the two corners of x not in g, as corner indices
    int k = 0;
    for (int j = 0; j < 5; ++j) {
      const int v = D.simplices(x, j);
      if (v != g[0] && v != g[1] && v != g[2]) out[k++] = j;
    }
  };
  std::vector<int> fwd = {s}, back;
  for (int dir = 0; dir < 2; ++dir) {
    int cur = s;
    int o[2];
    others(s, o);
    int exit = o[dir];  // leave s across the facet opposite this corner
    for (;;) {
      const int next = D.neighbors(cur, exit);
      if (next < 0 || next == s) break;
      (dir == 0 ? fwd : back).push_back(next);
      const int came_from = cur;
      cur = next;
      others(cur, o);
      // Leave cur across the facet that is not shared with came_from.
      exit = D.neighbors(cur, o[0]) == came_from ? o[1] : o[0];
    }
    if (dir == 0 && D.neighbors(cur, exit) == s) {
      *closed = true;
      return fwd;
    }
  }
  *closed = false;
  std::reverse(back.begin(), back.end());
  back.insert(back.end(), fwd.begin(), fwd.end());
  return back;
}

// May layer L's membership of simplex s change without changing a key's slice? Near the source
// the simplices with a lower face of 3 or 4 corners make the source's slice; near the target those
// with an upper face of 3 or 4.
bool may_flip(const Delaunay4& D, int n0, int s, int L) {
  int nl = 0;
  for (int j = 0; j < 5; ++j) nl += D.simplices(s, j) < n0;
  if (L == kEarly) return nl <= 2;
  if (L == kLate) return nl >= 3;
  return true;
}

// The triangles of simplex s that span both keys (slices inside the slab cut them), as keys.
void spanning_triangles(const Delaunay4& D, int n0, int s, std::vector<SimplexKey>& out) {
  for (int a = 0; a < 5; ++a)
    for (int b = a + 1; b < 5; ++b)
      for (int c = b + 1; c < 5; ++c) {
        const int g[3] = {D.simplices(s, a), D.simplices(s, b), D.simplices(s, c)};
        const int nl = (g[0] < n0) + (g[1] < n0) + (g[2] < n0);
        if (nl != 0 && nl != 3) out.push_back(simplex_key(g, 3));
      }
}

// Fills (or, where that is not allowed, empties) the rings around boundary triangles that more than
// two boundary facets hold, until the boundary is a 3-manifold at its triangles: a worklist seeded
// with every triangle of every boundary facet, refilled with the triangles of flipped simplices.
// Returns the flips (at most max_flips).
int repair_nonmanifold(const Delaunay4& D, int n0, std::vector<unsigned char>& kept, int L, int max_flips) {
  const unsigned char bit = static_cast<unsigned char>(1 << L);
  auto in = [&](int x) { return x >= 0 && (kept[x] & bit); };
  // Boundary facets of the kept set that hold the ring's triangle: one per kept/not-kept step.
  auto boundary_count = [&](const std::vector<int>& ring, bool closed) {
    int c = 0;
    for (size_t k = 0; k + 1 < ring.size(); ++k) c += in(ring[k]) != in(ring[k + 1]);
    if (closed) c += in(ring.back()) != in(ring.front());
    else c += in(ring.front()) + in(ring.back());  // the hull's outside is never kept
    return c;
  };
  std::vector<std::pair<SimplexKey, int>> work;  // triangle, a simplex holding it
  std::vector<SimplexKey> tris;
  for (int s = 0; s < D.simplices.rows(); ++s) {
    if (!in(s)) continue;
    bool on_boundary = false;
    for (int i = 0; i < 5; ++i) on_boundary = on_boundary || !in(D.neighbors(s, i));
    if (!on_boundary) continue;
    tris.clear();
    spanning_triangles(D, n0, s, tris);
    for (const auto& g : tris) work.push_back({g, s});
  }
  int flips = 0;
  std::vector<char> flipped(kept.size(), 0);
  while (!work.empty() && flips < max_flips) {
    const auto [g, s] = work.back();
    work.pop_back();
    bool closed = false;
    const std::vector<int> ring = ring_around(D, s, {g[0], g[1], g[2]}, &closed);
    if (boundary_count(ring, closed) <= 2) continue;
    // Each simplex changes at most once, so repairs cannot undo each other.
    auto free = [&](int x) { return !flipped[x] && may_flip(D, n0, x, L); };
    bool can_fill = true;
    for (int x : ring) can_fill = can_fill && (in(x) || free(x));
    for (int x : ring) {
      const bool flip = can_fill ? !in(x) : (in(x) && free(x));
      if (!flip) continue;
      kept[x] ^= bit;
      flipped[x] = 1;
      ++flips;
      tris.clear();
      spanning_triangles(D, n0, x, tris);
      for (const auto& h : tris)
        if (h != g) work.push_back({h, x});
    }
  }
  return flips;
}

// ---- extraction (the boundary of the kept pieces, clipped to their layer) -----------------------

class PieceWriter {
 public:
  PieceWriter(const MatrixX4dRow& points, int n0, double t0, double t1)
      : P_(points), n0_(n0), t0_(t0), t1_(t1) {
    V_.assign(points.data(), points.data() + points.size());
  }

  // The facet of `simplex` opposite corner `skip`, clipped to local times [a, b], oriented away from
  // the simplex's inside. The clipped facet is a convex polytope; its boundary is triangulated by
  // rules that depend on the boundary face alone (so neighbouring pieces agree) and the polytope is
  // then coned from its first vertex.
  void facet(const int* simplex, int skip, double a, double b) {
    int v[4], n = 0, nl = 0;
    for (int j = 0; j < 5; ++j)
      if (j != skip) v[n++] = simplex[j];
    // The boundary of a positive simplex is sum (-1)^i (v0 .. v^i .. v4), outward (manifold.h's
    // convention); the pieces are oriented against this order through barycentric coordinates,
    // which stays exact where the 4D simplex is nearly flat.
    Eigen::Matrix<double, 5, 4, Eigen::RowMajor> Q;
    for (int j = 0; j < 5; ++j) Q.row(j) = P_.row(simplex[j]);
    const bool positive = (orientation_4d(Q) > 0) == (skip % 2 == 0);
    std::copy(v, v + 4, outward_.begin());
    if (!positive) std::swap(outward_[2], outward_[3]);
    std::sort(v, v + 4, [&](int x, int y) { return (x >= n0_) < (y >= n0_) || ((x >= n0_) == (y >= n0_) && x < y); });
    for (int j = 0; j < 4; ++j) nl += v[j] < n0_;
    if (nl == 0 || nl == 4) return;  // a key tetrahedron (a cap): never cut by a slice inside the slab
    tris_.clear();
    bary_.clear();
    face_ = 0;
    // Side faces: each triangle of the facet spanning both times, swept over [a, b].
    for (int g = 0; g < 4; ++g) {
      int w[3], k = 0, gl = 0;
      for (int j = 0; j < 4; ++j)
        if (j != g) w[k++] = v[j], gl += v[j] < n0_;
      if (gl == 0 || gl == 3) continue;
      const Rail r1 = gl == 1 ? Rail{w[0], w[1]} : Rail{w[0], w[2]};
      const Rail r2 = gl == 1 ? Rail{w[0], w[2]} : Rail{w[1], w[2]};
      side(r1, r2, a, b);
    }
    cross_section(v, nl, a);
    cross_section(v, nl, b);
    cone();
  }

  int num_vertices() const { return static_cast<int>(V_.size() / 4); }
  const std::vector<double>& vertices() const { return V_; }
  const std::vector<std::array<int, 4>>& tets() const { return T_; }

 private:
  // A rail is a lower-upper edge (l, u); its point at local time tau.
  int rail_point(const std::array<int, 2>& r, double tau) {  // r = {lower, upper}
    const int id = rail_vertex(r, tau);
    Eigen::Vector4d& w = bary_[id];
    w.setZero();
    for (int k = 0; k < 4; ++k) {
      if (outward_[k] == r[0]) w[k] += 1 - tau;
      if (outward_[k] == r[1]) w[k] += tau;
    }
    return id;
  }

  int corner(int v) {
    Eigen::Vector4d& w = bary_[v];
    for (int k = 0; k < 4; ++k) w[k] = outward_[k] == v ? 1.0 : 0.0;
    return v;
  }

  int rail_vertex(const std::array<int, 2>& r, double tau) {
    if (tau == 0.0) return r[0];
    if (tau == 1.0) return r[1];
    const std::uint64_t key = static_cast<std::uint64_t>(r[0]) << 32 | static_cast<std::uint32_t>(r[1]);
    auto [it, fresh] = cut_[tau].emplace(key, num_vertices());
    if (fresh) {
      for (int d = 0; d < 3; ++d) V_.push_back((1 - tau) * P_(r[0], d) + tau * P_(r[1], d));
      V_.push_back(t0_ + tau * (t1_ - t0_));
    }
    return it->second;
  }

  using Rail = std::array<int, 2>;  // lower vertex, upper vertex

  // Boundary faces are planar polygons (one or two triangles); the cone skips every triangle of a
  // face that holds the apex, not only the triangles that do (they are flat with it).
  void add_triangle(int x, int y, int z) {
    if (x != y && y != z && x != z) tris_.push_back({x, y, z, face_});
  }
  void next_face() { ++face_; }
  const Eigen::Vector4d& bary(int id) const { return bary_.at(id); }

  // A planar quad in cyclic order, fanned from its smallest vertex (so a face triangulates the same
  // in every piece that holds it, and as the cone from the piece's smallest vertex expects); a
  // collapsed quad is one triangle.
  void add_quad(int p, int q, int r, int s) {
    next_face();
    const int c[4] = {p, q, r, s};
    int m = 0;
    for (int k = 1; k < 4; ++k)
      if (c[k] < c[m]) m = k;
    add_triangle(c[m], c[(m + 1) % 4], c[(m + 2) % 4]);
    add_triangle(c[m], c[(m + 2) % 4], c[(m + 3) % 4]);
  }

  // The trapezoid swept by the segment between two rails over [a, b].
  void side(const Rail& r1, const Rail& r2, double a, double b) {
    add_quad(rail_point(r1, a), rail_point(r2, a), rail_point(r2, b), rail_point(r1, b));
  }

  // The facet's cross-section at local time tau (its lower face at 0, its upper face at 1): a
  // triangle or a quad.
  void cross_section(const int* v, int nl, double tau) {
    next_face();
    if (tau == 0.0) {
      if (nl == 3) add_triangle(corner(v[0]), corner(v[1]), corner(v[2]));
      return;
    }
    if (tau == 1.0) {
      if (nl == 1) add_triangle(corner(v[1]), corner(v[2]), corner(v[3]));
      return;
    }
    if (nl == 1) {
      add_triangle(rail_point({v[0], v[1]}, tau), rail_point({v[0], v[2]}, tau), rail_point({v[0], v[3]}, tau));
    } else if (nl == 3) {
      add_triangle(rail_point({v[0], v[3]}, tau), rail_point({v[1], v[3]}, tau), rail_point({v[2], v[3]}, tau));
    } else {
      const Rail r00 = {v[0], v[2]}, r01 = {v[0], v[3]}, r11 = {v[1], v[3]}, r10 = {v[1], v[2]};
      const int c00 = rail_point(r00, tau), c01 = rail_point(r01, tau), c11 = rail_point(r11, tau),
                c10 = rail_point(r10, tau);
      add_quad(c00, c01, c11, c10);
    }
  }

  // Cones the boundary triangles from the piece's smallest vertex; each tetrahedron oriented so that
  // its 4D normal points away from the kept simplex.
  void cone() {
    int apex = tris_[0][0];
    for (const auto& t : tris_) apex = std::min({apex, t[0], t[1], t[2]});
    std::vector<char> holds_apex(face_ + 1, 0);
    for (const auto& t : tris_)
      if (t[0] == apex || t[1] == apex || t[2] == apex) holds_apex[t[3]] = 1;
    for (const auto& tri : tris_) {
      if (holds_apex[tri[3]]) continue;
      std::array<int, 4> t = {apex, tri[0], tri[1], tri[2]};
      Eigen::Matrix4d B;
      for (int k = 0; k < 4; ++k) B.row(k) = bary(t[k]).transpose();
      const double d = B.determinant();
      if (std::abs(d) < 1e-12) continue;  // flat: adds nothing to any slice
      const int o = d > 0 ? 1 : -1;
      if (o < 0) std::swap(t[2], t[3]);
      T_.push_back(t);
    }
  }

  const MatrixX4dRow& P_;
  const int n0_;
  const double t0_, t1_;
  std::vector<double> V_;
  std::vector<std::array<int, 4>> T_;
  std::map<double, std::unordered_map<std::uint64_t, int>> cut_;  // per cut time: rail -> vertex
  std::array<int, 4> outward_;  // the current facet's corners, outward order
  std::unordered_map<int, Eigen::Vector4d> bary_;  // piece vertex -> barycentric coordinates in outward_
  std::vector<std::array<int, 4>> tris_;  // boundary triangles of the current piece and their face
  int face_ = 0;
};

AnimationManifold extract(const Delaunay4& D, const std::vector<unsigned char>& kept, const MatrixX4dRow& P, int n0,
                          double t0, double t1, const TransitionOptions& o) {
  const double bounds[4] = {0.0, o.early, o.late, 1.0};
  PieceWriter writer(P, n0, t0, t1);
  for (int L = 0; L < 3; ++L)
    for (int s = 0; s < D.simplices.rows(); ++s) {
      if (!(kept[s] >> L & 1)) continue;
      for (int i = 0; i < 5; ++i) {
        const int nb = D.neighbors(s, i);
        if (nb >= 0 && (kept[nb] >> L & 1)) continue;
        writer.facet(D.simplices.row(s).data(), i, bounds[L], bounds[L + 1]);
      }
    }
  // Compact to the vertices the tetrahedra use.
  const auto& T = writer.tets();
  std::vector<int> map(writer.num_vertices(), -1);
  int n = 0;
  for (const auto& t : T)
    for (int v : t)
      if (map[v] < 0) map[v] = n++;
  AnimationManifold M;
  M.V.resize(n, 4);
  for (int v = 0; v < writer.num_vertices(); ++v)
    if (map[v] >= 0)
      for (int d = 0; d < 4; ++d) M.V(map[v], d) = writer.vertices()[4 * static_cast<size_t>(v) + d];
  M.T.resize(static_cast<Eigen::Index>(T.size()), 4);
  for (size_t k = 0; k < T.size(); ++k)
    for (int c = 0; c < 4; ++c) M.T(static_cast<Eigen::Index>(k), c) = map[T[k][c]];
  M.times = {t0, t1};
  M.slab_offsets = {0, static_cast<int>(T.size())};
  return M;
}

}  // namespace

TransitionStats& TransitionStats::operator+=(const TransitionStats& o) {
  source_points += o.source_points;
  target_points += o.target_points;
  source_steiner += o.source_steiner;
  target_steiner += o.target_steiner;
  source_missing += o.source_missing;
  target_missing += o.target_missing;
  simplices += o.simplices;
  kept_early += o.kept_early;
  kept_middle += o.kept_middle;
  kept_late += o.kept_late;
  repairs += o.repairs;
  tets += o.tets;
  conform_seconds += o.conform_seconds;
  delaunay_seconds += o.delaunay_seconds;
  classify_seconds += o.classify_seconds;
  extract_seconds += o.extract_seconds;
  total_seconds += o.total_seconds;
  return *this;
}

void check_transition_key(const TriMesh& key, const std::string& what) {
  if (key.V.cols() != 3 || key.F.cols() != 3) throw Error(what + ": positions and triangles need 3 columns");
  if (key.F.rows() < 4) throw Error(what + ": a closed surface needs at least 4 triangles, this has " +
                                    std::to_string(key.F.rows()));
  if (!key.V.allFinite()) throw Error(what + ": a vertex coordinate is not finite (NaN or infinity)");
  for (int f = 0; f < key.F.rows(); ++f) {
    if (key.F.row(f).minCoeff() < 0 || key.F.row(f).maxCoeff() >= key.V.rows())
      throw Error(what + ": triangle " + std::to_string(f) + " has a vertex index out of range");
    if (key.F(f, 0) == key.F(f, 1) || key.F(f, 1) == key.F(f, 2) || key.F(f, 0) == key.F(f, 2))
      throw Error(what + ": triangle " + std::to_string(f) + " repeats a vertex");
  }
  if (!is_closed_and_oriented(key.F)) {
    const Eigen::MatrixXi open = boundary_edges(key.F);
    throw Error(what + ": not a closed, consistently oriented surface (" + std::to_string(open.rows()) +
                " boundary or badly oriented edges); a key of a transition must enclose a volume");
  }
  if (!(enclosed_volume(key.V, key.F) > 0))
    throw Error(what + ": encloses no positive volume (inside-out triangles?)");
  bool crossing = false;
  try {
    crossing = self_intersects(key);
  } catch (const Error& e) {
    throw Error(what + ": " + e.what());
  }
  if (crossing) throw Error(what + ": the surface intersects itself");
}

AnimationManifold build_transition(const TriMesh& source_in, double t0, const TriMesh& target_in, double t1,
                                   const TransitionOptions& o, TransitionStats* stats) {
  const auto start = Clock::now();
  if (!(std::isfinite(t0) && std::isfinite(t1) && t0 < t1))
    throw Error("transition: key times must be finite and increasing");
  if (!(o.early > 0 && o.early < o.late && o.late < 1))
    throw Error("transition: layer times must satisfy 0 < early < late < 1");
  TransitionStats st;
  const TriMesh source = compacted(source_in), target = compacted(target_in);
  auto t = Clock::now();
  ConformingSurface S, T;
  try {
    S = conforming_delaunay_surface(source.V, source.F, o.max_conform_rounds);
  } catch (const Error& e) {
    throw Error(std::string("source key: ") + e.what());
  }
  try {
    T = conforming_delaunay_surface(target.V, target.F, o.max_conform_rounds);
  } catch (const Error& e) {
    throw Error(std::string("target key: ") + e.what());
  }
  add_interior_points(S, o.interior_spacing * mean_edge_length(S));
  add_interior_points(T, o.interior_spacing * mean_edge_length(T));
  st.conform_seconds = seconds_since(t);

  const int n0 = static_cast<int>(S.V.rows() + S.interior.rows()), n1 = static_cast<int>(T.V.rows() + T.interior.rows());
  MatrixX4dRow P(n0 + n1, 4);
  P.topLeftCorner(S.V.rows(), 3) = S.V;
  P.block(S.V.rows(), 0, S.interior.rows(), 3) = S.interior;
  P.block(0, 3, n0, 1).setConstant(t0);
  P.block(n0, 0, T.V.rows(), 3) = T.V;
  P.bottomLeftCorner(T.interior.rows(), 3) = T.interior;
  P.block(n0, 3, n1, 1).setConstant(t1);
  t = Clock::now();
  const Delaunay4 D = delaunay_4d(P);
  st.delaunay_seconds = seconds_since(t);
  t = Clock::now();
  const KeySolid in_s(key_tets(D, 0, n0), P, {S.V, S.F, {}}, S.F);
  const KeySolid in_t(key_tets(D, n0, n0 + n1), P, {T.V, T.F, {}}, T.F.array() + n0);
  {
    std::vector<unsigned char> kept = classify(D, n0, in_s, in_t);
    for (int L = 0; L < 3; ++L) st.repairs += repair_nonmanifold(D, n0, kept, L, static_cast<int>(D.simplices.rows()));
    st.classify_seconds += seconds_since(t);
    t = Clock::now();
    AnimationManifold M = extract(D, kept, P, n0, t0, t1, o);
    st.extract_seconds = seconds_since(t);
    st.source_points = n0;
    st.target_points = n1;
    st.source_steiner = S.steiner;
    st.target_steiner = T.steiner;
    st.source_missing = S.missing;
    st.target_missing = T.missing;
    st.simplices = static_cast<int>(D.simplices.rows());
    for (unsigned char k : kept) {
      st.kept_early += k & 1;
      st.kept_middle += k >> 1 & 1;
      st.kept_late += k >> 2 & 1;
    }
    st.tets = M.num_tets();
    st.total_seconds = seconds_since(start);
    if (stats) *stats = st;
    return M;
  }
}

}  // namespace dfm
