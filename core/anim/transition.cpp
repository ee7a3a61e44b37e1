#include "core/anim/transition.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <future>
#include <cmath>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

#include <Eigen/Geometry>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include "core/anim/conforming_surface.h"
#include "core/anim/conforming_tetgen.h"
#include "core/anim/crossing_fit.h"
#include "core/anim/elastic_pairs.h"
#include "core/anim/delaunay_4d.h"
#include "core/anim/face_protection.h"
#include "core/anim/iso_manifold.h"
#include "core/anim/key_alignment.h"
#include "core/anim/key_distance.h"
#include "core/anim/key_plane.h"
#include "core/anim/key_time_seal.h"
#include "core/anim/layer_extrusion.h"
#include "core/anim/layer_pair_delaunay.h"
#include "core/anim/layer_transients.h"
#include "core/anim/lattice_refinement.h"
#include "core/anim/level_set_relax.h"
#include "core/anim/rounded_distance.h"
#include "core/anim/space_warp.h"
#include "core/anim/transition_points.h"
#include "core/anim/surface_checks.h"
#include "core/bind/closest_surface_point.h"
#include "core/bind/handle_geometry.h"
#include "core/bind/parallel_for.h"
#include "core/util/error.h"
#include "core/util/huge_pages.h"

namespace dfm {

using namespace transition_detail;

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


// The manifold's tetrahedra in one slab per layer interval where none crosses a layer time (else
// the intervals merge).
AnimationManifold into_slabs(IsoManifold iso, const std::vector<double>& layer_times) {
  const int nt = static_cast<int>(iso.T.rows());
  std::vector<double> lo, hi;
  reserve_huge(lo, nt);
  reserve_huge(hi, nt);
  lo.resize(nt);
  hi.resize(nt);
  parallel_for(nt, 0, [&](int t) {
    lo[t] = 1e300, hi[t] = -1e300;
    for (int c = 0; c < 4; ++c) {
      lo[t] = std::min(lo[t], iso.V(iso.T(t, c), 3));
      hi[t] = std::max(hi[t], iso.V(iso.T(t, c), 3));
    }
  });
  // crossed[k]: some tetrahedron has layer_times[k] strictly inside its time span.
  std::vector<char> crossed(layer_times.size(), 0);
  for (int t = 0; t < nt; ++t)
    for (auto k = std::upper_bound(layer_times.begin(), layer_times.end(), lo[t]); k != layer_times.end() && *k < hi[t]; ++k)
      crossed[k - layer_times.begin()] = 1;
  std::vector<double> cuts = {layer_times.front()};
  for (size_t k = 1; k + 1 < layer_times.size(); ++k)
    if (!crossed[k]) cuts.push_back(layer_times[k]);
  cuts.push_back(layer_times.back());
  // Each tetrahedron's slab, then the slabs' rows in tetrahedron order (a counting sort).
  std::vector<int> slab(nt), offsets(cuts.size(), 0);
  for (int t = 0; t < nt; ++t) {
    size_t s = std::upper_bound(cuts.begin(), cuts.end(), lo[t]) - cuts.begin();
    slab[t] = static_cast<int>(std::min(std::max<size_t>(s, 1), cuts.size() - 1) - 1);
    ++offsets[slab[t] + 1];
  }
  for (size_t s = 1; s < offsets.size(); ++s) offsets[s] += offsets[s - 1];
  AnimationManifold M;
  M.times = cuts;
  M.slab_offsets = offsets;
  M.T.resize(nt, 4);
  advise_huge_pages(M.T.data(), sizeof(int) * M.T.size());
  for (int t = 0; t < nt; ++t) M.T.row(offsets[slab[t]]++) = iso.T.row(t);
  M.V = std::move(iso.V);
  return M;
}

}  // namespace

KeyBuildStats& KeyBuildStats::operator+=(const KeyBuildStats& o) {
  points += o.points;
  steiner += o.steiner;
  missing += o.missing;
  flipped += o.flipped;
  chords += o.chords;
  plane_fixes += o.plane_fixes;
  tied += o.tied;
  return *this;
}

TransitionStats& TransitionStats::operator+=(const TransitionStats& o) {
  source += o.source;
  target += o.target;
  middle_points += o.middle_points;
  refined_points += o.refined_points;
  sealed += o.sealed;
  relaxed += o.relaxed;
  transients += o.transients;
  simplices += o.simplices;
  tets += o.tets;
  elastic_pairs += o.elastic_pairs;
  conform_seconds += o.conform_seconds;
  field_seconds += o.field_seconds;
  delaunay_seconds += o.delaunay_seconds;
  extract_seconds += o.extract_seconds;
  relax_seconds += o.relax_seconds;
  turn_degrees = o.turn_degrees;
  scale = o.scale;
  align_seconds += o.align_seconds;
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

namespace {

// Every point of the transition with its field value and local time u: the middle lattice once per
// layer (at u[1..K]), the source key's (at 0), the target key's (at 1), with where each part starts
// (the middle first: it is cut while the keys are still being built).
struct FieldPoints {
  std::vector<Eigen::RowVector4d> points;  // x, y, z, u
  std::vector<double> values;
  std::vector<char> anchored;
  int lattice_size = 0, source_begin = 0, source_end = 0, target_begin = 0;
  std::vector<int> layer_begin;  // per middle layer

  // Values are kept at least `away` from 0: a crossing that close to a point would make slivers. (Not
  // much farther: the shift moves the level set, which reads as noise in the slices' normals.)
  // (Snapping such points onto the level set instead, as Raman and Wenger's snap marching cubes do,
  // can pinch it where the field has a saddle; moving the level set by `away` cannot.) A key's surface
  // vertices are anchored (f null): the level set passes through them.
  void add(const Eigen::MatrixXd& P, double u, const Eigen::VectorXd* f, double away, double anchor_value) {
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      points.push_back(Eigen::RowVector4d(P(i, 0), P(i, 1), P(i, 2), u));
      values.push_back(f ? clamp_away_from_zero((*f)[i], away) : anchor_value);
      anchored.push_back(f == nullptr);
    }
  }
};

// The middle lattice where any middle layer's zero set may pass (transition.h), and its points'
// rounded signed distances to both keys (rounded_distance.h).
struct Lattice {
  Eigen::MatrixXd X;
  Eigen::VectorXd d_s, d_t;  // rounded
  Eigen::MatrixXd g_s, g_t;  // their gradients
  Tetrahedralization delaunay;  // of X
  MatrixX4iRow K;               // its tetrahedra, each sorted ascending, the list sorted
};

// T's tetrahedra as hull_facets_in lists them (layer_extrusion.h): corners ascending, rows sorted.
MatrixX4iRow sorted_tets(const Eigen::MatrixXi& T) {
  std::vector<std::array<int, 4>> tets(T.rows());
  for (Eigen::Index t = 0; t < T.rows(); ++t) {
    for (int c = 0; c < 4; ++c) tets[t][c] = T(t, c);
    std::sort(tets[t].begin(), tets[t].end());
  }
  std::sort(tets.begin(), tets.end());
  MatrixX4iRow K(T.rows(), 4);
  for (size_t i = 0; i < tets.size(); ++i)
    for (int c = 0; c < 4; ++c) K(static_cast<Eigen::Index>(i), c) = tets[i][c];
  return K;
}

Lattice middle_lattice(const Box& box, double h_mid, const SignedDistance& d_s, const SignedDistance& d_t, double u_first,
                       double u_last, double rounding) {
  Lattice L;
  // A lower bound on the smallest |blend| over [u_first, u_last] (0 where it may change sign; it is
  // linear in u): a rounded distance is within rounding |d| of d. Divided by its Lipschitz constant,
  // as lattice_band_points assumes 1.
  const double lipschitz = 1 + rounding;
  L.X = lattice_band_points(box, h_mid, 1.2 * h_mid / lipschitz, [&](const Eigen::MatrixXd& Y) {
    const Eigen::VectorXd s = d_s(Y), e = d_t(Y);
    Eigen::VectorXd g(Y.rows());
    for (Eigen::Index i = 0; i < Y.rows(); ++i) {
      const double a = (1 - u_first) * s[i] + u_first * e[i], b = (1 - u_last) * s[i] + u_last * e[i];
      const double sa = rounding * ((1 - u_first) * std::abs(s[i]) + u_first * std::abs(e[i]));
      const double sb = rounding * ((1 - u_last) * std::abs(s[i]) + u_last * std::abs(e[i]));
      const bool positive = a - sa > 0 && b - sb > 0, negative = a + sa < 0 && b + sb < 0;
      g[i] = positive || negative ? std::min(std::abs(a) - sa, std::abs(b) - sb) / lipschitz : 0.0;
    }
    return g;
  });
  L.d_s = rounded_distance(d_s, L.X, rounding, &L.g_s);
  L.d_t = rounded_distance(d_t, L.X, rounding, &L.g_t);
  L.delaunay = delaunay_3d(L.X);
  L.K = sorted_tets(L.delaunay.tets);
  return L;
}

// The middle layers' points.
FieldPoints layer_points(const Lattice& L, const std::vector<double>& u, double h_mid, bool fit) {
  FieldPoints p;
  p.lattice_size = static_cast<int>(L.X.rows());
  const std::vector<std::array<int, 2>> edges = fit ? tet_edges(L.K) : std::vector<std::array<int, 2>>{};
  for (size_t k = 1; k + 1 < u.size(); ++k) {
    Eigen::VectorXd f = (1 - u[k]) * L.d_s + u[k] * L.d_t;
    if (fit) f = fit_crossings(L.X, edges, f, (1 - u[k]) * L.g_s + u[k] * L.g_t);
    p.layer_begin.push_back(static_cast<int>(p.points.size()));
    p.add(L.X, u[k], &f, kAway * h_mid, -kMinValue * h_mid);
  }
  return p;
}

// A key's points at local time u after them (h: the key's spacing): its surface vertices, then its
// fill. Returns where they start.
int add_key_points(FieldPoints& p, const KeyLayer& k, double u, double h, double h_mid) {
  const int begin = static_cast<int>(p.points.size());
  const double eps = kMinValue * h_mid;
  p.add(k.surface.V, u, nullptr, eps, -eps);
  p.add(k.surface.fill, u, &k.fill_values, kAway * h, -eps);
  return begin;
}

// The 4D Delaunay triangulation of A at local time ua followed by B at ub (u scaled by time_scale), in
// the points' order: A's rows, then B's.
Delaunay4 end_triangulation(const Eigen::MatrixXd& A, double ua, const Eigen::MatrixXd& B, double ub, double time_scale) {
  MatrixX4dRow P4(A.rows() + B.rows(), 4);
  P4.topLeftCorner(A.rows(), 3) = A;
  P4.topRightCorner(A.rows(), 1).setConstant(ua * time_scale);
  P4.bottomLeftCorner(B.rows(), 3) = B;
  P4.bottomRightCorner(B.rows(), 1).setConstant(ub * time_scale);
  return delaunay_4d(P4);
}

// S's point numbers: those below `split` plus a, the others minus split plus b.
void renumber(MatrixX5iRow& S, int split, int a, int b) {
  for (Eigen::Index s = 0; s < S.rows(); ++s)
    for (int c = 0; c < 5; ++c) S(s, c) += S(s, c) < split ? a : b - split;
}

// The middle layers' values as layer_transients.h takes them: the lattice points, each layer's
// time and values.
struct LayerValues {
  Eigen::MatrixXd X;
  std::vector<double> u;
  std::vector<Eigen::VectorXd> v;
};

LayerValues layer_values(const FieldPoints& p) {
  const int layers = static_cast<int>(p.layer_begin.size()), n = p.lattice_size;
  LayerValues l;
  l.X.resize(n, 3);
  for (int i = 0; i < n; ++i) l.X.row(i) = p.points[p.layer_begin.front() + i].head<3>();
  l.v.assign(layers, Eigen::VectorXd(n));
  for (int k = 0; k < layers; ++k) {
    l.u.push_back(p.points[p.layer_begin[k]][3]);
    for (int i = 0; i < n; ++i) l.v[k][i] = p.values[p.layer_begin[k] + i];
  }
  return l;
}

LayerTransientOptions transient_options(const TransitionOptions& o, double h_mid) {
  LayerTransientOptions lo;
  lo.radius = 2 * h_mid;
  lo.max_life = o.transient_life;
  return lo;
}

// How far around a bulging edge's midpoint the lattice is refined, in spacings.
constexpr double kRefineReach = 0.5;

// Merges the middle layers' short-lived topology (layer_transients.h) into events at their start, on
// K (lattice numbers); returns how many.
int merge_transients(FieldPoints& p, const MatrixX4iRow& K, const TransitionOptions& o, double h_mid) {
  LayerValues l = layer_values(p);
  const LayerTransientStats st = merge_layer_transients(l.X, K, l.u, l.v, kAway * h_mid, transient_options(o, h_mid));
  for (size_t k = 0; k < l.v.size(); ++k)
    for (int i = 0; i < p.lattice_size; ++i) p.values[p.layer_begin[k] + i] = l.v[k][i];
  return st.events;
}

// The rows of `centres` farther than `reach` from every point of L listed in `points`.
Eigen::MatrixXd away_from(const Eigen::MatrixXd& centres, const Lattice& L, const std::vector<int>& points, double reach) {
  Eigen::MatrixXd kept(centres.rows(), 3);
  Eigen::Index n = 0;
  for (Eigen::Index r = 0; r < centres.rows(); ++r)
    if (std::none_of(points.begin(), points.end(), [&](int p) { return (centres.row(r) - L.X.row(p)).squaredNorm() < reach * reach; }))
      kept.row(n++) = centres.row(r);
  return kept.topRows(n);
}

// Adds the points P to L with their rounded distances and gradients, and tetrahedralizes it again.
void add_lattice_points(Lattice& L, const Eigen::MatrixXd& P, const SignedDistance& d_s, const SignedDistance& d_t,
                        double rounding) {
  Eigen::MatrixXd g_s, g_t;
  const Eigen::VectorXd e_s = rounded_distance(d_s, P, rounding, &g_s), e_t = rounded_distance(d_t, P, rounding, &g_t);
  const Eigen::Index n = L.X.rows(), m = P.rows();
  auto append = [&](auto& to, const auto& rows) {
    to.conservativeResize(n + m, to.cols());
    to.bottomRows(m) = rows;
  };
  append(L.X, P);
  append(L.g_s, g_s);
  append(L.g_t, g_t);
  append(L.d_s, e_s);
  append(L.d_t, e_t);
  L.delaunay = delaunay_3d(L.X);
  L.K = sorted_tets(L.delaunay.tets);
}

// Refines L where the blend bulges off its chords near its zero set (lattice_refinement.h), away
// from the short-lived events merge_transients would merge: a finer lattice there reads a gap
// closing through more, earlier bridges, and the merge would move the event's start. Returns the
// points added.
int refine_lattice(Lattice& L, const Box& box, double h_mid, const SignedDistance& d_s, const SignedDistance& d_t,
                   const std::vector<double>& u, const TransitionOptions& o) {
  if (!(o.refine_tolerance > 0)) return 0;
  Eigen::MatrixXd mid = bulging_edge_midpoints(L.X, tet_edges(L.K), L.d_s, L.d_t, L.g_s, L.g_t,
                                               std::vector<double>(u.begin() + 1, u.end() - 1), h_mid, o.refine_tolerance);
  if (o.transient_life > 0 && mid.rows() > 0) {
    const LayerValues l = layer_values(layer_points(L, u, h_mid, o.fit_crossings));
    const LayerTransientOptions t = transient_options(o, h_mid);
    mid = away_from(mid, L, layer_transient_points(l.X, L.K, l.u, l.v, t), 2 * t.radius + kRefineReach * h_mid);
  }
  const Eigen::MatrixXd extra = finer_lattice_points(lattice_origin(box, h_mid), h_mid, mid, kRefineReach * h_mid);
  if (extra.rows() > 0) add_lattice_points(L, extra, d_s, d_t, o.crease_rounding);
  return static_cast<int>(extra.rows());
}

IsoField iso_field(const FieldPoints& p, double t0, double t1) {
  IsoField field;
  field.points.resize(static_cast<Eigen::Index>(p.points.size()), 4);
  advise_huge_pages(field.points.data(), sizeof(double) * field.points.size());
  for (size_t i = 0; i < p.points.size(); ++i)
    field.points.row(static_cast<Eigen::Index>(i)) << p.points[i].head<3>(), t0 + p.points[i][3] * (t1 - t0);
  field.values = Eigen::Map<const Eigen::VectorXd>(p.values.data(), static_cast<Eigen::Index>(p.values.size()));
  field.anchored = p.anchored;
  return field;
}

KeyBuildStats key_build_stats(const KeyLayer& k) {
  KeyBuildStats st;
  st.steiner = k.surface.steiner;
  st.missing = k.surface.missing;
  st.flipped = static_cast<int>(k.surface.flipped.size());
  st.chords = k.chords;
  return st;
}

// The middle lattice, built once by whichever thread asks first.
class SharedLattice {
 public:
  // u: the layers' local times, the keys' included.
  SharedLattice(const Box& box, double h_mid, const SignedDistance& d_s, const SignedDistance& d_t,
                const std::vector<double>& u, const TransitionOptions& o)
      : box_(box), h_mid_(h_mid), d_s_(d_s), d_t_(d_t), u_(u), o_(o) {}
  const Lattice& get() {
    std::call_once(once_, [&] {
      const auto t = Clock::now();
      L_ = middle_lattice(box_, h_mid_, d_s_, d_t_, u_[1], u_[u_.size() - 2], o_.crease_rounding);
      refined_ = refine_lattice(L_, box_, h_mid_, d_s_, d_t_, u_, o_);
      seconds_ = seconds_since(t);
    });
    return L_;
  }
  double seconds() const { return seconds_; }
  int refined() const { return refined_; }

 private:
  const Box& box_;
  double h_mid_;
  const SignedDistance &d_s_, &d_t_;
  const std::vector<double>& u_;
  const TransitionOptions& o_;
  std::once_flag once_;
  Lattice L_;
  double seconds_ = 0;
  int refined_ = 0;
};

// What both keys' ends share.
struct EndSetting {
  const Box& box;
  double h_mid, time_scale;
  const TransitionOptions& o;
  const std::vector<double>& u;  // the layers' local times, the keys' included
  SharedLattice& lattice;
};

// A key's layer, its tetrahedra for correcting its plane (key_plane.h) and its end of the 4D
// triangulation (end_triangulation: the source's points before the first layer's lattice, the last
// layer's lattice before the target's).
struct KeyEnd {
  KeyLayer layer;
  KeyTets tets;
  MatrixX5iRow D;
  bool tied = false;
  double conform_seconds = 0, delaunay_seconds = 0;
};

// A key's end of the 4D triangulation: the Voronoi overlay of its tetrahedra and the lattice's
// (layer_pair_delaunay.h), else, on an exact tie, CGAL's dD triangulation, which must then read the
// lattice's tetrahedra as K.
MatrixX5iRow end_simplices(const KeyTets& key, const Lattice& L, bool is_source, const EndSetting& at, bool& tied) {
  const DelaunayLayer k{key.points, key.tets, key.neighbours}, l{L.X, L.delaunay.tets, L.delaunay.neighbours};
  if (auto S = is_source ? layer_pair_delaunay(k, l) : layer_pair_delaunay(l, k)) return std::move(*S);
  tied = true;
  const Delaunay4 D = is_source ? end_triangulation(key.points, 0.0, L.X, at.u[1], at.time_scale)
                                : end_triangulation(L.X, at.u[at.o.layers], key.points, 1.0, at.time_scale);
  const int first = is_source ? static_cast<int>(key.points.rows()) : 0;
  if (!(hull_facets_in(D, first, first + static_cast<int>(L.X.rows())) == L.K))
    throw Error("transition: the 4D triangulation's tetrahedra in the middle layer are not the lattice's");
  return D.simplices;
}

KeyEnd key_end(const char* which, const TriMesh& key, const SignedDistance& d, double h, bool is_source,
               const EndSetting& at) {
  KeyEnd e;
  auto t = Clock::now();
  try {
    e.layer = key_layer(key, d, at.box, h, at.h_mid, at.o.max_conform_rounds, is_source ? 0 : at.o.layers + 1);
  } catch (const Error& x) {
    throw Error(std::string(which) + " key: " + x.what());
  }
  e.conform_seconds = seconds_since(t);
  t = Clock::now();
  e.tets = key_tets(e.layer.surface, e.layer.fill_values);
  e.D = end_simplices(e.tets, at.lattice.get(), is_source, at, e.tied);
  e.delaunay_seconds = seconds_since(t);
  return e;
}

// The middle layers (transition.h): the lattice at each layer's time, its short-lived events merged,
// and K x each layer interval where the field changes sign, by staircase prisms, cut into `level_set`
// as its first part.
struct Middle {
  FieldPoints p;
  int simplices = 0, transients = 0;
  double field_seconds = 0, prism_seconds = 0, extract_seconds = 0;
};

Middle middle_layers(SharedLattice& lattice, const std::vector<double>& u, double t0, double t1, const TransitionOptions& o,
                     double h_mid, IsoManifoldBuilder& level_set) {
  Middle m;
  const Lattice& L = lattice.get();
  auto t = Clock::now();
  m.p = layer_points(L, u, h_mid, o.fit_crossings);
  m.field_seconds = lattice.seconds() + seconds_since(t);
  t = Clock::now();
  FieldPoints& p = m.p;
  m.transients = merge_transients(p, L.K, o, h_mid);
  const MatrixX5iRow S = extrude_tets(L.K, p.layer_begin, [&](Eigen::Index tet, int k) {
    int neg = 0;
    for (int c = 0; c < 4; ++c)
      neg += (p.values[p.layer_begin[k] + L.K(tet, c)] < 0) + (p.values[p.layer_begin[k + 1] + L.K(tet, c)] < 0);
    return neg > 0 && neg < 8;
  });
  m.simplices = static_cast<int>(S.rows());
  m.prism_seconds = seconds_since(t);
  t = Clock::now();
  level_set.add(iso_field(p, t0, t1), S);
  m.extract_seconds = seconds_since(t);
  return m;
}

// The field's morph between keys already in one frame (transition.h, "The field"), with o.layers
// middle layers. Its vertices in the target key's plane have time t0 + 1.0 * (t1 - t0).
AnimationManifold morph(const TriMesh& source, double t0, const TriMesh& target, double t1, const TransitionOptions& o,
                        TransitionStats& st) {
  const double h_s = o.spacing * mean_edge_length(source.V, source.F), h_t = o.spacing * mean_edge_length(target.V, target.F);
  const double h_mid = std::min(h_s, h_t);
  Box box{source.V.colwise().minCoeff().cwiseMin(target.V.colwise().minCoeff()),
          source.V.colwise().maxCoeff().cwiseMax(target.V.colwise().maxCoeff())};
  box.lo.array() -= 2 * h_mid;
  box.hi.array() += 2 * h_mid;

  // Layer k of K sits at local time (k - 1/2) / K, away from the round times a user scrubs to.
  std::vector<double> u = {0.0};
  for (int k = 1; k <= o.layers; ++k) u.push_back((k - 0.5) / o.layers);
  u.push_back(1.0);
  // Time scaled so that a key and its nearest layer lie two lattice spacings apart.
  const double time_scale = 4.0 * h_mid * o.layers;

  // Each key's layer and its end of the 4D triangulation on a thread of its own (the two keys' layers
  // often cost very different times), and the middle layers on a third, cut first.
  const SignedDistance d_s(source.V, source.F), d_t(target.V, target.F);
  SharedLattice lattice(box, h_mid, d_s, d_t, u, o);
  const EndSetting at{box, h_mid, time_scale, o, u, lattice};
  IsoManifoldBuilder level_set;
  auto middle = std::async(std::launch::async, middle_layers, std::ref(lattice), std::cref(u), t0, t1, std::cref(o), h_mid,
                           std::ref(level_set));
  auto target_end = std::async(std::launch::async, key_end, "target", std::cref(target), std::cref(d_t), h_t, false, std::cref(at));
  KeyEnd S = key_end("source", source, d_s, h_s, true, at);
  Middle m = middle.get();
  FieldPoints& p = m.p;
  st.field_seconds = m.field_seconds;
  st.transients = m.transients;

  // The source's end while the target's is still being built (often the longer one).
  auto t = Clock::now();
  const int ns = static_cast<int>(S.tets.points.rows());
  p.source_begin = add_key_points(p, S.layer, 0.0, h_s, h_mid);
  p.source_end = static_cast<int>(p.points.size());
  renumber(S.D, ns, p.source_begin, p.layer_begin.front());
  double delaunay_seconds = seconds_since(t);
  t = Clock::now();
  level_set.add(iso_field(p, t0, t1), S.D);
  double extract_seconds = m.extract_seconds + seconds_since(t);

  KeyEnd T = target_end.get();
  st.conform_seconds = std::max(S.conform_seconds, T.conform_seconds);
  t = Clock::now();
  p.target_begin = add_key_points(p, T.layer, 1.0, h_t, h_mid);
  renumber(T.D, p.lattice_size, p.layer_begin.back(), p.target_begin);
  st.delaunay_seconds = std::max({S.delaunay_seconds, T.delaunay_seconds, m.prism_seconds}) + delaunay_seconds + seconds_since(t);
  st.simplices = static_cast<int>(S.D.rows() + m.simplices + T.D.rows());

  t = Clock::now();
  const IsoField field = iso_field(p, t0, t1);
  level_set.add(field, T.D);
  IsoManifold iso = level_set.finish(field);
  const KeyPlaneStats plane_s = correct_key_plane(iso.V, iso.T, t0, S.tets);
  const KeyPlaneStats plane_t = correct_key_plane(iso.V, iso.T, t1, T.tets);
  const double seal = 1e-6 * (t1 - t0);  // how far inside the slab a sealing cone's point sits
  st.sealed = seal_key_time(iso.V, iso.T, t0, t0 + seal) + seal_key_time(iso.V, iso.T, t1, t1 - seal);
  std::vector<double> layer_times;
  for (double x : u) layer_times.push_back(t0 + x * (t1 - t0));
  layer_times.back() = t1;
  if (o.relax_rounds > 0) {
    // Only from the first middle layer to the last: the keys' planes and their Delaunay joins stay.
    std::vector<char> movable(iso.V.rows());
    for (Eigen::Index v = 0; v < iso.V.rows(); ++v)
      movable[v] = iso.V(v, 3) >= layer_times[1] && iso.V(v, 3) <= layer_times[o.layers];
    LevelSetRelaxOptions r;
    r.rounds = o.relax_rounds;
    r.radius = 0.8 * h_mid;  // within a lattice cell: wider fits reach past the two edges' ring
    r.max_move = 0.5 * h_mid;
    r.time_scale = 0.5 * h_mid * o.layers / (t1 - t0);  // a layer interval as long as half a lattice spacing
    const auto relax_start = Clock::now();
    st.relaxed = relax_level_set(iso.V, iso.T, movable, r).moved;
    st.relax_seconds = seconds_since(relax_start);
  }
  AnimationManifold M = into_slabs(std::move(iso), layer_times);
  st.extract_seconds = extract_seconds + seconds_since(t);

  st.source = key_build_stats(S.layer);
  st.target = key_build_stats(T.layer);
  st.source.tied = S.tied;
  st.target.tied = T.tied;
  st.source.points = p.source_end - p.source_begin;
  st.middle_points = p.lattice_size;
  st.refined_points = lattice.refined();
  st.target.points = static_cast<int>(p.points.size()) - p.target_begin;
  st.source.plane_fixes = plane_s.bridges + plane_s.carved;
  st.target.plane_fixes = plane_t.bridges + plane_t.carved;
  st.tets = M.num_tets();
  return M;
}

}  // namespace

namespace {

double bounding_diagonal(const Eigen::MatrixXd& V) { return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm(); }

// Picked points farther than this from their key, in its bounding-box diagonals, are refused.
constexpr double kPairReach = 0.02;

// Steps of the picked pairs' warp (space_warp.h: WarpPath).
constexpr int kWarpSteps = 8;

// The reference target T^ = W^-1(A(T)) (transition.h) with the vertices `carried` (W^-1 of the
// target's in the source's frame). Throws dfm::Error when W folds space on either key or T^ is not a
// valid key.
TriMesh checked_reference(const TriMesh& source, const TriMesh& target, const WarpPath& w, const Eigen::MatrixXd& carried) {
  TriMesh reference{carried, target.F, {}};
  if (w.identity()) return reference;
  // W_u must not turn space inside out where the morph is: on both keys' paths.
  for (const Eigen::MatrixXd* X : std::initializer_list<const Eigen::MatrixXd*>{&source.V, &reference.V})
    if (const auto f = first_fold(w, *X))
      throw Error("the picked pairs fold space near (" + std::to_string((*X)(f->row, 0)) + " " +
                  std::to_string((*X)(f->row, 1)) + " " + std::to_string((*X)(f->row, 2)) + ") at u = " +
                  std::to_string(f->u) + ": pin more of the shape, or move the pairs less");
  check_transition_key(reference, "the target key warped by the picked pairs");
  return reference;
}

// Puts the aligned (and warped) morph's vertices where they belong (transition.h, "The placement"):
// a vertex at time t goes through the warp and the placement interpolated at its own u. The source
// key's plane stays as it is; in the target key's plane each vertex of the reference target
// (`reference`, the morph's input) becomes the target's own vertex, bit for bit, and any other
// point on it (a surface Steiner point) the point of the target's triangle with its barycentric
// coordinates, so that the slice there is the target.
void place(AnimationManifold& M, double t0, double t1, const KeyPlacement& p, const WarpPath& w,
           const TriMesh& reference, const TriMesh& target) {
  const double T1 = t0 + 1.0 * (t1 - t0);
  struct Bits {
    size_t operator()(const Eigen::RowVector3d& x) const {
      return std::hash<double>()(x[0]) * 31 + std::hash<double>()(x[1]) * 17 + std::hash<double>()(x[2]);
    }
  };
  std::unordered_map<Eigen::RowVector3d, int, Bits> own;
  for (int v = 0; v < reference.V.rows(); ++v) own.emplace(reference.V.row(v), v);
  const double diag = bounding_diagonal(reference.V);
  std::unique_ptr<SurfaceLocator> locate;
  for (int v = 0; v < M.num_vertices(); ++v) {
    const double t = M.V(v, 3);
    if (t == t0) continue;
    const Eigen::RowVector3d x = M.V.row(v).head<3>();
    Eigen::RowVector3d y;
    if (t == T1) {
      const auto it = own.find(x);
      if (it != own.end()) {
        y = target.V.row(it->second);
      } else if (!w.identity()) {
        if (!locate) locate = std::make_unique<SurfaceLocator>(reference.V, reference.F, 1e-6 * diag);
        const SurfaceSample s = locate->closest(x.transpose());
        if (s.found()) {
          y.setZero();
          for (int k = 0; k < 3; ++k) y += s.weight[k] * target.V.row(s.vertex[k]);
        } else {
          y = placed_at(p, 1, warp(w, x));
        }
      } else {
        y = placed_at(p, 1, x);
      }
    } else {
      const double u = std::min(1.0, std::max(0.0, (t - t0) / (t1 - t0)));
      y = placed_at(p, u, warp(w, x, u));
    }
    M.V.row(v).head<3>() = y;
  }
}

}  // namespace

std::optional<PairProblem> transition_pair_problem(const TriMesh& source, const TriMesh& target,
                                                   const Eigen::MatrixXd& pairs) {
  if (pairs.rows() == 0) return std::nullopt;
  if (pairs.cols() != 6) return PairProblem{0, "a pair needs 6 numbers (x0 y0 z0 x1 y1 z1), got " + std::to_string(pairs.cols())};
  for (int i = 0; i < pairs.rows(); ++i)
    if (!pairs.row(i).allFinite()) return PairProblem{i, "a coordinate is not finite (NaN or infinity)"};
  const SignedDistance d0(source.V, source.F), d1(target.V, target.F);
  const Eigen::VectorXd e0 = d0(pairs.leftCols(3)).cwiseAbs(), e1 = d1(pairs.rightCols(3)).cwiseAbs();
  const double r0 = kPairReach * bounding_diagonal(source.V), r1 = kPairReach * bounding_diagonal(target.V);
  for (int i = 0; i < pairs.rows(); ++i) {
    if (e0[i] > r0)
      return PairProblem{i, "the first point is " + std::to_string(e0[i]) + " from its key (more than " +
                                std::to_string(r0) + ", 2% of the key's bounding-box diagonal)"};
    if (e1[i] > r1)
      return PairProblem{i, "the second point is " + std::to_string(e1[i]) + " from its key (more than " +
                                std::to_string(r1) + ", 2% of the key's bounding-box diagonal)"};
    for (int j = 0; j < i; ++j)
      if (pairs.row(j).head<3>() == pairs.row(i).head<3>())
        return PairProblem{i, "its first point repeats pair " + std::to_string(j + 1) + "'s"};
  }
  return std::nullopt;
}

KeyPlacement transition_placement(const TriMesh& source, const TriMesh& target, const TransitionOptions& o) {
  if (!o.align) return {};
  return key_placement(solid_moments(source.V, source.F), solid_moments(target.V, target.F));
}

Eigen::RowVector3d pair_position(const KeyPlacement& p, const Eigen::Matrix<double, 1, 6>& pair, double u) {
  const Eigen::RowVector3d x0 = pair.head<3>(), x1 = to_source_frame(p, pair.tail<3>());
  return placed_at(p, u, x0 + u * (x1 - x0));
}

AnimationManifold build_transition(const TriMesh& source_in, double t0, const TriMesh& target_in, double t1,
                                   const TransitionOptions& o, TransitionStats* stats) {
  const auto start = Clock::now();
  if (!(std::isfinite(t0) && std::isfinite(t1) && t0 < t1))
    throw Error("transition: key times must be finite and increasing");
  if (o.layers < 1 || !(o.spacing > 0)) throw Error("transition: needs at least one layer and a positive spacing");
  if (!(o.max_turn_per_layer > 0)) throw Error("transition: the turn per layer must be positive");
  if (!(o.transient_life >= 0)) throw Error("transition: the transients' life must be 0 or more");
  if (!(o.refine_tolerance >= 0)) throw Error("transition: the refinement tolerance must be 0 or more");
  if (!(o.crease_rounding >= 0 && o.crease_rounding < 1)) throw Error("transition: the crease rounding must be in [0, 1)");
  if (o.elastic_samples < 0) throw Error("transition: the elastic samples must be 0 or more");
  TransitionStats st;
  const TriMesh source = compacted(source_in), target = compacted(target_in);
  if (const auto bad = transition_pair_problem(source, target, o.pairs))
    throw Error("picked pair " + std::to_string(bad->pair + 1) + ": " + bad->problem);

  // The placement (key_alignment.h) and the warp (space_warp.h), both in the source's frame.
  auto t = Clock::now();
  const KeyPlacement p = transition_placement(source, target, o);
  Eigen::MatrixXd picked(o.pairs.rows(), 6);
  if (o.pairs.rows() > 0) picked << o.pairs.leftCols(3), to_source_frame(p, o.pairs.rightCols(3));
  const TriMesh framed{to_source_frame(p, target.V), target.F, {}};
  ElasticFit fit;
  if (o.pairs.rows() > 0 && o.elastic_samples > 0) {
    ElasticPairOptions eo;
    eo.samples = o.elastic_samples;
    eo.steps = kWarpSteps;
    fit = elastic_pairs(source, framed, picked, eo);
  }
  WarpPath w;
  TriMesh reference;
  if (fit.pairs.rows() > 0) {
    try {
      reference = checked_reference(source, target, fit.warp, fit.carried);
      w = std::move(fit.warp);
    } catch (const Error&) {
      fit.pairs.resize(0, 6);  // a warped target that is not a valid key: the picked pairs decide
    }
  }
  if (fit.pairs.rows() == 0) {
    w = fit_warp_path(picked.leftCols(3), picked.rightCols(3), kWarpSteps);
    reference = checked_reference(source, target, w, unwarp_rows(w, framed.V));
  }
  st.elastic_pairs = static_cast<int>(fit.pairs.rows());
  TransitionOptions layered = o;
  const double turn = Eigen::AngleAxisd(p.R).angle() * 180 / M_PI;
  // In fours: layer k of K sits at (k - 1/2) / K, which then never falls on t = 1/4, 1/2 or 3/4 (a
  // slice there would be the layer's own coarse triangulation).
  const int needed = static_cast<int>(std::ceil(turn / o.max_turn_per_layer - 1e-9));
  if (needed > o.layers) layered.layers = 4 * ((needed + 3) / 4);
  st.turn_degrees = turn;
  st.scale = p.scale;
  st.align_seconds = seconds_since(t);

  AnimationManifold M = morph(source, t0, reference, t1, layered, st);
  t = Clock::now();
  if (o.align || !w.identity()) place(M, t0, t1, p, w, reference, target);
  st.align_seconds += seconds_since(t);
  st.total_seconds = seconds_since(start);
  if (stats) *stats = st;
  return M;
}

}  // namespace dfm
