// Shape spaces from morphing (Alexa 2002, ch. 5): Eq. 5.31's chain reproduces each base bit for bit at
// e_i (linear and ARAP), the linear chain is Eq. 5.36's affine combination, linear analysis (5.5.3)
// returns the coordinates a shape was made with and agrees with a Lagrange-multiplier least squares
// written here, and the pad's weights are barycentric coordinates in a brute-force Delaunay triangle.
#include <cmath>
#include <random>

#include <catch2/catch.hpp>
#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "core/anim/arap_interpolation.h"
#include "core/anim/shape_space.h"
#include "core/anim/shape_space_pad.h"
#include "core/util/error.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;

namespace {

// An icosphere with every vertex moved by a seeded random offset (scale s): bases of one connectivity.
std::vector<TriMesh> wobbly_spheres(int n, double s, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const TriMesh sphere = test::icosphere(Eigen::Vector3d::Zero(), 1.0, 1);
  std::vector<TriMesh> out(n, sphere);
  for (TriMesh& m : out)
    for (int i = 0; i < m.V.rows(); ++i)
      for (int c = 0; c < 3; ++c) m.V(i, c) += s * u(rng);
  return out;
}

std::vector<Eigen::MatrixXd> vertices(const std::vector<TriMesh>& meshes) {
  std::vector<Eigen::MatrixXd> out;
  for (const TriMesh& m : meshes) out.push_back(m.V);
  return out;
}

// Eq. 5.36 directly: sum_i x_i V(e_i).
Eigen::MatrixXd affine_combination(const std::vector<Eigen::MatrixXd>& B, const Eigen::VectorXd& x) {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(B[0].rows(), 3);
  for (size_t i = 0; i < B.size(); ++i) out += x(i) * B[i];
  return out;
}

Eigen::VectorXd unit(int n, int i) { return Eigen::VectorXd::Unit(n, i); }

// A bar: the level-1 icosphere stretched 3x along x (closed, 42 vertices: TetGen takes milliseconds).
TriMesh bar() {
  TriMesh m = test::icosphere(Eigen::Vector3d::Zero(), 0.3, 1);
  m.V.col(0) *= 3.0;
  return m;
}

Eigen::MatrixXd rigidly_moved(const Eigen::MatrixXd& V, double angle, const Eigen::Vector3d& axis, const Eigen::RowVector3d& shift) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  return (V * R.transpose()).rowwise() + shift;
}

double max_edge_length_change(const TriMesh& rest, const Eigen::MatrixXd& U) {
  double err = 0;
  for (int f = 0; f < rest.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = rest.F(f, k), b = rest.F(f, (k + 1) % 3);
      err = std::max(err, std::abs((U.row(a) - U.row(b)).norm() - (rest.V.row(a) - rest.V.row(b)).norm()));
    }
  return err;
}

}  // namespace

TEST_CASE("shape space: Eq. 5.31's chain order, the linear chain is the affine combination (5.36)", "[anim][shape_space]") {
  // x = (0.2, 0, 0.5, 0, 0.3): C_4 = B_4, C_3 = C_4 (x_3 = 0), C_2 = m(B_2, C_3, 0.3 / 0.8), C_1 = C_2,
  // C_0 = m(B_0, C_1, 0.8 / 1).
  Eigen::VectorXd x(5);
  x << 0.2, 0, 0.5, 0, 0.3;
  const MorphChain chain = morph_chain(x);
  CHECK(chain.start == 4);
  REQUIRE(chain.steps.size() == 2);
  CHECK(chain.steps[0].base == 2);
  CHECK(chain.steps[0].t == Approx(0.3 / 0.8).epsilon(1e-15));
  CHECK(chain.steps[1].base == 0);
  CHECK(chain.steps[1].t == Approx(0.8).epsilon(1e-15));

  const std::vector<Eigen::MatrixXd> B = vertices(wobbly_spheres(5, 0.2, 7));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.5, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd w(5);
    for (int i = 0; i < 5; ++i) w(i) = u(rng);  // extrapolating weights too
    w(0) += 1.0 - w.sum();                       // barycentric
    if (std::abs(w.tail(4).sum()) < 0.1) continue;  // keep partial sums away from 0
    const Eigen::MatrixXd got = synthesize_linear(B, w), want = affine_combination(B, w);
    CHECK((got - want).cwiseAbs().maxCoeff() < 1e-12);
  }
}

TEST_CASE("shape space: each base at its own coordinates e_i, bit for bit (linear)", "[anim][shape_space]") {
  const std::vector<TriMesh> meshes = wobbly_spheres(4, 0.3, 11);
  const std::vector<Eigen::MatrixXd> B = vertices(meshes);
  ShapeSpace space(meshes, {}, ShapeMorph::Linear);
  for (int i = 0; i < 4; ++i) {
    CHECK(synthesize_linear(B, unit(4, i)) == B[i]);
    CHECK(space.synthesize(unit(4, i)) == B[i]);
  }
}

TEST_CASE("shape space: linear analysis returns the coordinates a shape was made with (5.5.3)", "[anim][shape_space]") {
  const std::vector<Eigen::MatrixXd> B = vertices(wobbly_spheres(4, 0.3, 5));
  for (const Eigen::Vector4d& x : {Eigen::Vector4d(0.1, 0.4, -0.2, 0.7), Eigen::Vector4d(0.25, 0.25, 0.25, 0.25),
                                   Eigen::Vector4d(1.5, -0.3, 0.1, -0.3), Eigen::Vector4d(0, 0, 1, 0)}) {
    // From the affine combination written here and from the production chain.
    for (const Eigen::MatrixXd& M : {affine_combination(B, x), synthesize_linear(B, x)}) {
      const ShapeAnalysis a = analyze_linear(B, M);
      CHECK((a.x - Eigen::VectorXd(x)).cwiseAbs().maxCoeff() < 1e-9);
      CHECK(a.residual_rms < 1e-9);
      CHECK(a.residual_max < 1e-9);
      CHECK(a.rank == 3);
      CHECK(a.quality() > 0.1);
    }
  }
}

TEST_CASE("shape space: analysis off the space is the sum-to-one least squares (Lagrange multiplier)", "[anim][shape_space]") {
  const std::vector<TriMesh> meshes = wobbly_spheres(4, 0.3, 9);
  const std::vector<Eigen::MatrixXd> B = vertices(meshes);
  const Eigen::MatrixXd M = wobbly_spheres(1, 0.5, 99)[0].V;  // not in the space
  const ShapeAnalysis a = ShapeSpace(meshes, {}, ShapeMorph::Linear).analyze(M);
  // min |A x - m|^2 subject to 1^T x = 1: [2 A^T A, 1; 1^T, 0] [x; lambda] = [2 A^T m; 1].
  const int n = 4, m = static_cast<int>(M.size());
  Eigen::MatrixXd A(m, n);
  for (int i = 0; i < n; ++i) A.col(i) = Eigen::Map<const Eigen::VectorXd>(B[i].data(), m);
  const Eigen::VectorXd mv = Eigen::Map<const Eigen::VectorXd>(M.data(), m);
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n + 1, n + 1);
  kkt.topLeftCorner(n, n) = 2 * A.transpose() * A;
  kkt.topRightCorner(n, 1).setOnes();
  kkt.bottomLeftCorner(1, n).setOnes();
  Eigen::VectorXd rhs(n + 1);
  rhs << 2 * A.transpose() * mv, 1.0;
  const Eigen::VectorXd want = kkt.fullPivLu().solve(rhs).head(n);
  CHECK((a.x - want).cwiseAbs().maxCoeff() < 1e-8);
  CHECK(a.x.sum() == Approx(1.0).epsilon(1e-14));
  double sq = 0, worst = 0;
  const Eigen::VectorXd r = A * want - mv;
  for (int v = 0; v < M.rows(); ++v) {
    const double d = std::sqrt(r(v) * r(v) + r(v + M.rows()) * r(v + M.rows()) + r(v + 2 * M.rows()) * r(v + 2 * M.rows()));
    sq += d * d, worst = std::max(worst, d);
  }
  CHECK(a.residual_rms == Approx(std::sqrt(sq / M.rows())).epsilon(1e-8));
  CHECK(a.residual_max == Approx(worst).epsilon(1e-6));
  CHECK(a.residual_rms > 0.05);

  // A dependent basis (B_3 halfway between B_1 and B_2): rank 2, quality 0, still a least-squares fit.
  std::vector<Eigen::MatrixXd> dep = B;
  dep[3] = 0.5 * (B[1] + B[2]);
  const ShapeAnalysis d = analyze_linear(dep, affine_combination(dep, Eigen::Vector4d(0.2, 0.3, 0.1, 0.4)));
  CHECK(d.rank == 2);
  CHECK(d.quality() == 0.0);
  CHECK(d.residual_max < 1e-9);
  CHECK(d.x.sum() == Approx(1.0).epsilon(1e-14));
}

TEST_CASE("shape space: ARAP chain hits the bases exactly, keeps rigid bases rigid, caches its setups", "[anim][shape_space][arap]") {
  const TriMesh b0 = bar();
  TriMesh b1 = b0, b2 = b0;
  b1.V = rigidly_moved(b0.V, 1.9, {0.2, 1.0, 0.3}, {0.5, 0.1, -0.2});
  b2.V = rigidly_moved(b0.V, -1.2, {1.0, 0.1, 0.6}, {-0.3, 0.4, 0.2});
  ShapeSpace space({b0, b1, b2}, {"b0", "b1", "b2"}, ShapeMorph::Arap);
  for (int i = 0; i < 3; ++i) CHECK(space.synthesize(unit(3, i)) == space.bases()[i]);

  // Every base a rigid motion of one shape: each morph in the chain turns rigidly (4.4), so the
  // synthesized shape keeps the edge lengths; the linear blend shrinks them.
  const Eigen::Vector3d x(0.3, 0.3, 0.4);
  const Eigen::MatrixXd U = space.synthesize(x);
  CHECK(max_edge_length_change(b0, U) < 1e-6);
  CHECK(max_edge_length_change(b0, synthesize_linear(space.bases(), x)) > 1e-2);
  CHECK(space.synthesize(x) == U);  // the cached setups give the same shape

  // Two nonzero weights: one morph, the pairwise ARAP interpolation built directly.
  const Eigen::Vector3d y(0.0, 0.35, 0.65);
  const Eigen::MatrixXd direct = ArapInterpolation(b1, b2.V).at(0.65);
  CHECK((space.synthesize(y) - direct).cwiseAbs().maxCoeff() < 1e-12);
  // Three: m(B_0, m(B_1, B_2, 0.4 / 0.7), 0.7).
  const Eigen::MatrixXd inner = ArapInterpolation(b1, b2.V).at(0.4 / 0.7);
  const Eigen::MatrixXd outer = ArapInterpolation(b0, inner).at(0.7);
  CHECK((space.synthesize(Eigen::Vector3d(0.3, 0.3, 0.4)) - outer).cwiseAbs().maxCoeff() < 1e-12);
}

namespace {

double orient2(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

// Brute force: the Delaunay triangles are the triples whose circumcircle holds no other point; the
// cursor's weights are its barycentric coordinates in the one containing it, or, outside the hull, the
// nearest point's on a hull edge (an edge with every other point on one side).
Eigen::VectorXd brute_force_weights(const PadPoints& P, const Eigen::Vector2d& q) {
  const int n = static_cast<int>(P.rows());
  auto p = [&](int i) { return Eigen::Vector2d(P.row(i).transpose()); };
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k) {
        const double area = orient2(p(i), p(j), p(k));
        if (std::abs(area) < 1e-12) continue;
        const double a = orient2(q, p(j), p(k)) / area, b = orient2(p(i), q, p(k)) / area, c = orient2(p(i), p(j), q) / area;
        if (a < -1e-12 || b < -1e-12 || c < -1e-12) continue;
        // Empty circumcircle: the circumcentre from the perpendicular bisectors.
        Eigen::Matrix2d Mx;
        Mx << (p(j) - p(i)).transpose(), (p(k) - p(i)).transpose();
        const Eigen::Vector2d rhs(0.5 * ((p(j)).squaredNorm() - p(i).squaredNorm()), 0.5 * (p(k).squaredNorm() - p(i).squaredNorm()));
        const Eigen::Vector2d cc = Mx.inverse() * (rhs - Mx * Eigen::Vector2d::Zero());
        const double r2 = (cc - p(i)).squaredNorm();
        bool empty = true;
        for (int o = 0; o < n; ++o)
          if (o != i && o != j && o != k && (p(o) - cc).squaredNorm() < r2 * (1 - 1e-12)) empty = false;
        if (!empty) continue;
        Eigen::VectorXd w = Eigen::VectorXd::Zero(n);
        w(i) = a, w(j) = b, w(k) = c;
        return w;
      }
  Eigen::VectorXd best_w;
  double best = 1e300;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if (i == j) continue;
      bool hull = true;
      for (int o = 0; o < n; ++o)
        if (orient2(p(i), p(j), p(o)) < 0) hull = false;
      if (!hull) continue;
      const double s = std::clamp((q - p(i)).dot(p(j) - p(i)) / (p(j) - p(i)).squaredNorm(), 0.0, 1.0);
      const double d = (p(i) + s * (p(j) - p(i)) - q).norm();
      if (d < best - 1e-12) {
        best = d;
        best_w = Eigen::VectorXd::Zero(n);
        best_w(i) = 1 - s, best_w(j) = s;
      }
    }
  return best_w;
}

}  // namespace

TEST_CASE("shape-space pad: Delaunay barycentrics inside, nearest hull point outside, e_i at the points", "[anim][shape_space]") {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  PadPoints P(7, 2);
  for (int i = 0; i < 7; ++i) P.row(i) << u(rng), u(rng);
  CHECK(pad_triangles(P).size() >= 5);
  for (int i = 0; i < 7; ++i) CHECK(pad_weights(P, P.row(i).transpose()) == unit(7, i));
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector2d q(1.4 * u(rng), 1.4 * u(rng));
    const Eigen::VectorXd w = pad_weights(P, q), want = brute_force_weights(P, q);
    REQUIRE(want.size() == 7);
    CHECK((w - want).cwiseAbs().maxCoeff() < 1e-9);
    CHECK(w.minCoeff() >= 0.0);
    CHECK(w.sum() == Approx(1.0).epsilon(1e-14));
    CHECK((w.array() > 0).count() <= 3);
  }
  // A base's own point gives it alone, so the pad's synthesis there is the base bit for bit.
  const std::vector<Eigen::MatrixXd> B = vertices(wobbly_spheres(7, 0.2, 4));
  CHECK(synthesize_linear(B, pad_weights(P, P.row(5).transpose())) == B[5]);

  // Two points and collinear points: the nearest point of the segments; clamped past the ends.
  PadPoints two(2, 2);
  two << 0, 0, 1, 0;
  CHECK((pad_weights(two, {0.25, 3.0}) - Eigen::Vector2d(0.75, 0.25)).norm() < 1e-15);
  CHECK(pad_weights(two, {-2.0, 1.0}) == Eigen::Vector2d(1, 0));
  PadPoints line(3, 2);
  line << 0, 0, 2, 0, 1, 0;
  CHECK(pad_triangles(line).empty());
  CHECK((pad_weights(line, {1.5, -1.0}) - Eigen::Vector3d(0, 0.5, 0.5)).norm() < 1e-15);
  CHECK((pad_position(line, Eigen::Vector3d(0, 0.5, 0.5)) - Eigen::Vector2d(1.5, 0)).norm() < 1e-15);
}

TEST_CASE("shape space: errors name the base and the problem", "[anim][shape_space]") {
  std::vector<TriMesh> m = wobbly_spheres(3, 0.1, 1);
  CHECK_THROWS_WITH(ShapeSpace({m[0]}, {"only.obj"}, ShapeMorph::Linear), Catch::Contains("at least 2 bases"));
  TriMesh other = test::icosphere(Eigen::Vector3d::Zero(), 1.0, 2);
  CHECK_THROWS_WITH(ShapeSpace({m[0], m[1], other}, {"a.obj", "b.obj", "c.obj"}, ShapeMorph::Linear),
                    Catch::Contains("c.obj") && Catch::Contains("differ from a.obj"));
  TriMesh flipped = m[1];
  flipped.F.col(1).swap(flipped.F.col(2));
  CHECK_THROWS_WITH(check_shape_bases({m[0], flipped}, {"a.obj", "b.obj"}), Catch::Contains("b.obj"));
  TriMesh nan = m[2];
  nan.V(3, 1) = std::nan("");
  CHECK_THROWS_WITH(check_shape_bases({m[0], nan}, {"a.obj", "n.obj"}), Catch::Contains("n.obj") && Catch::Contains("not finite"));

  ShapeSpace space(m, {}, ShapeMorph::Linear);
  CHECK_THROWS_WITH(space.synthesize(Eigen::Vector2d(0.5, 0.5)), Catch::Contains("needs 3 coordinates, got 2"));
  CHECK_THROWS_WITH(space.synthesize(Eigen::Vector3d(0.5, std::nan(""), 0.5)), Catch::Contains("coordinate 1 is not finite"));
  CHECK_THROWS_WITH(space.synthesize(Eigen::Vector3d(0.5, 0.5, 0.5)), Catch::Contains("sum to 1.5"));
  CHECK_THROWS_WITH(space.synthesize(Eigen::Vector3d(1.0, 1.0, -1.0)), Catch::Contains("chain is undefined"));
  CHECK_THROWS_WITH(space.analyze(m[0].V.topRows(5)), Catch::Contains("5 vertices"));
  PadPoints P(2, 2);
  P << 0, 0, 1, std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH(pad_weights(P, {0, 0}), Catch::Contains("pad point 1"));
  CHECK_THROWS_WITH(parse_shape_morph("cubic"), Catch::Contains("linear or arap"));
}
