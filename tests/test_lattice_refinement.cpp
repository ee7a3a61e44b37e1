// Refining a transition's middle lattice where the blend bulges off its chords (issue 30;
// core/anim/lattice_refinement.h): the finer lattice against a brute-force enumeration of the
// body-centred cubic lattice, and the bulge rule on fields whose zero sets are known in closed form.
#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <vector>

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "core/anim/lattice_refinement.h"

using namespace dfm;

namespace {

// Coordinates of p in quarters of a from lo, which must be integers.
std::array<long long, 3> quarters(const Eigen::RowVector3d& p, const Eigen::RowVector3d& lo, double a) {
  std::array<long long, 3> q;
  for (int d = 0; d < 3; ++d) {
    const double x = (p[d] - lo[d]) / (0.25 * a);
    q[d] = std::llround(x);
    REQUIRE(std::abs(x - static_cast<double>(q[d])) < 1e-9);
  }
  return q;
}

}  // namespace

TEST_CASE("finer lattice: the half-edge lattice's points near the centres, less the coarse lattice's", "[transition]") {
  const Eigen::RowVector3d lo(-0.3, 0.1, 2.0);
  const double a = 0.2, reach = 0.13;
  Eigen::MatrixXd centres(2, 3);
  centres << 0.0, 0.5, 2.2, 0.07, 0.52, 2.21;  // overlapping balls: shared points come once
  const Eigen::MatrixXd P = finer_lattice_points(lo, a, centres, reach);
  REQUIRE(P.rows() > 0);
  std::set<std::array<long long, 3>> got;
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const std::array<long long, 3> q = quarters(P.row(i), lo, a);
    CHECK(got.insert(q).second);
  }
  // Brute force over a box of quarter steps: the cube edge a / 2 lattice is all-even or all-odd
  // quarters; the cube edge a lattice is all multiples of 4 or all 2 modulo 4.
  std::set<std::array<long long, 3>> want;
  for (long long x = -20; x <= 20; ++x)
    for (long long y = -10; y <= 30; ++y)
      for (long long z = -10; z <= 60; ++z) {
        const auto mod = [](long long v, long long m) { return ((v % m) + m) % m; };
        const bool even = mod(x, 2) == 0 && mod(y, 2) == 0 && mod(z, 2) == 0;
        const bool odd = mod(x, 2) == 1 && mod(y, 2) == 1 && mod(z, 2) == 1;
        if (!even && !odd) continue;
        const bool coarse = (mod(x, 4) == 0 && mod(y, 4) == 0 && mod(z, 4) == 0) ||
                            (mod(x, 4) == 2 && mod(y, 4) == 2 && mod(z, 4) == 2);
        if (coarse) continue;
        const Eigen::RowVector3d p = lo + 0.25 * a * Eigen::RowVector3d(double(x), double(y), double(z));
        if ((p - centres.row(0)).norm() <= reach || (p - centres.row(1)).norm() <= reach) want.insert({x, y, z});
      }
  CHECK(got == want);
  // With the coarse points, every point's nearest neighbour lies at the half lattice's a sqrt(3) / 4.
  for (const auto& q : got) {
    double nearest = 1e300;
    for (long long dx = -2; dx <= 2; ++dx)
      for (long long dy = -2; dy <= 2; ++dy)
        for (long long dz = -2; dz <= 2; ++dz) {
          const long long x = q[0] + dx, y = q[1] + dy, z = q[2] + dz;
          const bool lattice = ((x & 1) == (y & 1)) && ((y & 1) == (z & 1));
          if ((dx || dy || dz) && lattice) nearest = std::min(nearest, 0.25 * a * std::sqrt(double(dx * dx + dy * dy + dz * dz)));
        }
    CHECK(nearest == Approx(a * std::sqrt(3.0) / 4));
  }
}

TEST_CASE("bulging edges: a slab thinner than an edge, hidden between its ends, is found; planes are not",
          "[transition]") {
  // d_s = |x| - w: a slab of half-width w = 0.1 a about x = 0 (gradient sign(x) e_x, the pseudo-normal
  // direction). The edge across it has both ends at 0.4 a outside: linear interpolation never sees
  // the slab. The edge along it, at x = 0.45 a, sees d_s constant.
  const double a = 0.5, w = 0.1 * a;
  Eigen::MatrixXd X(4, 3);
  X << -0.5 * a, 0, 0, 0.5 * a, 0, 0, 0.45 * a, 0, 0, 0.45 * a, a, 0;
  Eigen::VectorXd d_s(4), d_t(4);
  Eigen::MatrixXd g_s(4, 3), g_t(4, 3);
  for (int i = 0; i < 4; ++i) {
    d_s[i] = std::abs(X(i, 0)) - w;
    g_s.row(i) << (X(i, 0) < 0 ? -1 : 1), 0, 0;
  }
  d_t.setConstant(1.0);  // far away: the blend at u is (1 - u) d_s + u
  g_t.setZero();
  const std::vector<std::array<int, 2>> edges = {{0, 1}, {2, 3}};
  SECTION("at u = 0 the slab's zero set lies within the across edge's bulge") {
    // The Hermite cubic's midpoint value is 0.4 a - a / 4 = 0.15 a, a quarter a off the chord.
    const Eigen::MatrixXd mid = bulging_edge_midpoints(X, edges, d_s, d_t, g_s, g_t, {0.0}, a, 0.1);
    REQUIRE(mid.rows() == 1);
    CHECK(mid.row(0).norm() < 1e-15);  // the across edge's midpoint, the origin
    CHECK(bulging_edge_midpoints(X, edges, d_s, d_t, g_s, g_t, {0.0}, a, 0.3).rows() == 0);  // 0.25 a < 0.3 a
  }
  SECTION("at u = 0.5 the blend is at least 0.5 - 0.05 a everywhere: no zero set near the bulge") {
    CHECK(bulging_edge_midpoints(X, edges, d_s, d_t, g_s, g_t, {0.5}, a, 0.1).rows() == 0);
  }
  SECTION("a linear field bulges nowhere") {
    Eigen::VectorXd lin(4);
    Eigen::MatrixXd g(4, 3);
    for (int i = 0; i < 4; ++i) lin[i] = 0.3 * X(i, 0) - 0.2 * X(i, 1), g.row(i) << 0.3, -0.2, 0;
    CHECK(bulging_edge_midpoints(X, edges, lin, lin, g, g, {0.0, 0.5, 1.0}, a, 1e-9).rows() == 0);
  }
  CHECK_THROWS_WITH(bulging_edge_midpoints(X, edges, d_s.head(3), d_t, g_s, g_t, {0.0}, a, 0.1),
                    Catch::Contains("disagree in size"));
  CHECK_THROWS_WITH(bulging_edge_midpoints(X, {{0, 4}}, d_s, d_t, g_s, g_t, {0.0}, a, 0.1), Catch::Contains("out of range"));
}
