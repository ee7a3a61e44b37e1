// Transitions that travel, turn and meet by picked pairs (issue 30): the solid's moments, the
// placement and its interpolation (Alexa 4.1.1), the space warp through picked pairs (Cohen-Or et al.
// 1998), and the acceptance on whole transitions. References are written here: box moments by hand,
// rotations by Rodrigues' formula, moments of slices by a divergence-theorem sum of their own.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <unordered_set>

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "core/anim/elastic_pairs.h"
#include "core/anim/key_alignment.h"
#include "core/anim/key_distance.h"
#include "core/anim/manifold_sequence.h"
#include "core/anim/slice.h"
#include "core/anim/space_warp.h"
#include "core/anim/surface_checks.h"
#include "core/anim/transition.h"
#include "core/mesh/io.h"
#include "core/util/error.h"
#include "tests/transition_test_meshes.h"

using namespace dfm;
using dfm::test::euler_characteristic;

namespace {

// Rodrigues: the rotation by `degrees` about the unit axis a.
Eigen::Matrix3d rodrigues(Eigen::Vector3d a, double degrees) {
  a.normalize();
  const double th = degrees * M_PI / 180;
  Eigen::Matrix3d K;
  K << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return Eigen::Matrix3d::Identity() + std::sin(th) * K + (1 - std::cos(th)) * K * K;
}

double angle_degrees(const Eigen::Matrix3d& R) {
  return std::acos(std::max(-1.0, std::min(1.0, (R.trace() - 1) / 2))) * 180 / M_PI;
}

// The box [lo, hi] with n[k] quads along axis k on each face, each quad cut along one diagonal or the
// other: the same solid triangulated differently.
TriMesh grid_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, const Eigen::Vector3i& n, bool other_diagonal) {
  std::map<std::array<int, 3>, int> id;
  std::vector<Eigen::RowVector3d> V;
  std::vector<Eigen::RowVector3i> F;
  auto vert = [&](std::array<int, 3> g) {
    auto [it, fresh] = id.emplace(g, static_cast<int>(V.size()));
    if (fresh) {
      Eigen::RowVector3d p;
      for (int k = 0; k < 3; ++k) p[k] = lo[k] + (hi[k] - lo[k]) * g[k] / n[k];
      V.push_back(p);
    }
    return it->second;
  };
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;  // e_b x e_c = e_a
      for (int p = 0; p < n[b]; ++p)
        for (int q = 0; q < n[c]; ++q) {
          auto at = [&](int dp, int dq) {
            std::array<int, 3> g;
            g[a] = side * n[a], g[b] = p + dp, g[c] = q + dq;
            return vert(g);
          };
          int v00 = at(0, 0), v10 = at(1, 0), v11 = at(1, 1), v01 = at(0, 1);
          if (side == 0) std::swap(v10, v01);  // facing -e_a
          if (!other_diagonal) F.push_back({v00, v10, v11}), F.push_back({v00, v11, v01});
          else F.push_back({v00, v10, v01}), F.push_back({v10, v11, v01});
        }
    }
  TriMesh m;
  m.V.resize(static_cast<Eigen::Index>(V.size()), 3);
  for (size_t i = 0; i < V.size(); ++i) m.V.row(static_cast<Eigen::Index>(i)) = V[i];
  m.F.resize(static_cast<Eigen::Index>(F.size()), 3);
  for (size_t i = 0; i < F.size(); ++i) m.F.row(static_cast<Eigen::Index>(i)) = F[i];
  return m;
}

TriMesh transformed(TriMesh m, const Eigen::Matrix3d& R, const Eigen::Vector3d& shift) {
  m.V = ((m.V * R.transpose()).rowwise() + shift.transpose()).eval();
  return m;
}

// Volume, centroid and central second moments of a closed surface's solid: tetrahedra from the
// vertices' mean, each integrated by the 4-point rule exact for quadratics (barycentrics a, b, b, b),
// a different quadrature from solid_moments' closed form.
struct Moments {
  double volume = 0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
};
Moments moments(const TriMesh& m) {
  const Eigen::Vector3d o = m.V.colwise().mean().transpose();
  const double a = 0.5854101966249685, b = 0.1381966011250105;
  double vol = 0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (int f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d p[4] = {o, m.V.row(m.F(f, 0)).transpose(), m.V.row(m.F(f, 1)).transpose(),
                                  m.V.row(m.F(f, 2)).transpose()};
    const double v = (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0])) / 6;
    vol += v;
    for (int q = 0; q < 4; ++q) {
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      for (int k = 0; k < 4; ++k) x += (k == q ? a : b) * p[k];
      first += v / 4 * x;
      second += v / 4 * x * x.transpose();
    }
  }
  Moments r;
  r.volume = vol;
  r.centroid = first / vol;
  r.second = second - vol * r.centroid * r.centroid.transpose();
  return r;
}

// Connected pieces of a triangle list (by shared vertices).
int pieces(const Eigen::MatrixXi& F, int n) {
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> find = [&](int x) { return parent[x] == x ? x : parent[x] = find(parent[x]); };
  std::vector<char> used(n, 0);
  for (int f = 0; f < F.rows(); ++f)
    for (int j = 0; j < 3; ++j) {
      used[F(f, j)] = 1;
      parent[find(F(f, j))] = find(F(f, (j + 1) % 3));
    }
  int c = 0;
  for (int v = 0; v < n; ++v) c += used[v] && find(v) == v;
  return c;
}

struct Bits {
  size_t operator()(const Eigen::Vector3d& p) const {
    return std::hash<double>()(p.x()) * 31 + std::hash<double>()(p.y()) * 17 + std::hash<double>()(p.z());
  }
};

// The key slices are the keys: every key vertex bit for bit, every slice vertex on the key, closed with
// the key's volume. Where the conforming step leaves a key's triangles missing (exact = false: the
// slice there takes the tetrahedralization's faces, transition.h) the volume is held to 1e-3 and
// closedness reported.
void check_key_slices(const AnimationManifold& M, const TriMesh& S, double t0, const TriMesh& T, double t1,
                      bool exact = true) {
  for (int k = 0; k < 2; ++k) {
    const TriMesh& key = k == 0 ? S : T;
    INFO("key " << k);
    const ManifoldSlice s = slice_manifold(M, SliceAxis::T, k == 0 ? t0 : t1);
    if (exact) CHECK(is_closed_and_oriented(s.mesh.F));
    else if (!is_closed_and_oriented(s.mesh.F)) WARN("key " << k << " slice not closed");
    const double diag = (key.V.colwise().maxCoeff() - key.V.colwise().minCoeff()).norm();
    CHECK(dfm::test::max_distance_to_surface(s.mesh.V, key) <= 1e-12 * diag);
    std::unordered_set<Eigen::Vector3d, Bits> at;
    for (int v = 0; v < s.mesh.V.rows(); ++v) at.insert(s.mesh.V.row(v).transpose());
    int absent = 0;
    for (int v = 0; v < key.V.rows(); ++v) absent += !at.count(key.V.row(v).transpose());
    CHECK(absent == 0);
    CHECK(std::abs(enclosed_volume(s.mesh.V, s.mesh.F) - enclosed_volume(key.V, key.F)) <=
          (exact ? 1e-9 : 1e-3) * enclosed_volume(key.V, key.F));
  }
}

// The longest principal axis of a solid (unit).
Eigen::Vector3d longest_axis(const Eigen::Matrix3d& second) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> e(second);
  return e.eigenvectors().col(2);
}

}  // namespace

// ---- formulas ------------------------------------------------------------------------------------

TEST_CASE("solid moments: a box's volume, centroid and second moments, whatever its triangulation", "[align]") {
  const Eigen::Vector3d lo(1, -2, 0.5), size(4, 1, 2);
  for (bool other : {false, true}) {
    const TriMesh box = grid_box(lo, lo + size, Eigen::Vector3i(5, 2, 3), other);
    const SolidMoments m = solid_moments(box.V, box.F);
    const double V = size.prod();
    CHECK(m.volume == Approx(V).epsilon(1e-13));
    CHECK((m.centroid - (lo + size / 2)).norm() < 1e-13);
    // Integral of (x - c)^2 over [-a/2, a/2] x ... is V a^2 / 12; the products vanish.
    const Eigen::Matrix3d ref = (V / 12 * size.cwiseProduct(size)).asDiagonal();
    CHECK((m.second - ref).norm() < 1e-12 * ref.norm());
  }
  // Turned and moved: R M R^T about the moved centroid.
  const Eigen::Matrix3d R = rodrigues(Eigen::Vector3d(1, 2, 3), 37);
  const TriMesh box = grid_box(lo, lo + size, Eigen::Vector3i(3, 1, 2), false);
  const SolidMoments a = solid_moments(box.V, box.F), b = solid_moments(transformed(box, R, {5, 6, 7}).V, box.F);
  CHECK((b.centroid - (R * a.centroid + Eigen::Vector3d(5, 6, 7))).norm() < 1e-12);
  CHECK((b.second - R * a.second * R.transpose()).norm() < 1e-12 * a.second.norm());
  // The quadrature reference agrees on an icosphere (a check of the reference itself).
  const TriMesh ico = dfm::test::icosphere(Eigen::Vector3d(0.3, 0, 0), 0.7, 2);
  const SolidMoments s = solid_moments(ico.V, ico.F);
  const Moments q = moments(ico);
  CHECK(s.volume == Approx(q.volume).epsilon(1e-12));
  CHECK((s.second - q.second).norm() < 1e-12 * q.second.norm());
}

TEST_CASE("principal rotation: the smallest turn the moments allow", "[align]") {
  const Eigen::Matrix3d M0 = Eigen::Vector3d(1, 2, 5).asDiagonal();
  SECTION("distinct moments: the turn itself") {
    const Eigen::Matrix3d R = rodrigues(Eigen::Vector3d(1, -1, 2), 30);
    CHECK((principal_rotation(M0, R * M0 * R.transpose()) - R).norm() < 1e-12);
  }
  SECTION("distinct moments, turned 170 degrees about an axis: the axis flips are free, 10 degrees back") {
    const Eigen::Matrix3d R = rodrigues(Eigen::Vector3d::UnitZ(), 170);
    const Eigen::Matrix3d got = principal_rotation(M0, 3.0 * R * M0 * R.transpose());  // scale does not matter
    CHECK((got - rodrigues(Eigen::Vector3d::UnitZ(), -10)).norm() < 1e-12);
  }
  SECTION("one distinct axis (a square section): the shortest turn between the distinct axes") {
    const Eigen::Matrix3d A = Eigen::Vector3d(1, 1, 5).asDiagonal();
    const Eigen::Matrix3d R = rodrigues(Eigen::Vector3d(1, 0, 0), 90) * rodrigues(Eigen::Vector3d(0, 0, 1), 25);
    const Eigen::Matrix3d got = principal_rotation(A, R * A * R.transpose());
    CHECK(angle_degrees(got) == Approx(90).margin(1e-9));
    CHECK(std::abs((got * Eigen::Vector3d::UnitZ()).dot(Eigen::Vector3d::UnitY())) == Approx(1).margin(1e-12));
    CHECK(std::abs(Eigen::AngleAxisd(got).axis().x()) == Approx(1).margin(1e-9));
  }
  SECTION("no distinct axis (a sphere): no turn") {
    const Eigen::Matrix3d R = rodrigues(Eigen::Vector3d(1, 1, 0), 60);
    const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
    CHECK(principal_rotation(I, R * (1.01 * I) * R.transpose()).isApprox(I, 1e-15));
  }
}

TEST_CASE("placement: identity at 0, the key's at 1, a half turn is a half turn", "[align]") {
  KeyPlacement p;
  p.c0 = Eigen::Vector3d(1, 2, 3);
  p.c1 = Eigen::Vector3d(-4, 0, 2);
  p.scale = 0.5;
  p.R = rodrigues(Eigen::Vector3d(0, 0, 1), 180);
  const Eigen::RowVector3d x(2.5, 2, 3);  // 1.5 from c0 along x
  CHECK((placed_at(p, 0, x).array() == x.array()).all());
  // u = 1: c1 + scale R (x - c0), and to_source_frame undoes it.
  const Eigen::RowVector3d one = placed_at(p, 1, x);
  CHECK((one - Eigen::RowVector3d(-4 - 0.75, 0, 2)).norm() < 1e-15 * 10);
  CHECK((to_source_frame(p, one) - x).norm() < 1e-14);
  // u = 1/2: halfway, scale (1 + 0.5) / 2, turned a quarter (about +z or -z: the half turn's axis has
  // no sign).
  const Eigen::RowVector3d half = placed_at(p, 0.5, x);
  const Eigen::RowVector3d mid = (p.c0 + p.c1).transpose() / 2;
  CHECK((half - mid).norm() == Approx(0.75 * 1.5).epsilon(1e-12));
  CHECK(std::abs((half - mid).x()) < 1e-12);
  CHECK(std::abs((half - mid).z()) < 1e-12);
  // A general turn: R(u) is Rodrigues about R's axis by u times its angle.
  p.R = rodrigues(Eigen::Vector3d(1, 2, 2), 120);
  p.scale = 2;
  for (double u : {0.1, 0.25, 0.7}) {
    const Eigen::Vector3d ref = (1 - u) * p.c0 + u * p.c1 +
                                ((1 - u) + u * 2) * rodrigues(Eigen::Vector3d(1, 2, 2), 120 * u) * (x.transpose() - p.c0);
    CHECK((placed_at(p, u, x).transpose() - ref).norm() < 1e-12);
  }
}

TEST_CASE("pair position: a picked pair travels from its point to its partner, turning with the placement", "[align]") {
  // Key 1 is key 0 turned a quarter about z through the origin: a point at (1, 0, 0) paired with
  // its image (0, 1, 0) goes round the arc, at u (cos(90 u), sin(90 u), 0), not along the chord.
  KeyPlacement p;
  p.R = rodrigues(Eigen::Vector3d(0, 0, 1), 90);
  const Eigen::Matrix<double, 1, 6> pair = (Eigen::Matrix<double, 1, 6>() << 1, 0, 0, 0, 1, 0).finished();
  for (double u : {0.0, 0.25, 0.5, 1.0}) {
    const double a = M_PI / 2 * u;
    CHECK((pair_position(p, pair, u) - Eigen::RowVector3d(std::cos(a), std::sin(a), 0)).norm() < 1e-12);
  }
  // A partner off the image: the frame point moves straight from x0 to A(x1), then is placed. With
  // scale 2 about c0 = (1, 1, 0) and no turn, A(x1) = c0 + (x1 - c1) / 2.
  p = KeyPlacement{};
  p.c0 = Eigen::Vector3d(1, 1, 0);
  p.c1 = Eigen::Vector3d(1, 1, 4);
  p.scale = 2;
  const Eigen::Matrix<double, 1, 6> off = (Eigen::Matrix<double, 1, 6>() << 2, 1, 0, 1, 1, 6).finished();
  const Eigen::RowVector3d x0(2, 1, 0), a1 = Eigen::RowVector3d(1, 1, 0) + (Eigen::RowVector3d(1, 1, 6) - Eigen::RowVector3d(1, 1, 4)) / 2;
  for (double u : {0.0, 0.3, 1.0}) {
    const Eigen::RowVector3d y = x0 + u * (a1 - x0), c0(1, 1, 0), c1(1, 1, 4);
    const Eigen::RowVector3d want = c0 + u * (c1 - c0) + ((1 - u) + u * 2) * (y - c0);
    CHECK((pair_position(p, off, u) - want).norm() < 1e-12);
  }
  CHECK((pair_position(p, off, 1) - Eigen::RowVector3d(1, 1, 6)).norm() < 1e-12);
  // The transition's own placement: none without alignment.
  TransitionOptions o;
  o.align = false;
  const KeyPlacement none = transition_placement(dfm::test::icosphere(Eigen::Vector3d::Zero(), 0.5, 1),
                                                 dfm::test::icosphere(Eigen::Vector3d(3, 0, 0), 0.3, 1), o);
  CHECK(none.c1 == Eigen::Vector3d::Zero());
  CHECK(none.scale == 1);
}

TEST_CASE("space warp: through its pairs, affine maps exactly, its inverse, its derivative", "[align]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> r(-1, 1);
  Eigen::MatrixXd from(7, 3), to(7, 3);
  for (int i = 0; i < 7; ++i)
    for (int k = 0; k < 3; ++k) from(i, k) = r(rng) + 5, to(i, k) = from(i, k) + 0.2 * r(rng);
  const SpaceWarp w = fit_space_warp(from, to);
  for (int i = 0; i < 7; ++i) CHECK((warp(w, from.row(i)) - to.row(i)).norm() < 1e-12);
  for (int i = 0; i < 20; ++i) {
    const Eigen::RowVector3d x(r(rng) + 5, r(rng) + 5, r(rng) + 5);
    CHECK((warp(w, unwarp(w, x)) - x).norm() < 1e-12);
    CHECK((warp(w, x, 0.25) - (x + 0.25 * (warp(w, x) - x))).norm() < 1e-14);
    // Central differences of D.
    Eigen::Matrix3d J;
    for (int k = 0; k < 3; ++k) {
      Eigen::RowVector3d e = Eigen::RowVector3d::Zero();
      e[k] = 1e-6;
      J.col(k) = (w.displacement(x + e) - w.displacement(x - e)).transpose() / 2e-6;
    }
    CHECK((J - w.displacement_jacobian(x)).norm() < 1e-6);
  }
  // Pairs on an affine map: the warp is that map everywhere.
  Eigen::Matrix3d A;
  A << 1.1, 0.2, 0, -0.1, 0.9, 0.05, 0, 0.1, 1.2;
  const Eigen::RowVector3d b(0.3, -0.2, 0.1);
  const Eigen::MatrixXd to_affine = (from * A.transpose()).rowwise() + b;
  const SpaceWarp wa = fit_space_warp(from, to_affine);
  for (int i = 0; i < 10; ++i) {
    const Eigen::RowVector3d x(3 * r(rng), 3 * r(rng), 3 * r(rng));
    CHECK((warp(wa, x) - (x * A.transpose() + b)).norm() < 1e-9);
  }
  // One pair: a translation.
  const SpaceWarp one = fit_space_warp(from.topRows(1), to.topRows(1));
  CHECK((warp(one, Eigen::RowVector3d(9, 9, 9)) - (Eigen::RowVector3d(9, 9, 9) + to.row(0) - from.row(0))).norm() < 1e-12);
  // A reflection has no inverse that keeps space's orientation.
  Eigen::MatrixXd mirrored = from;
  mirrored.col(0) = (10 - from.col(0).array()).matrix();
  CHECK_THROWS_WITH(unwarp(fit_space_warp(from, mirrored), Eigen::RowVector3d(5, 5, 5)), Catch::Contains("fold"));
  CHECK_THROWS_WITH(fit_space_warp(from.topRows(2).replicate(2, 1), to.topRows(4)), Catch::Contains("coincide"));
}

TEST_CASE("space warp: pairs near a plane keep the affine part to the plane", "[align]") {
  // Six points on the plane z = 0, lifted off it by up to 2% of their spread, sent to the plane z = 0
  // turned by 30 degrees and moved. Nothing in the pairs says how space stretches across the plane:
  // an affine part fitted to the lifts would read their flattening as squashing z (dW_z/dz near 0).
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> r(-1, 1);
  Eigen::MatrixXd from(6, 3), to(6, 3);
  const Eigen::Matrix3d turn = rodrigues(Eigen::Vector3d::UnitZ(), 30);
  for (int i = 0; i < 6; ++i) {
    from.row(i) << std::cos(i * M_PI / 3), std::sin(i * M_PI / 3), 0.02 * r(rng);
    to.row(i) = (turn * Eigen::Vector3d(from(i, 0), from(i, 1), 0)).transpose() + Eigen::RowVector3d(0.3, 0.1, 0);
  }
  const SpaceWarp w = fit_space_warp(from, to);
  for (int i = 0; i < 6; ++i) CHECK((warp(w, from.row(i)) - to.row(i)).norm() < 1e-12);
  // On the plane: dW/dz is e_z up to the lifts' own displacements (0.02 over a spread of 1), and W
  // turns by 30 degrees within the plane.
  for (int i = 0; i < 30; ++i) {
    const Eigen::RowVector3d x(0.8 * r(rng), 0.8 * r(rng), 0);
    const Eigen::Matrix3d J = Eigen::Matrix3d::Identity() + w.displacement_jacobian(x);
    INFO("at " << x << ": dW/dz " << J.col(2).transpose());
    CHECK((J.col(2) - Eigen::Vector3d::UnitZ()).norm() < 0.1);
    CHECK((J.topLeftCorner<2, 2>() - turn.topLeftCorner<2, 2>()).norm() < 0.1);
  }
}

TEST_CASE("warp path: straight paths, through its pairs, affine maps exactly, its inverse, no fold where one warp folds",
          "[align]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> r(-1, 1);
  Eigen::MatrixXd from(7, 3), to(7, 3);
  for (int i = 0; i < 7; ++i)
    for (int k = 0; k < 3; ++k) from(i, k) = r(rng), to(i, k) = from(i, k) + 0.5 * r(rng);
  const WarpPath path = fit_warp_path(from, to, 8);
  REQUIRE(path.steps.size() == 8);
  for (int i = 0; i < 7; ++i)
    for (double u : {0.0, 0.3, 0.5, 0.97, 1.0})
      CHECK((warp(path, from.row(i), u) - (from.row(i) + u * (to.row(i) - from.row(i)))).norm() < 1e-10);
  for (int i = 0; i < 10; ++i) {
    const Eigen::RowVector3d x(r(rng), r(rng), r(rng));
    CHECK((unwarp(path, warp(path, x)) - x).norm() < 1e-10);
    CHECK(warp(path, x, 0) == x);
  }
  // Pairs on an affine map: W_u is (1 - u) x + u (A x + b) everywhere, as one warp's in-between is.
  Eigen::Matrix3d A;
  A << 1.1, 0.2, 0, -0.1, 0.9, 0.05, 0, 0.1, 1.2;
  const Eigen::RowVector3d b(0.3, -0.2, 0.1);
  const WarpPath affine = fit_warp_path(from, (from * A.transpose()).rowwise() + b, 8);
  for (int i = 0; i < 10; ++i) {
    const Eigen::RowVector3d x(2 * r(rng), 2 * r(rng), 2 * r(rng));
    for (double u : {0.2, 0.55, 1.0})
      CHECK((warp(affine, x, u) - ((1 - u) * x + u * (x * A.transpose() + b))).norm() < 1e-9);
  }
  // An inner ring turned by 120 degrees inside a pinned outer ring (and pinned poles): one warp
  // through the pairs folds space between the rings; the path's eighth steps do not.
  Eigen::MatrixXd in(14, 3), out(14, 3);
  const Eigen::Matrix3d turn = rodrigues(Eigen::Vector3d::UnitZ(), 120);
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d p(std::cos(i * M_PI / 3), std::sin(i * M_PI / 3), 0);
    in.row(i) = p.transpose(), out.row(i) = (turn * p).transpose();
    in.row(6 + i) = out.row(6 + i) = 2.5 * p.transpose();
  }
  in.row(12) = out.row(12) = Eigen::RowVector3d(0, 0, 1);
  in.row(13) = out.row(13) = Eigen::RowVector3d(0, 0, -1);
  const SpaceWarp one = fit_space_warp(in, out);
  const WarpPath eight = fit_warp_path(in, out, 8);
  double one_worst = HUGE_VAL;
  int folds = 0;
  for (int a = 0; a < 48; ++a)
    for (double radius : {1.25, 1.5, 1.75, 2.0, 2.25}) {
      const Eigen::RowVector3d x(radius * std::cos(a * M_PI / 24), radius * std::sin(a * M_PI / 24), 0);
      one_worst = std::min(one_worst, (Eigen::Matrix3d::Identity() + one.displacement_jacobian(x)).determinant());
      if (fold_time(eight, x)) ++folds;
      // The path's image is reached back.
      CHECK((unwarp(eight, warp(eight, x)) - x).norm() < 1e-9);
    }
  INFO("one warp's smallest det(dW/dx) between the rings: " << one_worst);
  CHECK(one_worst <= 0);
  CHECK(folds == 0);
  CHECK_THROWS_WITH(fit_warp_path(in, out, 0), Catch::Contains("step"));
  // Two points swapping places meet half way.
  Eigen::MatrixXd swap = in;
  swap.row(0) = in.row(3), swap.row(3) = in.row(0);
  CHECK_THROWS_WITH(fit_warp_path(in, swap, 8), Catch::Contains("fold") && Catch::Contains("u = 0.5"));
}

// ---- acceptance (issue 30) -----------------------------------------------------------------------

TEST_CASE("transition travels: a small sphere 3 away", "[transition][align]") {
  // Before alignment the slices at 0.25 .. 0.75 were empty (the blend of two far-apart distances).
  const TriMesh S = dfm::test::icosphere(Eigen::Vector3d::Zero(), 1, 3);
  const TriMesh T = dfm::test::icosphere(Eigen::Vector3d(3, 0, 0), 0.6, 2);
  TransitionStats st;
  const AnimationManifold M = build_transition(S, 0, T, 1, {}, &st);
  validate_manifold(M, "travel");
  INFO(st.tets << " tets, " << st.total_seconds << " s");
  check_key_slices(M, S, 0, T, 1);
  const double V0 = enclosed_volume(S.V, S.F), V1 = enclosed_volume(T.V, T.F);
  for (double t : {0.1, 0.25, 0.5, 0.75, 0.9}) {
    INFO("t = " << t);
    const ManifoldSlice s = slice_manifold(M, SliceAxis::T, t);
    REQUIRE(s.mesh.F.rows() > 0);
    CHECK(is_closed_and_oriented(s.mesh.F));
    CHECK(pieces(s.mesh.F, static_cast<int>(s.mesh.V.rows())) == 1);
    CHECK(euler_characteristic(s.mesh.F) == 2);
    const Moments m = moments(s.mesh);
    INFO("centroid " << m.centroid.transpose() << ", volume " << m.volume << " (keys " << V0 << ", " << V1 << ")");
    CHECK((m.centroid - Eigen::Vector3d(3 * t, 0, 0)).norm() <= 0.02 * 3);
    CHECK(m.volume >= 0.95 * V1);
    CHECK(m.volume <= 1.05 * V0);
    // The documented morph: unit spheres in the source's frame, placed by P_t: a sphere of radius
    // (1 - t) + 0.6 t about (3t, 0, 0).
    const double radius = (1 - t) + 0.6 * t;
    double worst = 0;
    for (int v = 0; v < s.mesh.V.rows(); ++v)
      worst = std::max(worst, std::abs((s.mesh.V.row(v) - Eigen::RowVector3d(3 * t, 0, 0)).norm() - radius));
    // The middle layers sample the field at twice the coarser key's edge (0.6 of the aligned radius
    // here), and the slice's facets cut inside the sphere: 7-14% of the radius measured.
    INFO("farthest from the reference sphere: " << worst);
    CHECK(worst <= 0.2 * radius);
  }
}

TEST_CASE("transition turns: a 4 x 1 x 1 box turned a quarter about z, moved, triangulated differently",
          "[transition][align]") {
  // Quads of 1/16 and 1/12: the middle layers' spacing (twice the coarser key's edge) rounds the
  // box's edges; at quads of 1/4 and 1/3 the slice lost 38% of the volume, turned or not (the issue's
  // fidelity item). Here 2.4% unturned.
  const TriMesh S = grid_box(Eigen::Vector3d(-2, -0.5, -0.5), Eigen::Vector3d(2, 0.5, 0.5), Eigen::Vector3i(64, 16, 16), false);
  const Eigen::Vector3d shift(1.5, 2, 0.5);
  const TriMesh T = transformed(grid_box(Eigen::Vector3d(-2, -0.5, -0.5), Eigen::Vector3d(2, 0.5, 0.5),
                                         Eigen::Vector3i(48, 12, 12), true),
                                rodrigues(Eigen::Vector3d::UnitZ(), 90), shift);
  TransitionStats st;
  const AnimationManifold M = build_transition(S, 0, T, 1, {}, &st);
  validate_manifold(M, "turn");
  INFO(st.tets << " tets, turn " << st.turn_degrees << " degrees, " << M.num_slabs() << " slabs, " << st.total_seconds << " s");
  CHECK(st.turn_degrees == Approx(90).margin(1e-6));
  check_key_slices(M, S, 0, T, 1);
  for (double t : {0.25, 0.5, 0.75}) {
    INFO("t = " << t);
    const ManifoldSlice s = slice_manifold(M, SliceAxis::T, t);
    CHECK(is_closed_and_oriented(s.mesh.F));
    CHECK(pieces(s.mesh.F, static_cast<int>(s.mesh.V.rows())) == 1);
    const Moments m = moments(s.mesh);
    const Eigen::Vector3d a = longest_axis(m.second);
    const double deg = std::acos(std::min(1.0, std::abs(a.x()))) * 180 / M_PI;
    INFO("longest axis " << a.transpose() << ": " << deg << " degrees from x; volume " << m.volume);
    CHECK(deg == Approx(90 * t).margin(5));
    CHECK(std::abs(a.z()) < 0.05);
    CHECK(m.volume == Approx(4).epsilon(0.05));
    CHECK((m.centroid - t * shift).norm() < 0.02 * shift.norm());
  }
}

namespace {

// An ellipsoid with radii (2, 0.8, 0.8) with bumps of relative height h around the unit directions q
// and its mirror image in y (of the sphere it is scaled from: icosphere vertices p move to
// p (1 + h sum exp(-|p - q|^2 / 0.35^2))). Symmetric in y and z, so z and y are principal axes.
TriMesh bumpy(int level, Eigen::Vector3d q, double h) {
  TriMesh m = dfm::test::icosphere(Eigen::Vector3d::Zero(), 1, level);
  q.normalize();
  const Eigen::Vector3d q2(q.x(), -q.y(), q.z());
  for (int v = 0; v < m.V.rows(); ++v) {
    const Eigen::Vector3d p = m.V.row(v).transpose();
    const double bump = std::exp(-(p - q).squaredNorm() / (0.35 * 0.35)) + std::exp(-(p - q2).squaredNorm() / (0.35 * 0.35));
    m.V.row(v) = (p * (1 + h * bump)).cwiseProduct(Eigen::Vector3d(2, 0.8, 0.8)).transpose();
  }
  return m;
}

int nearest_vertex(const TriMesh& m, const Eigen::Vector3d& x) {
  int best = 0;
  for (int v = 1; v < m.V.rows(); ++v)
    if ((m.V.row(v).transpose() - x).norm() < (m.V.row(best).transpose() - x).norm()) best = v;
  return best;
}

// The distance from p to the nearest triangle of m.
double distance_to(const TriMesh& m, const Eigen::Vector3d& p) {
  double best = 1e300;
  for (int f = 0; f < m.F.rows(); ++f)
    best = std::min(best, dfm::test::point_triangle_distance(p, m.V.row(m.F(f, 0)).transpose(), m.V.row(m.F(f, 1)).transpose(),
                                                             m.V.row(m.F(f, 2)).transpose()));
  return best;
}

// The placement of keys symmetric under z -> -z (z a principal axis), by the documented definition
// with a closed-form 2D principal axis: centroids, the ratio of radii of gyration, and the turn about
// z between the long axes' directions in the xy plane (the smaller of the two ways).
struct PlanarPlacement {
  Eigen::Vector3d c0, c1;
  double scale, degrees;
  Eigen::Vector3d to_source(const Eigen::Vector3d& x) const {
    return c0 + rodrigues(Eigen::Vector3d::UnitZ(), -degrees) * (x - c1) / scale;
  }
  Eigen::Vector3d at(double u, const Eigen::Vector3d& x) const {
    return (1 - u) * c0 + u * c1 + ((1 - u) + u * scale) * rodrigues(Eigen::Vector3d::UnitZ(), u * degrees) * (x - c0);
  }
};
PlanarPlacement planar_placement(const TriMesh& a, const TriMesh& b) {
  const Moments ma = moments(a), mb = moments(b);
  auto direction = [](const Eigen::Matrix3d& M) {  // of the largest moment in the xy plane, degrees
    return 0.5 * std::atan2(2 * M(0, 1), M(0, 0) - M(1, 1)) * 180 / M_PI;
  };
  double d = direction(mb.second) - direction(ma.second);
  while (d > 90) d -= 180;
  while (d <= -90) d += 180;
  return {ma.centroid, mb.centroid, std::sqrt((mb.second.trace() / mb.volume) / (ma.second.trace() / ma.volume)), d};
}

}  // namespace

// [heavy]: release only (16 s there, about 150 s under the sanitizers); the pairs' warp runs there in
// test_cli_key_mesh's --pairs case and this file's turn and travel cases.
TEST_CASE("transition pairs: bumps that move along the top and bottom follow their picked pairs",
          "[transition][align][heavy]") {
  // Two bumps (above and below) near the +x end of the source and near the -x end of the target (a
  // coarser icosphere's, so a transition). The keys are mirror images: alignment only shifts the
  // target by the centroids' difference, and the morph alone fades the bumps and grows the others. A
  // pair from tip to tip for each bump, with pairs pinning the ends, front and back, carries them over.
  const Eigen::Vector3d q0(0.35, 0.94, 0), q1(-0.35, 0.94, 0);
  const TriMesh S = bumpy(4, q0, 0.6), T = bumpy(3, q1, 0.6);
  // The in-between's sampling (the middle layers' spacing) blunts the ellipsoid's ends and the tips
  // by 1.5-3% of the diagonal at the default spacing (2), 1.2-1.7% at 1.5 (the fidelity item,
  // with or without pairs): the test samples at 1.
  TransitionOptions with, without;
  with.spacing = without.spacing = 1;
  const double diag = (S.V.colwise().maxCoeff().cwiseMax(T.V.colwise().maxCoeff()) -
                       S.V.colwise().minCoeff().cwiseMin(T.V.colwise().minCoeff())).norm();
  const Eigen::Vector3d tip = q0.normalized().cwiseProduct(Eigen::Vector3d(3.2, 1.28, 1.28));
  // The ends must be pinned: the tips and the front and back alone fit an affine map that mirrors x.
  const std::vector<Eigen::Vector3d> spots = {tip, {tip.x(), -tip.y(), 0}, {0, 0, 0.8}, {0, 0, -0.8}, {2, 0, 0}, {-2, 0, 0}};
  Eigen::MatrixXd pairs(static_cast<Eigen::Index>(spots.size()), 6);
  for (size_t i = 0; i < spots.size(); ++i) {
    const Eigen::Vector3d other = i < 2 ? Eigen::Vector3d(-spots[i].x(), spots[i].y(), 0) : spots[i];
    pairs.row(static_cast<Eigen::Index>(i)) << S.V.row(nearest_vertex(S, spots[i])), T.V.row(nearest_vertex(T, other));
  }
  INFO("tip pair " << pairs.row(0));
  const PlanarPlacement P = planar_placement(S, T);
  INFO("placement: turn " << P.degrees << " degrees, scale " << P.scale << ", centroids " << P.c0.transpose() << " / "
                          << P.c1.transpose());
  auto path = [&](int i, double u) {
    const Eigen::Vector3d x0 = pairs.row(i).head<3>().transpose(), x1 = pairs.row(i).tail<3>().transpose();
    return P.at(u, x0 + u * (P.to_source(x1) - x0));
  };
  with.pairs = pairs;
  TransitionStats st, sp;
  const AnimationManifold M = build_transition(S, 0, T, 1, with, &st), plain = build_transition(S, 0, T, 1, without, &sp);
  INFO(st.total_seconds << " s; triangles not conforming: with pairs " << st.source.missing << " + " << st.target.missing
       << ", without " << sp.source.missing << " + " << sp.target.missing);
  validate_manifold(M, "pairs");
  CHECK(st.turn_degrees == Approx(std::abs(P.degrees)).margin(1e-6));
  // The bumps' flanks cost the conforming step triangles (4 of the target's stay missing, 17 of the warped
  // target's, whose key slice is then not closed; without pairs the key volumes are 1.5e-7 and 2e-4 off):
  // the key slices are held as transition.h's non-conforming keys are.
  check_key_slices(plain, S, 0, T, 1, false);
  check_key_slices(M, S, 0, T, 1, false);
  for (double t : {0.25, 0.5, 0.75}) {
    INFO("t = " << t);
    const ManifoldSlice s = slice_manifold(M, SliceAxis::T, t), s_plain = slice_manifold(plain, SliceAxis::T, t);
    CHECK(is_closed_and_oriented(s.mesh.F));
    CHECK(pieces(s.mesh.F, static_cast<int>(s.mesh.V.rows())) == 1);
    for (int i = 0; i < pairs.rows(); ++i) {
      const double d = distance_to(s.mesh, path(i, t));
      INFO("pair " << i + 1 << " at " << path(i, t).transpose() << ": " << d / diag << " of the diagonal");
      CHECK(d <= 0.01 * diag);
    }
    // Alignment alone: the tips' paths are far from the slice in the middle of the move.
    for (int i = 0; i < 2; ++i) {
      const double alone = distance_to(s_plain.mesh, path(i, t));
      INFO("alignment alone: tip " << i + 1 << "'s path is " << alone / diag << " of the diagonal from the slice");
      if (t == 0.5) CHECK(alone > 0.03 * diag);
    }
  }
}

TEST_CASE("elastic pairs: closest points that carry the target onto the source, on both keys, never folding",
          "[align]") {
  // The unit sphere and an ellipsoid (1.5, 1, 0.7) about the same centre, one picked pair at +x.
  const TriMesh S = dfm::test::icosphere(Eigen::Vector3d::Zero(), 1, 3);
  TriMesh T = dfm::test::icosphere(Eigen::Vector3d::Zero(), 1, 2);
  T.V = T.V * Eigen::Vector3d(1.5, 1, 0.7).asDiagonal();
  Eigen::MatrixXd picked(1, 6);
  picked << 1, 0, 0, 1.5, 0, 0;
  const Eigen::MatrixXd extra = elastic_pairs(S, T, picked).pairs;
  REQUIRE(extra.rows() >= 8);
  // Each pair's first point on the source's triangles, its second on the target's (brute force).
  for (Eigen::Index i = 0; i < extra.rows(); ++i) {
    INFO("pair " << extra.row(i));
    CHECK(distance_to(S, extra.row(i).head<3>().transpose()) < 1e-9);
    CHECK(distance_to(T, extra.row(i).tail<3>().transpose()) < 1e-9);
  }
  // The target carried back by the warp lies closer to the sphere than with the picked pair alone.
  auto farthest_from_sphere = [&](const Eigen::MatrixXd& pairs) {
    const WarpPath w = fit_warp_path(pairs.leftCols(3), pairs.rightCols(3), 8);
    double worst = 0;
    for (Eigen::Index v = 0; v < T.V.rows(); ++v) {
      const Eigen::RowVector3d x = unwarp(w, T.V.row(v));
      worst = std::max(worst, std::abs(x.norm() - 1));
      CHECK_FALSE(fold_time(w, x).has_value());
    }
    return worst;
  };
  Eigen::MatrixXd all(1 + extra.rows(), 6);
  all << picked, extra;
  const double alone = farthest_from_sphere(picked), with = farthest_from_sphere(all);
  INFO("farthest carried target vertex from the sphere: " << with << " with the closest-point pairs, " << alone << " without");
  CHECK(alone > 0.25);
  CHECK(with < 0.5 * alone);
  // Picked pairs that fold space leave nothing to add.
  Eigen::MatrixXd swap(2, 6);
  swap << 1, 0, 0, -1.5, 0, 0, -1, 0, 0, 1.5, 0, 0;
  CHECK(elastic_pairs(S, T, swap).pairs.rows() == 0);
  CHECK_THROWS_WITH(elastic_pairs(S, T, Eigen::MatrixXd(1, 3)), Catch::Contains("6 columns"));
}

// [heavy]: release only (about 5 s there).
TEST_CASE("transition pairs: the teddy's hands, feet and head sent round a ring, in one piece", "[transition][align][heavy]") {
  // The default scene's teddy to assets/key-torus.obj, its hands and feet picked to the ring's four
  // diagonals and its head to the top, as an artist would. Those pairs lie nearly in a plane and pull
  // the limbs round: one warp through them folds space (an affine part read off their small
  // deviations from the plane squashed it flat, and alone the pull folds it near the head), the
  // eight-step path does not (space_warp.h).
  const TriMesh S = read_surface(std::string(DFM_SOURCE_DIR) + "/assets/default.obj");
  const TriMesh T = read_surface(std::string(DFM_SOURCE_DIR) + "/assets/key-torus.obj");
  auto extreme = [&](int axis, double sign, double side) {  // the vertex farthest along sign * axis on one side of x = 0
    int best = -1;
    for (int v = 0; v < S.V.rows(); ++v)
      if (side * S.V(v, 0) > 0.1 || side == 0)
        if (best < 0 || sign * S.V(v, axis) > sign * S.V(best, axis)) best = v;
    return Eigen::RowVector3d(S.V.row(best));
  };
  const double c = 0.95 / std::sqrt(2.0);
  Eigen::MatrixXd pairs(5, 6);
  pairs << extreme(0, 1, 0), c, c, 0,                    // right hand to the upper right
      extreme(0, -1, 0), -c, c, 0,                       // left hand to the upper left
      extreme(1, 1, 0), 0, 0.95, 0,                      // head to the top
      extreme(1, -1, 1), c, -c, 0,                       // right foot to the lower right
      extreme(1, -1, -1), -c, -c, 0;                     // left foot to the lower left
  INFO("pairs\n" << pairs);
  const KeyPlacement P = key_placement(solid_moments(S.V, S.F), solid_moments(T.V, T.F));
  const Eigen::MatrixXd to = to_source_frame(P, pairs.rightCols(3));
  const SpaceWarp one = fit_space_warp(pairs.leftCols(3), to);
  double worst = HUGE_VAL;
  for (int v = 0; v < S.V.rows(); ++v)
    for (double u : {0.25, 0.5, 0.75, 1.0})
      worst = std::min(worst, (Eigen::Matrix3d::Identity() + u * one.displacement_jacobian(S.V.row(v))).determinant());
  for (int v = 0; v < T.V.rows(); ++v)  // the target's vertices where one warp would send them
    worst = std::min(worst, (Eigen::Matrix3d::Identity() + one.displacement_jacobian(to_source_frame(P, T.V.row(v)))).determinant());
  INFO("one warp's smallest det(dW_u/dx) on the keys: " << worst);
  CHECK(worst <= 0);

  TransitionOptions o, alone;
  o.pairs = alone.pairs = pairs;
  alone.elastic_samples = 0;
  TransitionStats st, sa;
  const AnimationManifold M = build_transition(S, 0, T, 1, o, &st), picked_only = build_transition(S, 0, T, 1, alone, &sa);
  INFO(st.total_seconds << " s, " << st.elastic_pairs << " elastic pairs; picked pairs alone " << sa.total_seconds << " s");
  CHECK(sa.elastic_pairs == 0);
  CHECK(st.elastic_pairs > 0);
  validate_manifold(M, "teddy pairs");
  const double V0 = enclosed_volume(S.V, S.F), V1 = enclosed_volume(T.V, T.F);
  {
    // Picked alone, the belly and the ring's sides drop out at t = 0.5 (the keys overlap at the limbs
    // only): 75% of the smaller key's volume is left, in two parts joined by a strand. With the
    // closest-point pairs the keys meet along the body: 89%, one figure.
    const TriMesh a = slice_manifold(M, SliceAxis::T, 0.5).mesh, b = slice_manifold(picked_only, SliceAxis::T, 0.5).mesh;
    const double va = enclosed_volume(a.V, a.F), vb = enclosed_volume(b.V, b.F);
    INFO("t = 0.5: volume " << va << " with the closest-point pairs, " << vb << " with the picked pairs alone (keys " << V0
                            << ", " << V1 << ")");
    CHECK(va >= 0.85 * std::min(V0, V1));
    CHECK(va >= 1.1 * vb);
  }
  const double diag = (S.V.colwise().maxCoeff().cwiseMax(T.V.colwise().maxCoeff()) -
                       S.V.colwise().minCoeff().cwiseMin(T.V.colwise().minCoeff())).norm();
  for (double t : {0.25, 0.5, 0.75}) {
    INFO("t = " << t);
    const ManifoldSlice s = slice_manifold(M, SliceAxis::T, t);
    CHECK(is_closed_and_oriented(s.mesh.F));
    CHECK(enclosed_volume(s.mesh.V, s.mesh.F) > 0);
    CHECK(pieces(s.mesh.F, static_cast<int>(s.mesh.V.rows())) == 1);
    // Each picked point on its path P_u(x0 + u (A(x1) - x0)) (transition.h), within 1% of the diagonal.
    for (int i = 0; i < 5; ++i) {
      const Eigen::RowVector3d x0 = pairs.row(i).head<3>(), x1 = to.row(i);
      const Eigen::RowVector3d at = placed_at(P, t, x0 + t * (x1 - x0));
      const double d = distance_to(s.mesh, at.transpose());
      INFO("pair " << i + 1 << " at " << at << ": " << d / diag << " of the diagonal");
      CHECK(d <= 0.01 * diag);
    }
  }
}

TEST_CASE("transition pairs: hostile pairs name the pair and the problem", "[transition][align]") {
  const TriMesh S = dfm::test::icosphere(Eigen::Vector3d::Zero(), 1, 2), T = dfm::test::icosphere(Eigen::Vector3d(3, 0, 0), 0.6, 1);
  Eigen::MatrixXd p(2, 6);
  p << 1, 0, 0, 3.6, 0, 0, 0, 1, 0, 3, 0.6, 0;
  CHECK_FALSE(transition_pair_problem(S, T, p).has_value());
  Eigen::MatrixXd nan = p;
  nan(1, 4) = std::nan("");
  CHECK(transition_pair_problem(S, T, nan)->pair == 1);
  CHECK_THAT(transition_pair_problem(S, T, nan)->problem, Catch::Contains("finite"));
  Eigen::MatrixXd far = p;
  far(0, 0) = 1.5;
  CHECK(transition_pair_problem(S, T, far)->pair == 0);
  CHECK_THAT(transition_pair_problem(S, T, far)->problem, Catch::Contains("first point") && Catch::Contains("from its key"));
  TransitionOptions o;
  o.pairs = far;
  CHECK_THROWS_WITH(build_transition(S, 0, T, 1, o), Catch::Contains("picked pair 1"));
  // Pairs that turn space inside out (the source's +x and -x ends swapped, the rest pinned).
  Eigen::MatrixXd flip(4, 6);
  flip << 1, 0, 0, 2.4, 0, 0, -1, 0, 0, 3.6, 0, 0, 0, 1, 0, 3, 0.6, 0, 0, 0, 1, 3, 0, 0.6;
  o.pairs = flip;
  CHECK_THROWS_WITH(build_transition(S, 0, T, 1, o), Catch::Contains("fold"));
  // The sequence names the keys.
  std::vector<KeySurface> keys = {{0, S.V, S.F, "a.obj"}, {1, T.V, T.F, "b.obj"}};
  keys[0].pairs_to_next = far;
  CHECK_THROWS_WITH(build_manifold_sequence(keys), Catch::Contains("a.obj to b.obj") && Catch::Contains("picked pair 1"));
}
