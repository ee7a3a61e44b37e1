#include "core/anim/transition.h"

#include <algorithm>
#include <chrono>
#include <future>
#include <cmath>
#include <memory>
#include <unordered_map>
#include <vector>

#include <Eigen/Geometry>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include "core/anim/conforming_surface.h"
#include "core/anim/conforming_tetgen.h"
#include "core/anim/delaunay_4d.h"
#include "core/anim/face_protection.h"
#include "core/anim/iso_manifold.h"
#include "core/anim/key_alignment.h"
#include "core/anim/key_distance.h"
#include "core/anim/key_plane.h"
#include "core/anim/key_time_seal.h"
#include "core/anim/layer_extrusion.h"
#include "core/anim/space_warp.h"
#include "core/anim/surface_checks.h"
#include "core/bind/closest_surface_point.h"
#include "core/bind/handle_geometry.h"
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


// ---- the points and the field ------------------------------------------------------------------

struct Box {
  Eigen::RowVector3d lo, hi;
};

// A deterministic jitter in [-0.5, 0.5)^3 per grid point and layer (a grid is cospherical
// everywhere, which the 4D Delaunay triangulation resolves slowly and the field does not need).
Eigen::RowVector3d jitter(std::uint64_t i, std::uint64_t layer) {
  Eigen::RowVector3d j;
  std::uint64_t x = i * 0x9E3779B97F4A7C15ull ^ (layer + 1) * 0xC2B2AE3D27D4EB4Full;
  for (int d = 0; d < 3; ++d) {
    x ^= x >> 33;
    x *= 0xFF51AFD7ED558CCDull;
    x ^= x >> 29;
    j[d] = static_cast<double>(x >> 11) * 0x1.0p-53 - 0.5;
  }
  return j;
}

// Points off a level set, on a grid of spacing h: those where lo <= |field| < hi (found from a
// coarse grid of spacing 2h: a signed distance, or a blend of them, changes by at most the distance
// moved), and the coarse grid's points where |field| >= far (none when far is infinite).
template <class Field>
std::pair<Eigen::MatrixXd, Eigen::VectorXd> band_points(const Box& box, double h, double lo, double hi, double far,
                                                         int layer, const Field& field) {
  const double H = 2 * h;
  const Eigen::Array3i n = (((box.hi - box.lo) / H).array().ceil().cast<int>() + 1).transpose();
  if (static_cast<double>(n.prod()) > 4e6) throw Error("transition: the point spacing is too fine for the keys' size");
  auto at = [&](int x, int y, int z) {  // fine grid coordinates
    const std::uint64_t i = (static_cast<std::uint64_t>(x) * (2 * n[1] + 1) + y) * (2 * n[2] + 1) + z;
    return (box.lo + Eigen::RowVector3d(x, y, z) * h + 0.3 * h * jitter(i, layer)).eval();
  };
  Eigen::MatrixXd C(n.prod(), 3);
  for (int x = 0, i = 0; x < n[0]; ++x)
    for (int y = 0; y < n[1]; ++y)
      for (int z = 0; z < n[2]; ++z) C.row(i++) = at(2 * x, 2 * y, 2 * z);
  const Eigen::VectorXd fc = field(C);
  auto coarse = [&](int x, int y, int z) { return fc[(static_cast<Eigen::Index>(x) * n[1] + y) * n[2] + z]; };
  std::vector<Eigen::RowVector3d> pts;
  std::vector<double> vals;
  for (Eigen::Index i = 0; i < C.rows(); ++i)
    if (std::abs(fc[i]) >= far) pts.push_back(C.row(i)), vals.push_back(fc[i]);
  if (hi > lo) {
    // Every fine point of a coarse cell the band may reach (a cell's far faces belong to the next).
    std::vector<Eigen::RowVector3d> fine;
    const double reach = hi + 2 * H;
    for (int x = 0; x + 1 < n[0]; ++x)
      for (int y = 0; y + 1 < n[1]; ++y)
        for (int z = 0; z + 1 < n[2]; ++z) {
          double m = 1e300;
          for (int c = 0; c < 8; ++c) m = std::min(m, std::abs(coarse(x + (c & 1), y + (c >> 1 & 1), z + (c >> 2 & 1))));
          if (m > reach) continue;
          for (int c = 0; c < 27; ++c) {
            const int dx = c % 3, dy = c / 3 % 3, dz = c / 9;
            if ((dx == 2 && x + 2 < n[0]) || (dy == 2 && y + 2 < n[1]) || (dz == 2 && z + 2 < n[2])) continue;
            fine.push_back(at(2 * x + dx, 2 * y + dy, 2 * z + dz));
          }
        }
    Eigen::MatrixXd Fm(static_cast<Eigen::Index>(fine.size()), 3);
    for (size_t i = 0; i < fine.size(); ++i) Fm.row(static_cast<Eigen::Index>(i)) = fine[i];
    const Eigen::VectorXd ff = field(Fm);
    for (Eigen::Index i = 0; i < Fm.rows(); ++i) {
      const double a = std::abs(ff[i]);
      if (a >= lo && a < hi && a < far) pts.push_back(Fm.row(i)), vals.push_back(ff[i]);
    }
  }
  Eigen::MatrixXd P(static_cast<Eigen::Index>(pts.size()), 3);
  for (size_t i = 0; i < pts.size(); ++i) P.row(static_cast<Eigen::Index>(i)) = pts[i];
  return {P, Eigen::Map<Eigen::VectorXd>(vals.data(), static_cast<Eigen::Index>(vals.size()))};
}

// The middle layers' points: a body-centred cubic lattice of cube edge a (its Delaunay tetrahedra
// are congruent and well shaped, so the blend's zero set is cut cleanly) where g < band, and a
// coarse jittered grid of spacing 2a where g >= band. g: 1-Lipschitz (a distance, or the smallest
// |blend| over the middle layers), evaluated first on the coarse grid to find the cells the band
// may reach.
template <class Field>
Eigen::MatrixXd lattice_band_points(const Box& box, double a, double band, const Field& g) {
  const double H = 2 * a;
  const Eigen::Array3i n = (((box.hi - box.lo) / H).array().ceil().cast<int>() + 1).transpose();
  if (static_cast<double>(n.prod()) > 4e6) throw Error("transition: the point spacing is too fine for the keys' size");
  Eigen::MatrixXd C(n.prod(), 3);
  for (int x = 0, i = 0; x < n[0]; ++x)
    for (int y = 0; y < n[1]; ++y)
      for (int z = 0; z < n[2]; ++z, ++i)
        C.row(i) = box.lo + Eigen::RowVector3d(x, y, z) * H + 0.3 * a * jitter(static_cast<std::uint64_t>(i), 7);
  const Eigen::VectorXd gc = g(C);
  auto coarse = [&](int x, int y, int z) { return gc[(static_cast<Eigen::Index>(x) * n[1] + y) * n[2] + z]; };
  std::vector<Eigen::RowVector3d> pts;
  for (Eigen::Index i = 0; i < C.rows(); ++i)
    if (gc[i] >= band) pts.push_back(C.row(i));
  // Lattice points in half-edge units: cube corners at even coordinates, centres at odd ones. A
  // coarse cell owns its near faces (its far ones belong to the next cell, where there is one).
  std::vector<Eigen::RowVector3d> fine;
  const double reach = band + 2 * H;
  for (int x = 0; x + 1 < n[0]; ++x)
    for (int y = 0; y + 1 < n[1]; ++y)
      for (int z = 0; z + 1 < n[2]; ++z) {
        double m = 1e300;
        for (int c = 0; c < 8; ++c) m = std::min(m, coarse(x + (c & 1), y + (c >> 1 & 1), z + (c >> 2 & 1)));
        if (m > reach) continue;
        const int last[3] = {x + 2 == n[0], y + 2 == n[1], z + 2 == n[2]};
        for (int dx = 0; dx <= 4; ++dx)
          for (int dy = 0; dy <= 4; ++dy)
            for (int dz = 0; dz <= 4; ++dz) {
              const int odd = (dx & 1) + (dy & 1) + (dz & 1);
              if (odd != 0 && odd != 3) continue;
              if ((dx == 4 && !last[0]) || (dy == 4 && !last[1]) || (dz == 4 && !last[2])) continue;
              fine.push_back(box.lo + Eigen::RowVector3d(4 * x + dx, 4 * y + dy, 4 * z + dz) * (0.5 * a));
            }
      }
  Eigen::MatrixXd Fm(static_cast<Eigen::Index>(fine.size()), 3);
  for (size_t i = 0; i < fine.size(); ++i) Fm.row(static_cast<Eigen::Index>(i)) = fine[i];
  const Eigen::VectorXd gf = g(Fm);
  for (Eigen::Index i = 0; i < Fm.rows(); ++i)
    if (gf[i] < band) pts.push_back(Fm.row(i));
  Eigen::MatrixXd P(static_cast<Eigen::Index>(pts.size()), 3);
  for (size_t i = 0; i < pts.size(); ++i) P.row(static_cast<Eigen::Index>(i)) = pts[i];
  return P;
}

// Field values are kept at least this far from 0 (relative to the spacing), so that no crossing
// sits on a point and no piece of the level set is flat.
constexpr double kMinValue = 1e-4;
constexpr double kAway = 0.05;  // middle points, in middle spacings
// How far a key's chord-cover points are pushed from 0, in the key's spacings. At the key's time only
// their signs matter where the key is conforming (every crossing there is an anchored surface vertex).
// Pushed away (a shift, not a clamp: equal values would put many crossings at one time), a point in a
// narrow concavity puts no crossing just after the key's time, where it would make short-lived specks
// and handles.
constexpr double kChordAway = 0.5;

// |v| at least eps; positive values at least sqrt(2) eps, so that two clamped values never put a
// crossing halfway between layers (a round time a user scrubs to, where a slice would pass through
// the crossing itself).
double clamp_away_from_zero(double v, double eps) {
  if (v >= 0) return std::max(v, std::sqrt(2.0) * eps);
  return std::min(v, -eps);
}

// One key's points at its time: the conforming surface (anchored, just inside), its fill near the
// surface at the key's own spacing and farther out at the middle spacing, and the centroids that
// keep concavities from being bridged.
struct KeyLayer {
  ConformingSurface surface;
  Eigen::VectorXd fill_values;
  Eigen::Index banded = 0;  // fill points before the chord cover's
  int chords = 0;
};

// How far a nearly flat quad's diagonals may pass from each other for flip_nearly_flat, in the
// key's bounding-box diagonals.
constexpr double kFlipGap = 1e-3;

// The key made conforming from TetGen's constrained tetrahedralization when TetGen takes it, else
// from the key itself. Where splits cascade, nearly flat quads take their other diagonal, as long as
// that leaves fewer triangles missing and every Steiner point on the key (d: its signed distance).
ConformingSurface conforming_key(const TriMesh& key, const SignedDistance& d, int max_rounds) {
  ConformingSurface s;
  try {
    s = tetgen_conforming_start(key.V, key.F);
    make_conforming(s, max_rounds);
  } catch (const Error&) {
    s = conforming_delaunay_surface(key.V, key.F, max_rounds);
  }
  const double diag = (key.V.colwise().maxCoeff() - key.V.colwise().minCoeff()).norm();
  for (int round = 0; round < 4 && s.missing > 0; ++round) {
    ConformingSurface t = s;
    if (flip_nearly_flat(t, kFlipGap * diag) == 0) break;
    try {
      if (t.missing > 0) make_conforming(t, max_rounds);
    } catch (const Error&) {
      break;
    }
    const Eigen::Index steiner = t.V.rows() - key.V.rows();
    if (t.missing >= s.missing || (steiner > 0 && d(t.V.bottomRows(steiner)).cwiseAbs().maxCoeff() > 1e-12 * diag)) break;
    s = std::move(t);
  }
  return s;
}

// The conforming key with the fill points the rule admits and its chords covered, split again where
// either cost triangles.
KeyLayer filled_layer(const ConformingSurface& conforming, const Eigen::MatrixXd& candidates, FillRule rule,
                      int max_rounds) {
  KeyLayer k;
  k.surface = conforming;
  // Split what the points broke, where a split does not land on a fill point.
  auto mend = [&] {
    if (k.surface.missing == 0) return;
    ConformingSurface again = k.surface;
    try {
      make_conforming(again, max_rounds);
      if (again.missing < k.surface.missing) k.surface = std::move(again);
    } catch (const Error&) {
    }
  };
  add_fill_points(k.surface, candidates, rule);
  mend();
  k.banded = k.surface.fill.rows();
  k.chords = cover_outside_chords(k.surface, rule);
  mend();
  return k;
}

KeyLayer key_layer(const TriMesh& key, const SignedDistance& d, const Box& box, double h_key, double h_mid,
                   int max_rounds, int layer) {
  const ConformingSurface surface = conforming_key(key, d, max_rounds);
  // Near the surface the key's own spacing; away from it the middle layers' (the far field).
  const auto near = band_points(box, h_key, 0.5 * h_key, 1.5 * h_key, HUGE_VAL, layer, d);
  const auto far = band_points(box, h_mid, 0, 0, 1.5 * h_key + h_mid, layer + 100, d);
  Eigen::MatrixXd C(near.first.rows() + far.first.rows(), 3);
  C << near.first, far.first;
  // Repairing after the fact fills co-spherical surfaces (regular grids) best, where protecting
  // balls are tight. A surface whose splits cascaded (not conforming, or conforming only after
  // flips) would lose its triangles again: it is protected.
  const bool irregular = surface.missing > 0 || !surface.flipped.empty();
  KeyLayer k = filled_layer(surface, C, irregular ? FillRule::Protect : FillRule::Repair, max_rounds);
  k.fill_values = d(k.surface.fill);
  for (Eigen::Index i = k.banded; i < k.fill_values.size(); ++i)
    k.fill_values[i] += std::copysign(kChordAway * h_key, k.fill_values[i]);
  return k;
}

// The manifold's tetrahedra in one slab per layer interval where none crosses a layer time (else
// the intervals merge).
AnimationManifold into_slabs(const IsoManifold& iso, const std::vector<double>& layer_times) {
  const int nt = static_cast<int>(iso.T.rows());
  std::vector<double> lo(nt), hi(nt);
  for (int t = 0; t < nt; ++t) {
    lo[t] = 1e300, hi[t] = -1e300;
    for (int c = 0; c < 4; ++c) {
      lo[t] = std::min(lo[t], iso.V(iso.T(t, c), 3));
      hi[t] = std::max(hi[t], iso.V(iso.T(t, c), 3));
    }
  }
  std::vector<double> cuts = {layer_times.front()};
  for (size_t k = 1; k + 1 < layer_times.size(); ++k) {
    const double b = layer_times[k];
    bool crossed = false;
    for (int t = 0; t < nt && !crossed; ++t) crossed = lo[t] < b && hi[t] > b;
    if (!crossed) cuts.push_back(b);
  }
  cuts.push_back(layer_times.back());
  std::vector<std::vector<int>> in(cuts.size() - 1);
  for (int t = 0; t < nt; ++t) {
    size_t s = std::upper_bound(cuts.begin(), cuts.end(), lo[t]) - cuts.begin();
    s = std::min(std::max<size_t>(s, 1), cuts.size() - 1) - 1;
    in[s].push_back(t);
  }
  AnimationManifold M;
  M.V = iso.V;
  M.T.resize(nt, 4);
  M.times = cuts;
  int row = 0;
  for (const auto& slab : in) {
    M.slab_offsets.push_back(row);
    for (int t : slab) M.T.row(row++) = iso.T.row(t);
  }
  M.slab_offsets.push_back(row);
  return M;
}

}  // namespace

TransitionStats& TransitionStats::operator+=(const TransitionStats& o) {
  source_points += o.source_points;
  target_points += o.target_points;
  middle_points += o.middle_points;
  source_steiner += o.source_steiner;
  target_steiner += o.target_steiner;
  source_missing += o.source_missing;
  source_flipped += o.source_flipped;
  target_flipped += o.target_flipped;
  target_missing += o.target_missing;
  source_chords += o.source_chords;
  source_plane_fixes += o.source_plane_fixes;
  target_plane_fixes += o.target_plane_fixes;
  sealed += o.sealed;
  target_chords += o.target_chords;
  simplices += o.simplices;
  tets += o.tets;
  conform_seconds += o.conform_seconds;
  field_seconds += o.field_seconds;
  delaunay_seconds += o.delaunay_seconds;
  extract_seconds += o.extract_seconds;
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

// The field's morph between keys already in one frame (transition.h, "The field"), with o.layers
// layers. Its vertices in the target key's plane have time t0 + 1.0 * (t1 - t0).
AnimationManifold morph(const TriMesh& source, double t0, const TriMesh& target, double t1, const TransitionOptions& o,
                        TransitionStats& st) {
  const double h_s = o.spacing * mean_edge_length(source.V, source.F), h_t = o.spacing * mean_edge_length(target.V, target.F);
  const double h_mid = std::min(h_s, h_t);
  Box box{source.V.colwise().minCoeff().cwiseMin(target.V.colwise().minCoeff()),
          source.V.colwise().maxCoeff().cwiseMax(target.V.colwise().maxCoeff())};
  box.lo.array() -= 2 * h_mid;
  box.hi.array() += 2 * h_mid;
  const double eps = kMinValue * h_mid;

  auto t = Clock::now();
  const SignedDistance d_s(source.V, source.F), d_t(target.V, target.F);
  // The two keys are independent: the target's on a second thread.
  auto layer_of = [&](const char* which, const TriMesh& key, const SignedDistance& d, double h, int layer) {
    try {
      return key_layer(key, d, box, h, h_mid, o.max_conform_rounds, layer);
    } catch (const Error& e) {
      throw Error(std::string(which) + " key: " + e.what());
    }
  };
  auto target_layer = std::async(std::launch::async, layer_of, "target", std::cref(target), std::cref(d_t), h_t, o.layers + 1);
  KeyLayer S = layer_of("source", source, d_s, h_s, 0);
  KeyLayer T = target_layer.get();
  st.conform_seconds = seconds_since(t);

  // Layer k of K sits at local time (k - 1/2) / K, away from the round times a user scrubs to.
  t = Clock::now();
  const int K = o.layers;
  std::vector<double> u = {0.0};
  for (int k = 1; k <= K; ++k) u.push_back((k - 0.5) / K);
  u.push_back(1.0);
  // One point set for every middle layer: the lattice where any middle layer's zero set may pass.
  const Eigen::MatrixXd X = lattice_band_points(box, h_mid, 1.2 * h_mid, [&](const Eigen::MatrixXd& Y) {
    const Eigen::VectorXd s = d_s(Y), e = d_t(Y);
    Eigen::VectorXd g(Y.rows());
    for (Eigen::Index i = 0; i < Y.rows(); ++i) {
      const double a = (1 - u[1]) * s[i] + u[1] * e[i], b = (1 - u[K]) * s[i] + u[K] * e[i];
      g[i] = (a < 0) != (b < 0) ? 0.0 : std::min(std::abs(a), std::abs(b));
    }
    return g;
  });
  const Eigen::VectorXd xs = d_s(X), xt = d_t(X);
  st.field_seconds = seconds_since(t);

  // The field on every point; 4D positions with time scaled so a layer gap is four middle spacings.
  std::vector<Eigen::RowVector4d> pts;
  std::vector<double> vals;
  std::vector<char> anchored;
  // Values are kept at least `away` from 0: a crossing that close to a point would make slivers.
  // (Snapping such points onto the level set instead, as Raman and Wenger's snap marching cubes do,
  // can pinch it where the field has a saddle; moving the level set by `away` cannot.) The keys'
  // surface vertices are anchored: the level set passes through them.
  auto add = [&](const Eigen::MatrixXd& P, double time, const Eigen::VectorXd* f, double away) {
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      pts.push_back(Eigen::RowVector4d(P(i, 0), P(i, 1), P(i, 2), time));
      vals.push_back(f ? clamp_away_from_zero((*f)[i], away) : -eps);
      anchored.push_back(f == nullptr);
    }
  };
  add(S.surface.V, 0.0, nullptr, eps);
  add(S.surface.fill, 0.0, &S.fill_values, kAway * h_s);
  const int n0 = static_cast<int>(pts.size()), nx = static_cast<int>(X.rows());
  std::vector<int> bases;
  for (int k = 1; k <= K; ++k) {
    const Eigen::VectorXd f = (1 - u[k]) * xs + u[k] * xt;
    bases.push_back(static_cast<int>(pts.size()));
    add(X, u[k], &f, kAway * h_mid);
  }
  const int n_end = static_cast<int>(pts.size());
  add(T.surface.V, 1.0, nullptr, eps);
  add(T.surface.fill, 1.0, &T.fill_values, kAway * h_t);
  const double time_scale = 4.0 * h_mid * K;
  IsoField field;
  field.points.resize(static_cast<Eigen::Index>(pts.size()), 4);
  for (size_t i = 0; i < pts.size(); ++i)
    field.points.row(static_cast<Eigen::Index>(i)) << pts[i].head<3>(), t0 + pts[i][3] * (t1 - t0);
  field.values = Eigen::Map<Eigen::VectorXd>(vals.data(), static_cast<Eigen::Index>(vals.size()));
  field.anchored = anchored;

  // The end intervals by 4D Delaunay triangulations of a key and the nearest middle layer; their
  // facets in that layer are the middle points' tetrahedralization K, extruded between the layers.
  t = Clock::now();
  auto end_interval = [&](int first_a, int last_a, int first_b, int last_b) {
    MatrixX4dRow P4(last_a - first_a + last_b - first_b, 4);
    std::vector<int> global;
    for (int r : {0, 1})
      for (int i = r ? first_b : first_a; i < (r ? last_b : last_a); ++i) {
        P4.row(static_cast<Eigen::Index>(global.size())) << pts[i].head<3>(), pts[i][3] * time_scale;
        global.push_back(i);
      }
    Delaunay4 D = delaunay_4d(P4);
    return std::make_pair(std::move(D), std::move(global));
  };
  auto last_end = std::async(std::launch::async, end_interval, bases.back(), bases.back() + nx, n_end,
                             static_cast<int>(pts.size()));
  auto [D0, g0] = end_interval(0, n0, bases.front(), bases.front() + nx);
  auto [D1, g1] = last_end.get();
  const MatrixX4iRow Kt = hull_facets_in(D0, n0, n0 + nx);
  if (!(hull_facets_in(D1, 0, nx) == Kt))
    throw Error("transition: the middle points' tetrahedralization differs between the two ends");
  const Eigen::VectorXd& fv = field.values;
  const MatrixX5iRow middle = extrude_tets(Kt, bases, [&](Eigen::Index tet, int k) {
    int neg = 0;
    for (int c = 0; c < 4; ++c) neg += (fv[bases[k] + Kt(tet, c)] < 0) + (fv[bases[k + 1] + Kt(tet, c)] < 0);
    return neg > 0 && neg < 8;
  });
  Delaunay4 D;
  D.simplices.resize(D0.simplices.rows() + middle.rows() + D1.simplices.rows(), 5);
  Eigen::Index row = 0;
  for (const auto* part : {&D0, &D1}) {
    const std::vector<int>& g = part == &D0 ? g0 : g1;
    for (Eigen::Index r = 0; r < part->simplices.rows(); ++r, ++row)
      for (int c = 0; c < 5; ++c) D.simplices(row, c) = g[part->simplices(r, c)];
  }
  D.simplices.bottomRows(middle.rows()) = middle;
  st.delaunay_seconds = seconds_since(t);
  t = Clock::now();
  std::vector<double> layer_times;
  for (double x : u) layer_times.push_back(t0 + x * (t1 - t0));
  layer_times.back() = t1;
  IsoManifold iso = iso_manifold(field, D);
  const KeyPlaneStats plane_s = correct_key_plane(iso.V, iso.T, t0, key_tets(S.surface, S.fill_values));
  const KeyPlaneStats plane_t = correct_key_plane(iso.V, iso.T, t1, key_tets(T.surface, T.fill_values));
  const double seal = 1e-6 * (t1 - t0);  // how far inside the slab a sealing cone's point sits
  st.sealed = seal_key_time(iso.V, iso.T, t0, t0 + seal) + seal_key_time(iso.V, iso.T, t1, t1 - seal);
  AnimationManifold M = into_slabs(iso, layer_times);
  st.extract_seconds = seconds_since(t);

  st.source_points = n0;
  st.middle_points = nx;
  st.target_points = static_cast<int>(pts.size()) - n_end;
  st.source_steiner = S.surface.steiner;
  st.target_steiner = T.surface.steiner;
  st.source_flipped = static_cast<int>(S.surface.flipped.size());
  st.target_flipped = static_cast<int>(T.surface.flipped.size());
  st.source_missing = S.surface.missing;
  st.target_missing = T.surface.missing;
  st.source_plane_fixes = plane_s.bridges + plane_s.carved;
  st.target_plane_fixes = plane_t.bridges + plane_t.carved;
  st.source_chords = S.chords;
  st.target_chords = T.chords;
  st.simplices = static_cast<int>(D.simplices.rows());
  st.tets = M.num_tets();
  return M;
}

}  // namespace

namespace {

double bounding_diagonal(const Eigen::MatrixXd& V) { return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm(); }

// Picked points farther than this from their key, in its bounding-box diagonals, are refused.
constexpr double kPairReach = 0.02;

// Puts the aligned (and warped) morph's vertices where they belong (transition.h, "The placement"):
// a vertex at time t goes through the warp and the placement interpolated at its own u. The source
// key's plane stays as it is; in the target key's plane each vertex of the reference target
// (`reference`, the morph's input) becomes the target's own vertex, bit for bit, and any other
// point on it (a surface Steiner point) the point of the target's triangle with its barycentric
// coordinates, so that the slice there is the target.
void place(AnimationManifold& M, double t0, double t1, const KeyPlacement& p, const SpaceWarp& w,
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

AnimationManifold build_transition(const TriMesh& source_in, double t0, const TriMesh& target_in, double t1,
                                   const TransitionOptions& o, TransitionStats* stats) {
  const auto start = Clock::now();
  if (!(std::isfinite(t0) && std::isfinite(t1) && t0 < t1))
    throw Error("transition: key times must be finite and increasing");
  if (o.layers < 1 || !(o.spacing > 0)) throw Error("transition: needs at least one layer and a positive spacing");
  if (!(o.max_turn_per_layer > 0)) throw Error("transition: the turn per layer must be positive");
  TransitionStats st;
  const TriMesh source = compacted(source_in), target = compacted(target_in);
  if (const auto bad = transition_pair_problem(source, target, o.pairs))
    throw Error("picked pair " + std::to_string(bad->pair + 1) + ": " + bad->problem);

  // The placement (key_alignment.h) and the warp (space_warp.h), both in the source's frame.
  auto t = Clock::now();
  KeyPlacement p;
  if (o.align) p = key_placement(solid_moments(source.V, source.F), solid_moments(target.V, target.F));
  const SpaceWarp w = fit_space_warp(o.pairs.leftCols(3), to_source_frame(p, o.pairs.rightCols(3)));
  TriMesh reference{to_source_frame(p, target.V), target.F, {}};
  for (int v = 0; v < reference.V.rows() && !w.identity(); ++v) reference.V.row(v) = unwarp(w, reference.V.row(v));
  if (!w.identity()) {
    // W_u must not turn space inside out where the morph is: det(I + u dD/dx) > 0 on both keys.
    for (const Eigen::MatrixXd* X : std::initializer_list<const Eigen::MatrixXd*>{&source.V, &reference.V})
      for (Eigen::Index v = 0; v < X->rows(); ++v) {
        const Eigen::Matrix3d J = w.displacement_jacobian(X->row(v));
        for (double u : {0.25, 0.5, 0.75, 1.0})
          if (!((Eigen::Matrix3d::Identity() + u * J).determinant() > 0))
            throw Error("the picked pairs fold space near (" + std::to_string((*X)(v, 0)) + " " +
                        std::to_string((*X)(v, 1)) + " " + std::to_string((*X)(v, 2)) + ") at u = " + std::to_string(u) +
                        ": pin more of the shape, or move the pairs less");
      }
    check_transition_key(reference, "the target key warped by the picked pairs");
  }
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
