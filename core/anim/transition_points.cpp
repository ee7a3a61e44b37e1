#include "core/anim/transition_points.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/anim/conforming_tetgen.h"
#include "core/anim/face_protection.h"
#include "core/anim/surface_delaunay.h"
#include "core/util/error.h"

namespace dfm::transition_detail {

namespace {

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

// Calls visit(x, y, z) for each cell of an n[0] x n[1] x n[2] grid of values (x-major) with a corner
// whose |value| is at most reach.
template <class Visit>
void cells_within(const Eigen::Array3i& n, const Eigen::VectorXd& values, double reach, const Visit& visit) {
  auto at = [&](int x, int y, int z) { return std::abs(values[(static_cast<Eigen::Index>(x) * n[1] + y) * n[2] + z]); };
  for (int x = 0; x + 1 < n[0]; ++x)
    for (int y = 0; y + 1 < n[1]; ++y)
      for (int z = 0; z + 1 < n[2]; ++z) {
        double m = 1e300;
        for (int c = 0; c < 8; ++c) m = std::min(m, at(x + (c & 1), y + (c >> 1 & 1), z + (c >> 2 & 1)));
        if (m <= reach) visit(x, y, z);
      }
}

// Points off a level set, on a grid of spacing h: those where lo <= |field| < hi (found from a
// coarse grid of spacing 2h: a signed distance, or a blend of them, changes by at most the distance
// moved), and the coarse grid's points where |field| >= far (none when far is infinite).
std::pair<Eigen::MatrixXd, Eigen::VectorXd> band_points(const Box& box, double h, double lo, double hi, double far,
                                                         int layer, const PointField& field) {
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
  std::vector<Eigen::RowVector3d> pts;
  std::vector<double> vals;
  for (Eigen::Index i = 0; i < C.rows(); ++i)
    if (std::abs(fc[i]) >= far) pts.push_back(C.row(i)), vals.push_back(fc[i]);
  if (hi > lo) {
    // Every fine point of a coarse cell the band may reach (a cell's far faces belong to the next).
    std::vector<Eigen::RowVector3d> fine;
    const double reach = hi + 2 * H;
    cells_within(n, fc, reach, [&](int x, int y, int z) {
      for (int c = 0; c < 27; ++c) {
        const int dx = c % 3, dy = c / 3 % 3, dz = c / 9;
        if ((dx == 2 && x + 2 < n[0]) || (dy == 2 && y + 2 < n[1]) || (dz == 2 && z + 2 < n[2])) continue;
        fine.push_back(at(2 * x + dx, 2 * y + dy, 2 * z + dz));
      }
    });
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

}  // namespace

// Shifted by a different amount along each axis, too little to matter to the field: a lattice with
// the keys' symmetries (a box with equal sides) would tie exactly in their 4D Delaunay
// triangulation (layer_pair_delaunay.h).
Eigen::RowVector3d lattice_origin(const Box& box, double a) { return box.lo - a * Eigen::RowVector3d(1.37e-6, 2.91e-6, 4.13e-6); }

Eigen::MatrixXd lattice_band_points(const Box& box, double a, double band, const PointField& g) {
  const double H = 2 * a;
  const Eigen::RowVector3d lo = lattice_origin(box, a);
  const Eigen::Array3i n = (((box.hi - lo) / H).array().ceil().cast<int>() + 1).transpose();
  if (static_cast<double>(n.prod()) > 4e6) throw Error("transition: the point spacing is too fine for the keys' size");
  Eigen::MatrixXd C(n.prod(), 3);
  for (int x = 0, i = 0; x < n[0]; ++x)
    for (int y = 0; y < n[1]; ++y)
      for (int z = 0; z < n[2]; ++z, ++i)
        C.row(i) = lo + Eigen::RowVector3d(x, y, z) * H + 0.3 * a * jitter(static_cast<std::uint64_t>(i), 7);
  const Eigen::VectorXd gc = g(C);
  std::vector<Eigen::RowVector3d> pts;
  for (Eigen::Index i = 0; i < C.rows(); ++i)
    if (gc[i] >= band) pts.push_back(C.row(i));
  // Lattice points in half-edge units: cube corners at even coordinates, centres at odd ones. A
  // coarse cell owns its near faces (its far ones belong to the next cell, where there is one).
  std::vector<Eigen::RowVector3d> fine;
  const double reach = band + 2 * H;
  cells_within(n, gc, reach, [&](int x, int y, int z) {
    const int last[3] = {x + 2 == n[0], y + 2 == n[1], z + 2 == n[2]};
    for (int dx = 0; dx <= 4; ++dx)
      for (int dy = 0; dy <= 4; ++dy)
        for (int dz = 0; dz <= 4; ++dz) {
          const int odd = (dx & 1) + (dy & 1) + (dz & 1);
          if (odd != 0 && odd != 3) continue;
          if ((dx == 4 && !last[0]) || (dy == 4 && !last[1]) || (dz == 4 && !last[2])) continue;
          fine.push_back(lo + Eigen::RowVector3d(4 * x + dx, 4 * y + dy, 4 * z + dz) * (0.5 * a));
        }
  });
  Eigen::MatrixXd Fm(static_cast<Eigen::Index>(fine.size()), 3);
  for (size_t i = 0; i < fine.size(); ++i) Fm.row(static_cast<Eigen::Index>(i)) = fine[i];
  const Eigen::VectorXd gf = g(Fm);
  for (Eigen::Index i = 0; i < Fm.rows(); ++i)
    if (gf[i] < band) pts.push_back(Fm.row(i));
  Eigen::MatrixXd P(static_cast<Eigen::Index>(pts.size()), 3);
  for (size_t i = 0; i < pts.size(); ++i) P.row(static_cast<Eigen::Index>(i)) = pts[i];
  return P;
}

namespace {

// How far a key's chord-cover points are pushed from 0, in the key's spacings. At the key's time only
// their signs matter where the key is conforming (every crossing there is an anchored surface vertex).
// Pushed away (a shift, not a clamp: equal values would put many crossings at one time), a point in a
// narrow concavity puts no crossing just after the key's time, where it would make short-lived specks
// and handles.
constexpr double kChordAway = 0.5;



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
  GrowingSurfaceDelaunay tetrahedralization;  // shared by the steps below: each changes few points
  // Split what the points broke, where a split does not land on a fill point.
  auto mend = [&] {
    if (k.surface.missing == 0) return;
    ConformingSurface again = k.surface;
    try {
      make_conforming(again, max_rounds, &tetrahedralization);
      if (again.missing < k.surface.missing) k.surface = std::move(again);
    } catch (const Error&) {
    }
  };
  add_fill_points(k.surface, candidates, rule, &tetrahedralization);
  mend();
  k.banded = k.surface.fill.rows();
  k.chords = cover_outside_chords(k.surface, rule, 1, &tetrahedralization);
  mend();
  return k;
}

}  // namespace

KeyLayer key_layer(const TriMesh& key, const SignedDistance& d, const Box& box, double h_key, double h_mid,
                   int max_rounds, int layer) {
  const ConformingSurface surface = conforming_key(key, d, max_rounds);
  const PointField field = [&d](const Eigen::MatrixXd& X) { return d(X); };
  // Near the surface the key's own spacing; away from it the middle layers' (the far field).
  const auto near = band_points(box, h_key, 0.5 * h_key, 1.5 * h_key, HUGE_VAL, layer, field);
  const auto far = band_points(box, h_mid, 0, 0, 1.5 * h_key + h_mid, layer + 100, field);
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

double clamp_away_from_zero(double v, double eps) {
  if (v >= 0) return std::max(v, std::sqrt(2.0) * eps);
  return std::min(v, -eps);
}

}  // namespace dfm::transition_detail
