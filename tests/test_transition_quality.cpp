// Issue 30: in-betweens an artist would keep. The slices at t = 0.25, 0.5, 0.75 against references
// computed here: the angle between edge-neighbouring triangles' normals against the keys' own, the
// distance (both ways) to the zero set of the morph transition.h documents, found by bisection on a
// grid, and the Euler characteristic over t = 0, 0.05, ..., 1 against the keys'.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "core/anim/delaunay_4d.h"
#include "core/anim/key_alignment.h"
#include "core/anim/key_distance.h"
#include "core/anim/layer_extrusion.h"
#include "core/anim/slice.h"
#include "core/anim/surface_checks.h"
#include "core/anim/transition.h"
#include "core/mesh/io.h"
#include "tests/test_support.h"
#include "tests/transition_test_meshes.h"

using namespace dfm;
using dfm::test::euler_characteristic;

namespace {

// Angles in degrees between the normals of triangles that share an edge, sorted.
std::vector<double> neighbour_angles(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  Eigen::MatrixXd N(F.rows(), 3);
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    N.row(f) = (b - a).cross(c - a).normalized().transpose();
  }
  std::map<std::pair<int, int>, int> first;
  std::vector<double> out;
  for (int f = 0; f < F.rows(); ++f)
    for (int j = 0; j < 3; ++j) {
      const int a = F(f, j), b = F(f, (j + 1) % 3);
      const auto [it, fresh] = first.emplace(std::make_pair(std::min(a, b), std::max(a, b)), f);
      if (!fresh) out.push_back(std::acos(std::clamp(N.row(f).dot(N.row(it->second)), -1.0, 1.0)) * 180 / M_PI);
    }
  std::sort(out.begin(), out.end());
  return out;
}

double percentile(const std::vector<double>& sorted, int p) { return sorted[sorted.size() * p / 100]; }

// Radius of gyration of the solid a closed, outward surface bounds: tetrahedra from the origin,
// int |x - c|^2 = int |x|^2 - V |c|^2, int_tet |x|^2 = vol / 10 (|a|^2 + |b|^2 + |c|^2 + a.b + b.c + c.a).
double radius_of_gyration(const TriMesh& m) {
  double vol = 0, second = 0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  for (int f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    const double v = a.dot(b.cross(c)) / 6;
    vol += v;
    first += v * (a + b + c) / 4;
    second += v / 10 * (a.squaredNorm() + b.squaredNorm() + c.squaredNorm() + a.dot(b) + b.dot(c) + c.dot(a));
  }
  const Eigen::Vector3d centroid = first / vol;
  return std::sqrt((second - vol * centroid.squaredNorm()) / vol);
}

double distance_to_mesh(const Eigen::Vector3d& p, const TriMesh& m) {
  double d = 1e300;
  for (int f = 0; f < m.F.rows(); ++f)
    d = std::min(d, dfm::test::point_triangle_distance(p, m.V.row(m.F(f, 0)), m.V.row(m.F(f, 1)), m.V.row(m.F(f, 2))));
  return d;
}

// The documented morph (transition.h) for a placement p (key_alignment.h's, or none): the reference
// target T^ = c0 + R^T (T - c1) / scale, F(x, u) = (1 - u) d_S(x) + u d_T^(x), placed by
// P_u(x) = c0 + u (c1 - c0) + s(u) R(u) (x - c0), s(u) = (1 - u) + u scale, R(u) the turn by u times R's
// angle about its axis.
struct PlacedMorph {
  PlacedMorph(const TriMesh& S, const TriMesh& T, const KeyPlacement& p, double c)
      : p(p), c(c), reference{source_frame(T.V, p), T.F, {}}, d_s(S.V, S.F), d_t(reference.V, reference.F) {}
  static Eigen::MatrixXd source_frame(const Eigen::MatrixXd& X, const KeyPlacement& p) {
    return ((X.rowwise() - p.c1.transpose()) * p.R / p.scale).rowwise() + p.c0.transpose();
  }
  double s(double u) const { return (1 - u) + u * p.scale; }
  Eigen::Matrix3d R(double u) const {
    const Eigen::AngleAxisd a(p.R);
    return Eigen::AngleAxisd(u * a.angle(), a.axis()).toRotationMatrix();
  }
  Eigen::Vector3d placed(const Eigen::Vector3d& x, double u) const { return p.c0 + u * (p.c1 - p.c0) + s(u) * R(u) * (x - p.c0); }
  Eigen::Vector3d unplaced(const Eigen::Vector3d& y, double u) const {
    return p.c0 + R(u).transpose() * (y - p.c0 - u * (p.c1 - p.c0)) / s(u);
  }
  // d averaged over the six points at c |d(x)| from x along the axes (rounded_distance.h's rule).
  Eigen::VectorXd rounded(const SignedDistance& d, const Eigen::MatrixXd& X) const {
    const Eigen::VectorXd v = d(X);
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(X.rows());
    for (int axis = 0; axis < 3; ++axis)
      for (double side : {-1.0, 1.0}) {
        Eigen::MatrixXd Y = X;
        Y.col(axis) += side * c * v.cwiseAbs();
        sum += d(Y) / 6;
      }
    return sum;
  }
  Eigen::VectorXd field(const Eigen::MatrixXd& X, double u) const { return (1 - u) * rounded(d_s, X) + u * rounded(d_t, X); }
  double field(const Eigen::Vector3d& x, double u) const { return field(Eigen::MatrixXd(x.transpose()), u)[0]; }
  KeyPlacement p;
  double c;  // TransitionOptions::crease_rounding
  TriMesh reference;
  SignedDistance d_s, d_t;
};

// The point where F(., u) changes sign between a and b (of opposite signs), by bisection.
Eigen::Vector3d sign_change(const PlacedMorph& m, Eigen::Vector3d a, Eigen::Vector3d b, double u) {
  const bool neg_a = m.field(a, u) < 0;
  for (int it = 0; it < 40; ++it) {
    const Eigen::Vector3d c = (a + b) / 2;
    ((m.field(c, u) < 0) == neg_a ? a : b) = c;
  }
  return (a + b) / 2;
}

// How far from x along +-g the field's sign first differs from its sign at x: radii doubling from
// reach / 256 find the first that shows it on either side, bisection the crossing there; infinity
// when none up to `reach` does.
double zero_along(const PlacedMorph& m, const Eigen::Vector3d& x, const Eigen::Vector3d& g, double u, double reach) {
  const bool neg = m.field(x, u) < 0;
  double inner = 0;
  for (double r = reach / 256; r <= reach; inner = r, r *= 2) {
    double best = HUGE_VAL;
    for (int side : {-1, 1})
      if ((m.field(Eigen::Vector3d(x + side * r * g), u) < 0) != neg)
        best = std::min(best, (sign_change(m, x + side * inner * g, x + side * r * g, u) - x).norm());
    if (best < HUGE_VAL) return best;
  }
  return HUGE_VAL;
}

// Directions spread over the sphere (a Fibonacci spiral).
std::vector<Eigen::Vector3d> sphere_directions(int n) {
  std::vector<Eigen::Vector3d> d;
  for (int i = 0; i < n; ++i) {
    const double z = 1 - (2 * i + 1.0) / n, r = std::sqrt(1 - z * z), phi = i * M_PI * (3 - std::sqrt(5.0));
    d.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
  }
  return d;
}

// An upper bound on x's distance to the zero set, up to `reach`: the smaller of the crossing along
// +-g (zero_along) and the smallest radius of reach / 16, 2 reach / 16, ..., reach at which one of the
// directions meets the other sign (F is continuous, so the zero set cuts that radius). Where F's
// gradient nearly vanishes the zero set's nearest point need not lie along it.
double zero_near(const PlacedMorph& m, const Eigen::Vector3d& x, const Eigen::Vector3d& g, double u, double reach) {
  static const std::vector<Eigen::Vector3d> dirs = sphere_directions(64);
  const double along = zero_along(m, x, g, u, reach);
  const bool neg = m.field(x, u) < 0;
  for (int k = 1; k <= 16 && k * reach / 16 < along; ++k)
    for (const Eigen::Vector3d& d : dirs)
      if ((m.field(Eigen::Vector3d(x + k * reach / 16 * d), u) < 0) != neg) return k * reach / 16;
  return along;
}

// Sampled distances, sorted: slice vertices to the zero set (zero_near, up to 4 tol; farther reads
// infinity) and zero-set points to the slice.
struct Fidelity {
  std::vector<double> slice_to_zero_set, zero_set_to_slice;
  double at(const std::vector<double>& d, int p) const { return d[d.size() * p / 100]; }
  // How many of d's samples lie farther than `bound`.
  static long over(const std::vector<double>& d, double bound) {
    return std::count_if(d.begin(), d.end(), [&](double x) { return !(x <= bound); });
  }
};

// Both distances, sampled: `samples` slice vertices' distances to the zero set (zero_near: along
// F's gradient or any of 64 directions, up to 4 tol; farther reads infinity), and `samples` zero-set points bisected on x
// edges of a grid of `cells` cells across the box.
Fidelity fidelity(const PlacedMorph& m, const TriMesh& slice, double u, const Eigen::RowVector3d& lo,
                  const Eigen::RowVector3d& hi, double tol, int cells, int samples) {
  Fidelity out;
  std::mt19937 rng(7);
  const double s = m.s(u);
  for (int k = 0; k < samples; ++k) {
    const int v = static_cast<int>(rng() % slice.V.rows());
    const Eigen::Vector3d x = m.unplaced(slice.V.row(v).transpose(), u);
    Eigen::Vector3d g;
    const double e = 1e-6;
    for (int d = 0; d < 3; ++d)
      g[d] = m.field(Eigen::Vector3d(x + e * Eigen::Vector3d::Unit(d)), u) - m.field(Eigen::Vector3d(x - e * Eigen::Vector3d::Unit(d)), u);
    g.normalize();
    out.slice_to_zero_set.push_back(s * zero_near(m, x, g, u, 4 * tol / s));
  }
  const double h = (hi - lo).maxCoeff() / cells;
  const Eigen::Array3i n = ((hi - lo) / h).array().ceil().cast<int>().transpose() + 1;
  Eigen::MatrixXd G(n.prod(), 3);
  for (int i = 0, r = 0; i < n[0]; ++i)
    for (int j = 0; j < n[1]; ++j)
      for (int k = 0; k < n[2]; ++k) G.row(r++) = lo + Eigen::RowVector3d(i, j, k) * h;
  const Eigen::VectorXd f = m.field(G, u);
  std::vector<int> crossings;  // rows whose +x neighbour has the other sign
  for (int i = 0; i + 1 < n[0]; ++i)
    for (int r = i * n[1] * n[2]; r < (i + 1) * n[1] * n[2]; ++r)
      if ((f[r] < 0) != (f[r + n[1] * n[2]] < 0)) crossings.push_back(r);
  REQUIRE(!crossings.empty());
  for (int k = 0; k < samples; ++k) {
    const int r = crossings[rng() % crossings.size()];
    const Eigen::Vector3d z = sign_change(m, G.row(r).transpose(), G.row(r + n[1] * n[2]).transpose(), u);
    out.zero_set_to_slice.push_back(distance_to_mesh(m.placed(z, u), slice));
  }
  std::sort(out.slice_to_zero_set.begin(), out.slice_to_zero_set.end());
  std::sort(out.zero_set_to_slice.begin(), out.zero_set_to_slice.end());
  return out;
}

struct Smoothness {
  double p90 = 0, p99 = 0;
};

Smoothness smoothness(const TriMesh& m) {
  const std::vector<double> a = neighbour_angles(m.V, m.F);
  return {percentile(a, 90), percentile(a, 99)};
}

// The acceptance's smoothness bound: the rougher key's percentile plus 5 degrees.
Smoothness rougher(const TriMesh& a, const TriMesh& b) {
  const Smoothness x = smoothness(a), y = smoothness(b);
  return {std::max(x.p90, y.p90) + 5, std::max(x.p99, y.p99) + 5};
}

// Euler characteristics over t = 0, 0.05, ..., 1; how many leave the keys' range.
int samples_out_of_range(const AnimationManifold& M, const TriMesh& a, const TriMesh& b, std::vector<int>& chis) {
  const int lo = std::min(euler_characteristic(a.F), euler_characteristic(b.F));
  const int hi = std::max(euler_characteristic(a.F), euler_characteristic(b.F));
  int out = 0;
  for (int i = 0; i <= 20; ++i) {
    chis.push_back(euler_characteristic(slice_manifold(M, SliceAxis::T, i / 20.0).mesh.F));
    out += chis.back() < lo || chis.back() > hi;
  }
  return out;
}

double joint_diagonal(const TriMesh& a, const TriMesh& b) {
  return (a.V.colwise().maxCoeff().cwiseMax(b.V.colwise().maxCoeff()) -
          a.V.colwise().minCoeff().cwiseMin(b.V.colwise().minCoeff()))
      .norm();
}

// Smooth, faithful to the documented morph, topology between the keys': the whole acceptance. At most
// `max_out` Euler characteristic samples may leave the keys' range (the acceptance allows one).
void check_in_betweens(const TriMesh& S, const TriMesh& T, const TransitionOptions& o, const char* name,
                       int max_out = 1, TransitionStats* stats = nullptr) {
  TransitionStats st;
  const AnimationManifold M = build_transition(S, 0, T, 1, o, &st);
  if (stats) *stats = st;
  INFO(name << ": " << st.total_seconds << " s, turn " << st.turn_degrees << " degrees, scale " << st.scale);
  const KeyPlacement placement = o.align ? key_placement(solid_moments(S.V, S.F), solid_moments(T.V, T.F)) : KeyPlacement{};
  if (o.align) REQUIRE(st.scale == Approx(radius_of_gyration(T) / radius_of_gyration(S)).epsilon(1e-9));
  REQUIRE(st.scale == Approx(placement.scale).epsilon(1e-12));
  REQUIRE(st.turn_degrees == Approx(Eigen::AngleAxisd(placement.R).angle() * 180 / M_PI).margin(1e-9));
  const PlacedMorph morph(S, T, placement, o.crease_rounding);
  const double diag = joint_diagonal(S, T);
  const Smoothness bound = rougher(S, T);
  Eigen::RowVector3d lo = S.V.colwise().minCoeff().cwiseMin(morph.reference.V.colwise().minCoeff());
  Eigen::RowVector3d hi = S.V.colwise().maxCoeff().cwiseMax(morph.reference.V.colwise().maxCoeff());
  lo.array() -= 0.05 * diag;
  hi.array() += 0.05 * diag;
  for (double t : {0.25, 0.5, 0.75}) {
    const TriMesh s = slice_manifold(M, SliceAxis::T, t).mesh;
    const Smoothness got = smoothness(s);
    const Fidelity fid = fidelity(morph, s, t, lo, hi, 0.005 * diag, 80, 300);
    const auto& a = fid.slice_to_zero_set;
    const auto& b = fid.zero_set_to_slice;
    INFO("t = " << t << ": " << s.F.rows() << " triangles, normals " << got.p90 << " / " << got.p99
                << " degrees (90th / 99th; bound " << bound.p90 << " / " << bound.p99
                << "), in diagonals: slice to zero set (90th / 99th / largest) " << fid.at(a, 90) / diag << " / "
                << fid.at(a, 99) / diag << " / " << a.back() / diag << ", zero set to slice " << fid.at(b, 90) / diag
                << " / " << fid.at(b, 99) / diag << " / " << b.back() / diag);
    CHECK(is_closed_and_oriented(s.F));
    CHECK(enclosed_volume(s.V, s.F) > 0);
    CHECK(got.p90 <= bound.p90);
    CHECK(got.p99 <= bound.p99);
    // The acceptance: the largest within 0.5% of the diagonal, both ways. (Every vertex, not these
    // samples: dense_misses below, where the blend is nearly flat, as at a gap's closing instant.)
    CHECK(a.back() <= 1.000001 * 0.005 * diag);
    CHECK(b.back() <= 0.005 * diag);
    if (!(b.back() <= 0.005 * diag && a.back() <= 1.000001 * 0.005 * diag))
      WARN(name << " at t = " << t << ": samples over 0.5% of the diagonal " << Fidelity::over(a, 1.000001 * 0.005 * diag)
                << " and " << Fidelity::over(b, 0.005 * diag) << " of " << a.size());
  }
  std::vector<int> chis;
  const int out = samples_out_of_range(M, S, T, chis);
  INFO("Euler characteristics " << Catch::Detail::stringify(chis));
  CHECK(chis.front() == euler_characteristic(S.F));
  CHECK(chis.back() == euler_characteristic(T.F));
  CHECK(out <= max_out);
}

// How many of the slice's vertices lie farther than 0.5% of the diagonal from the zero set: all of
// them by F / |grad F| (central differences), those reading over 0.25% by zero_near.
int dense_misses(const PlacedMorph& m, const TriMesh& slice, double u, double diag) {
  Eigen::MatrixXd X(slice.V.rows(), 3);
  for (Eigen::Index v = 0; v < X.rows(); ++v) X.row(v) = m.unplaced(slice.V.row(v).transpose(), u).transpose();
  const Eigen::VectorXd f = m.field(X, u);
  Eigen::MatrixXd G(X.rows(), 3);
  const double e = 1e-6;
  for (int d = 0; d < 3; ++d) {
    Eigen::MatrixXd A = X, B = X;
    A.col(d).array() += e;
    B.col(d).array() -= e;
    G.col(d) = (m.field(A, u) - m.field(B, u)) / (2 * e);
  }
  const double tol = 0.005 * diag;
  int over = 0;
  for (Eigen::Index v = 0; v < X.rows(); ++v) {
    if (!(m.s(u) * std::abs(f[v]) / G.row(v).norm() > 0.5 * tol)) continue;
    over += m.s(u) * zero_near(m, X.row(v).transpose(), G.row(v).normalized().transpose(), u, 4 * tol / m.s(u)) > 1.000001 * tol;
  }
  return over;
}

}  // namespace

TEST_CASE("in-betweens: a sphere to a torus, smooth, on the documented field's zero set", "[transition][heavy]") {
  // The torus, a regular grid, reads 7.2 degrees at its 90th and 99th percentiles alike; where its
  // hole opens (t near 0.7) the slice curves more tightly than either key, and the lattice's facets
  // there reach 10.7 degrees at the 99th at t = 0.75, within the bound of 12.2.
  check_in_betweens(dfm::test::icosphere(Eigen::Vector3d::Zero(), 0.45, 4),
                    dfm::test::torus(Eigen::Vector3d::Zero(), 0.32, 0.12, 100, 50), {}, "sphere to torus");
}

TEST_CASE("in-betweens: bunny to 3holes, smooth, on the documented field's zero set", "[transition][heavy]") {
  DFM_DATA_OR_SKIP(bunny, "bunny.off");
  DFM_DATA_OR_SKIP(holes, "3holes.off");
  // Unaligned (the bunny turns 36 degrees into 3holes' frame otherwise): the field is the blend itself.
  TransitionOptions o;
  o.align = false;
  check_in_betweens(dfm::test::into_unit_box(read_surface(bunny)), dfm::test::into_unit_box(read_surface(holes)), o,
                    "bunny to 3holes");
}

TEST_CASE("in-betweens: the teddy to key-torus, smooth, on the documented field's zero set", "[transition][heavy]") {
  // Where the teddy's head meets its shoulders the gap closes near u = 0.48 through bridges and
  // pockets, and F's zero set has slits for a moment: at t = 0.5 the slice's Euler characteristic is
  // -4, the one sample the acceptance lets leave [0, 2]. The placement turns the torus 0.6 degrees.
  check_in_betweens(read_surface(std::string(DFM_SOURCE_DIR) + "/assets/default.obj"),
                    read_surface(std::string(DFM_SOURCE_DIR) + "/assets/key-torus.obj"), {}, "teddy to key-torus");
}

TEST_CASE("in-betweens: the teddy's neck closing merged at once (transient_life) stays within the keys' topology",
          "[transition][heavy]") {
  const TriMesh S = read_surface(std::string(DFM_SOURCE_DIR) + "/assets/default.obj");
  const TriMesh T = read_surface(std::string(DFM_SOURCE_DIR) + "/assets/key-torus.obj");
  TransitionOptions o;
  o.transient_life = 0.08;
  TransitionStats st;
  const AnimationManifold M = build_transition(S, 0, T, 1, o, &st);
  CHECK(st.transients > 0);
  std::vector<int> chis;
  CHECK(samples_out_of_range(M, S, T, chis) == 0);
  INFO("Euler characteristics " << Catch::Detail::stringify(chis));
  CHECK(chis.front() == 2);
  CHECK(chis.back() == 0);
}

TEST_CASE("in-betweens: the bunny's ear thinner than a lattice spacing, every vertex, refined and not",
          "[transition][heavy]") {
  // At t = 0.25 the bunny's ears shrink into 3holes. F dips between lattice points of one sign there
  // (lattice_refinement.h); without refinement 58 of the slice's 23,672 vertices lie over 0.5% of
  // the diagonal from F's zero set.
  DFM_DATA_OR_SKIP(bunny, "bunny.off");
  DFM_DATA_OR_SKIP(holes, "3holes.off");
  const TriMesh S = dfm::test::into_unit_box(read_surface(bunny)), T = dfm::test::into_unit_box(read_surface(holes));
  TransitionOptions o;
  o.align = false;
  const PlacedMorph morph(S, T, KeyPlacement{}, o.crease_rounding);
  const double diag = joint_diagonal(S, T);
  TransitionStats refined;
  const TriMesh with = slice_manifold(build_transition(S, 0, T, 1, o, &refined), SliceAxis::T, 0.25).mesh;
  o.refine_tolerance = 0;
  const TriMesh without = slice_manifold(build_transition(S, 0, T, 1, o), SliceAxis::T, 0.25).mesh;
  const int misses_with = dense_misses(morph, with, 0.25, diag), misses_without = dense_misses(morph, without, 0.25, diag);
  INFO("refined " << refined.refined_points << " of " << refined.middle_points << " middle points; vertices over 0.5%: "
                  << misses_with << " of " << with.V.rows() << " refined, " << misses_without << " of " << without.V.rows()
                  << " not");
  CHECK(refined.refined_points > 0);
  CHECK(misses_without > 20);
  CHECK(misses_with * 10 <= misses_without);
}

TEST_CASE("layer extrusion: the staircase fills tet x interval; neighbours split their shared face alike", "[transition]") {
  // Two tetrahedra sharing face (1, 2, 3), layer 0 at t = 0 (points 0..4), layer 1 at t = 2 (5..9).
  Eigen::MatrixXd P(5, 3);
  P << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1;
  MatrixX4iRow K(2, 4);
  K << 0, 1, 2, 3, 1, 2, 3, 4;
  const MatrixX5iRow S = extrude_tets(K, {0, 5}, [](Eigen::Index, int) { return true; });
  REQUIRE(S.rows() == 8);
  auto point4 = [&](int i) { return Eigen::Vector4d(P(i % 5, 0), P(i % 5, 1), P(i % 5, 2), i < 5 ? 0.0 : 2.0); };
  auto tet_volume = [&](int t) {
    Eigen::Matrix3d E;
    for (int c = 0; c < 3; ++c) E.col(c) = (P.row(K(t, c + 1)) - P.row(K(t, 0))).transpose();
    return std::abs(E.determinant()) / 6;
  };
  for (int t = 0; t < 2; ++t) {
    double sum = 0;
    for (int s = 4 * t; s < 4 * t + 4; ++s) {
      Eigen::Matrix4d E;
      for (int c = 0; c < 4; ++c) E.col(c) = point4(S(s, c + 1)) - point4(S(s, 0));
      const double v = std::abs(E.determinant()) / 24;
      CHECK(v > 0);
      sum += v;
    }
    CHECK(sum == Approx(tet_volume(t) * 2).epsilon(1e-12));  // the prism's 4-volume: base x height
  }
  // Every facet inside the prism stack is shared by exactly two simplices: the shared face's prism
  // (1, 2, 3) x [0, 2] is split the same way from both sides.
  std::map<std::array<int, 4>, int> facets;
  for (Eigen::Index s = 0; s < S.rows(); ++s)
    for (int skip = 0; skip < 5; ++skip) {
      std::array<int, 4> f;
      for (int c = 0, n = 0; c < 5; ++c)
        if (c != skip) f[n++] = S(s, c);
      std::sort(f.begin(), f.end());
      ++facets[f];
    }
  int shared_face = 0;
  for (const auto& [f, n] : facets) {
    bool on_shared = true;
    for (int v : f) on_shared = on_shared && (v % 5 >= 1 && v % 5 <= 3);
    if (on_shared) {
      ++shared_face;
      CHECK(n == 2);
    }
    CHECK(n <= 2);
  }
  CHECK(shared_face == 3);  // a triangular prism in three tetrahedra
}

TEST_CASE("hull facets: a two-layer 4D Delaunay triangulation's tetrahedra in a layer are that layer's Delaunay tetrahedra",
          "[transition]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(0, 1);
  MatrixX4dRow P(60, 4);
  for (int i = 0; i < 60; ++i) P.row(i) << U(rng), U(rng), U(rng), i < 30 ? 0.0 : 0.7;
  const Delaunay4 D = delaunay_4d(P);
  const MatrixX4iRow top = hull_facets_in(D, 30, 60);
  REQUIRE(top.rows() > 0);
  std::vector<char> used(30, 0);
  for (Eigen::Index t = 0; t < top.rows(); ++t) {
    // The circumsphere (brute force: equidistant centre) holds no other top point.
    Eigen::Vector3d q[4];
    for (int c = 0; c < 4; ++c) q[c] = P.row(30 + top(t, c)).head<3>().transpose(), used[top(t, c)] = 1;
    Eigen::Matrix3d A;
    Eigen::Vector3d b;
    for (int r = 0; r < 3; ++r) A.row(r) = 2 * (q[r + 1] - q[0]).transpose(), b[r] = q[r + 1].squaredNorm() - q[0].squaredNorm();
    const Eigen::Vector3d c = A.fullPivLu().solve(b);
    const double r2 = (q[0] - c).squaredNorm();
    for (int i = 0; i < 30; ++i) {
      bool corner = false;
      for (int k = 0; k < 4; ++k) corner = corner || top(t, k) == i;
      if (!corner) CHECK((P.row(30 + i).head<3>().transpose() - c).squaredNorm() > r2 * (1 - 1e-9));
    }
  }
  for (int i = 0; i < 30; ++i) CHECK(used[i]);
}
