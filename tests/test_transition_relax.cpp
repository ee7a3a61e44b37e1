// Issue 30: smoothing a transition's sampled level set (level_set_relax.h), against an exact one: a
// growing sphere |x| = r(t) sampled coarsely by marching pentatopes on a jittered 4D lattice.
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "core/anim/delaunay_4d.h"
#include "core/anim/iso_manifold.h"
#include "core/anim/level_set_relax.h"
#include "core/anim/manifold.h"
#include "core/anim/slice.h"
#include "core/anim/surface_checks.h"
#include "core/util/error.h"

using namespace dfm;

namespace {

constexpr double kSpacing = 0.25;
double radius(double t) { return 0.55 + 0.2 * t; }

// The exact level set's outward 4D normal (the field's gradient) at (x, t).
Eigen::Vector4d exact_normal(const Eigen::RowVector4d& p) {
  const Eigen::Vector3d x = p.head<3>().transpose();
  Eigen::Vector4d g;
  g << x.normalized(), -0.2;
  return g.normalized();
}

// <N, w> = det[w, p1 - p0, p2 - p0, p3 - p0] (manifold.h), by cofactors.
Eigen::Vector4d tet_normal(const MatrixX4dRow& V, const Eigen::RowVector4i& t) {
  Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
  for (int k = 0; k < 3; ++k) M.row(k + 1) = V.row(t[k + 1]) - V.row(t[0]);
  Eigen::Vector4d n;
  for (int i = 0; i < 4; ++i) {
    M.row(0) = Eigen::RowVector4d::Unit(i);
    n[i] = M.determinant();
  }
  return n;
}

IsoManifold sphere_level_set() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-0.2 * kSpacing, 0.2 * kSpacing);
  std::vector<Eigen::RowVector4d> pts;
  for (int l = 0; l <= 4; ++l)
    for (int i = 0; i <= 8; ++i)
      for (int j = 0; j <= 8; ++j)
        for (int k = 0; k <= 8; ++k)
          pts.emplace_back(-1 + i * kSpacing + jitter(rng), -1 + j * kSpacing + jitter(rng), -1 + k * kSpacing + jitter(rng),
                           l / 4.0);
  IsoField f;
  f.points.resize(static_cast<Eigen::Index>(pts.size()), 4);
  f.values.resize(f.points.rows());
  for (Eigen::Index p = 0; p < f.points.rows(); ++p) {
    f.points.row(p) = pts[p];
    f.values[p] = pts[p].head<3>().norm() - radius(pts[p][3]);
  }
  f.anchored.assign(pts.size(), 0);
  return iso_manifold(f, delaunay_4d(f.points));
}

// Mean angle (degrees) between the slice's triangle normals and the sphere's at their centroids.
double slice_normal_error(const MatrixX4dRow& V, const MatrixX4iRow& T, double t) {
  AnimationManifold M;
  M.V = V;
  M.T = T;
  M.times = {0.0, 1.0};
  M.slab_offsets = {0, static_cast<int>(T.rows())};
  const TriMesh s = slice_manifold(M, SliceAxis::T, t).mesh;
  REQUIRE(s.F.rows() > 0);
  CHECK(is_closed_and_oriented(s.F));
  CHECK(enclosed_volume(s.V, s.F) > 0);
  double sum = 0;
  for (int f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a).normalized(), e = (a + b + c).normalized();
    sum += std::acos(std::max(-1.0, std::min(1.0, n.dot(e)))) * 180 / M_PI;
  }
  return sum / s.F.rows();
}

}  // namespace

TEST_CASE("relax_level_set: a coarse growing sphere gets closer to the exact normals, stays on it, turns nothing over",
          "[transition]") {
  const IsoManifold iso = sphere_level_set();
  REQUIRE(iso.T.rows() > 1000);
  std::vector<char> movable(iso.V.rows());
  int moving = 0;
  for (Eigen::Index v = 0; v < iso.V.rows(); ++v) moving += movable[v] = iso.V(v, 3) >= 0.25 && iso.V(v, 3) <= 0.75;
  REQUIRE(moving > 100);

  MatrixX4dRow V = iso.V;
  LevelSetRelaxOptions o;
  o.radius = 0.8 * kSpacing;
  o.max_move = 0.5 * kSpacing;
  const LevelSetRelaxStats st = relax_level_set(V, iso.T, movable, o);
  CHECK(st.moved > moving * 9 / 10);

  double worst_before = 0, worst_after = 0, mean_before = 0, mean_after = 0;
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    // Only x, y, z of the movable vertices change; the others stay bit for bit.
    CHECK(V(v, 3) == iso.V(v, 3));
    if (!movable[v]) {
      CHECK(V.row(v) == iso.V.row(v));
      continue;
    }
    const double e0 = std::abs(iso.V.row(v).head<3>().norm() - radius(iso.V(v, 3)));
    const double e1 = std::abs(V.row(v).head<3>().norm() - radius(V(v, 3)));
    worst_before = std::max(worst_before, e0), worst_after = std::max(worst_after, e1);
    mean_before += e0 / moving, mean_after += e1 / moving;
  }
  INFO("distance to the exact sphere, largest: before " << worst_before << ", after " << worst_after << "; mean "
                                                        << mean_before << ", " << mean_after);
  // Marching leaves them up to 0.15 spacings off (chords of the curved sphere); a hyperplane fit
  // pulls them toward its chords, a little farther in on average, never past that.
  CHECK(worst_after <= 0.15 * kSpacing);
  CHECK(mean_after <= 0.05 * kSpacing);

  // No tetrahedron turned over, and those whose corners all moved face the exact normal (the
  // field's gradient) more closely on average.
  double before = 0, after = 0;
  int inner = 0;
  for (Eigen::Index t = 0; t < iso.T.rows(); ++t) {
    const Eigen::RowVector4i q = iso.T.row(t);
    const Eigen::RowVector4d c = 0.25 * (V.row(q[0]) + V.row(q[1]) + V.row(q[2]) + V.row(q[3]));
    const Eigen::Vector4d n0 = tet_normal(iso.V, q), n1 = tet_normal(V, q);
    CHECK(n0.dot(n1) > 0);
    if (movable[q[0]] && movable[q[1]] && movable[q[2]] && movable[q[3]]) {
      before += std::acos(std::min(1.0, n0.normalized().dot(exact_normal(c))));
      after += std::acos(std::min(1.0, n1.normalized().dot(exact_normal(c))));
      ++inner;
    }
  }
  REQUIRE(inner > 100);
  INFO("mean 4D normal error, degrees: before " << before / inner * 180 / M_PI << ", after " << after / inner * 180 / M_PI);
  CHECK(after < 0.95 * before);

  // The slices between the moved layers: closed, outward, normals closer to the sphere's.
  for (double t : {0.4, 0.5, 0.6}) {
    const double e0 = slice_normal_error(iso.V, iso.T, t), e1 = slice_normal_error(V, iso.T, t);
    INFO("t = " << t << ": slice normal error " << e0 << " -> " << e1 << " degrees");
    CHECK(e1 < e0);
  }
}

TEST_CASE("relax_level_set: refuses flags of the wrong size, indices out of range, no radius", "[transition]") {
  MatrixX4dRow V = MatrixX4dRow::Zero(5, 4);
  MatrixX4iRow T(1, 4);
  T << 0, 1, 2, 3;
  CHECK_THROWS_AS(relax_level_set(V, T, std::vector<char>(4, 1), {}), Error);
  LevelSetRelaxOptions none;
  none.radius = 0;
  CHECK_THROWS_AS(relax_level_set(V, T, std::vector<char>(5, 1), none), Error);
  T << 0, 1, 2, 5;
  CHECK_THROWS_AS(relax_level_set(V, T, std::vector<char>(5, 1), {}), Error);
}
