// Generalized winding numbers: exact values on analytic configurations, and the hierarchical
// (far-field) evaluation against the direct sum on real, open and closed, meshes.
#include <catch2/catch.hpp>

#include <random>

#include "core/bind/winding_bvh.h"
#include "core/bind/winding_number.h"
#include "core/mesh/io.h"
#include "tests/test_support.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;
using dfm::test::box_mesh;
using dfm::test::icosphere;

TEST_CASE("solid angle of an octant triangle is 4 pi / 8, sign by orientation", "[winding]") {
  const Eigen::Vector3d x(1, 0, 0), y(0, 1, 0), z(0, 0, 1), o(0, 0, 0);
  REQUIRE(solid_angle(x, y, z, o) == Approx(M_PI / 2).epsilon(1e-14));
  REQUIRE(solid_angle(x, z, y, o) == Approx(-M_PI / 2).epsilon(1e-14));
  // Seen from far on the same side as the origin it subtends ~ +area / d^2 (area = sqrt(3)/2).
  const Eigen::Vector3d far = -1e3 * Eigen::Vector3d(1, 1, 1).normalized();
  const double d = (far - Eigen::Vector3d(1, 1, 1) / 3.0).norm();
  REQUIRE(solid_angle(x, y, z, far) == Approx(std::sqrt(3.0) / 2 / (d * d)).epsilon(1e-5));
}

TEST_CASE("closed cube: 1 inside, 0 outside, -1 when flipped", "[winding]") {
  TriMesh cube = box_mesh(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1));
  Eigen::MatrixXi flipped = cube.F;
  flipped.col(1).swap(flipped.col(2));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-3, 3);
  for (int i = 0; i < 500; ++i) {
    Eigen::Vector3d p(u(rng), u(rng), u(rng));
    const double m = p.cwiseAbs().maxCoeff();
    if (std::abs(m - 1) < 1e-3) continue;
    const double expect = m < 1 ? 1.0 : 0.0;
    REQUIRE(std::abs(winding_number(cube.V, cube.F, p) - expect) < 1e-6);
    REQUIRE(std::abs(winding_number(cube.V, flipped, p) + expect) < 1e-6);
  }
}

TEST_CASE("open cube: the winding number is 1/2 at the hole's centre and varies smoothly across it", "[winding]") {
  TriMesh cube = box_mesh(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1));
  // Remove the top face (z = 1: corners 4..7, faces 2 and 3).
  Eigen::MatrixXi F(10, 3);
  F << cube.F.topRows(2), cube.F.bottomRows(8);
  REQUIRE(winding_number(cube.V, F, Eigen::Vector3d(0, 0, 1)) == Approx(0.5).margin(1e-12));
  const double below = winding_number(cube.V, F, Eigen::Vector3d(0, 0, 0.99));
  const double above = winding_number(cube.V, F, Eigen::Vector3d(0, 0, 1.01));
  REQUIRE(below > 0.5);
  REQUIRE(below < 0.6);
  REQUIRE(above < 0.5);
  REQUIRE(above > 0.4);
  REQUIRE(winding_number(cube.V, F, Eigen::Vector3d(0, 0, 0)) > 0.7);
}

TEST_CASE("icosphere: tree equals direct and classifies in/out", "[winding]") {
  TriMesh s = icosphere(Eigen::Vector3d(0.3, -0.2, 0.1), 1.0, 4);  // 5120 triangles
  WindingTree tree = build_winding_tree(s.V, s.F);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2, 2);
  Eigen::MatrixXd P(2000, 3);
  for (int i = 0; i < P.rows(); ++i) P.row(i) << u(rng), u(rng), u(rng);
  const Eigen::VectorXd wd = winding_numbers_direct(s.V, s.F, P);
  const Eigen::VectorXd wt = winding_numbers(tree, P);
  REQUIRE((wd - wt).cwiseAbs().maxCoeff() < 1e-4);
  for (int i = 0; i < P.rows(); ++i) {
    const double r = (P.row(i) - Eigen::RowVector3d(0.3, -0.2, 0.1)).norm();
    if (r < 0.95) REQUIRE(std::abs(wd(i) - 1) < 1e-6);
    if (r > 1.05) REQUIRE(std::abs(wd(i)) < 1e-6);
  }
  // A huge beta never uses the far field: exact agreement.
  for (int i = 0; i < 50; ++i)
    REQUIRE(winding_number(tree, P.row(i).transpose(), WindingAccuracy{1e9, 1e-300}) == Approx(wd(i)).margin(1e-12));
}

static void compare_on(const std::string& path, int n) {
  TriMesh m = read_surface(path);
  WindingTree tree = build_winding_tree(m.V, m.F);
  const Eigen::RowVector3d lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.1, 1.1);
  Eigen::MatrixXd P(n, 3);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) P(i, k) = lo(k) + u(rng) * (hi(k) - lo(k));
  // Also points just off the surface (near field), where errors would show first.
  for (int i = 0; i < n / 4; ++i) {
    const int f = static_cast<int>(rng() % m.F.rows());
    P.row(i) = (m.V.row(m.F(f, 0)) + m.V.row(m.F(f, 1)) + m.V.row(m.F(f, 2))) / 3.0 +
               1e-3 * (hi - lo).norm() * Eigen::RowVector3d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
  }
  const Eigen::VectorXd wd = winding_numbers_direct(m.V, m.F, P);
  const Eigen::VectorXd wt = winding_numbers(tree, P);
  INFO(path << ": max |hierarchical - direct| = " << (wd - wt).cwiseAbs().maxCoeff());
  REQUIRE((wd - wt).cwiseAbs().maxCoeff() < 1e-4);
  // The far field is really used: a looser tree (beta 1, no error bound) differs measurably.
  REQUIRE((wd - winding_numbers(tree, P, WindingAccuracy{1.0, 1e300})).cwiseAbs().maxCoeff() > 1e-6);
}

// [heavy]: release only; under the sanitizers "icosphere: tree equals direct" runs the same tree and
// direct sums, and the beetle case below the tree on an open surface.
TEST_CASE("hierarchical == direct within 1e-4 on bunny (closed) and beetle (open)", "[winding][data][heavy]") {
  DFM_DATA_OR_SKIP(bunny, "bunny.off");
  compare_on(bunny, 2000);
  DFM_DATA_OR_SKIP(beetle, "beetle.off");
  compare_on(beetle, 2000);
}

TEST_CASE("beetle (open): inside points well above 1/2, far points 0", "[winding][data]") {
  DFM_DATA_OR_SKIP(path, "beetle.off");
  TriMesh m = read_surface(path);
  WindingTree tree = build_winding_tree(m.V, m.F);
  const Eigen::RowVector3d lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
  REQUIRE(std::abs(winding_number(tree, (hi + 1000 * (hi - lo)).transpose())) < 1e-6);
  // The centroid of the vertices is inside the beetle's body.
  const Eigen::Vector3d c = m.V.colwise().mean().transpose();
  REQUIRE(winding_number(tree, c) > 0.5);
}
