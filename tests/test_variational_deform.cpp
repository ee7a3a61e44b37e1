// Variational region deformation (core/sculpt/variational_deform.h; Jacobson 2013, ch. 3) against
// references written here: the closed-form radially symmetric biharmonic solution on an annulus
// (3.3.2's region conditions in the continuous limit: u and du/dr of the fixed and handle regions),
// convergence under refinement (3.5, Fig. 3.9), the C1 / C2 behaviour at a region boundary (3.3.2,
// Fig. 3.2), and the regions held exactly.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include <Eigen/Dense>

#include "core/sculpt/variational_deform.h"
#include "core/util/error.h"
#include "tests/sculpt_test_meshes.h"

using namespace dfm;
using namespace dfm::test;

namespace {

constexpr double kA = 0.25, kB = 1.0, kOuter = 1.25, kLift = 0.05;

// u = c1 + c2 r^2 + c3 ln r + c4 r^2 ln r, the radial solutions of Delta^2 u = 0, with u(a) = lift,
// u'(a) = 0 (the handle region, translated) and u(b) = u'(b) = 0 (the flat fixed region).
struct RadialBiharmonic {
  Eigen::Vector4d c;
  RadialBiharmonic(double a, double b, double lift) {
    auto row_u = [](double r) { return Eigen::RowVector4d(1, r * r, std::log(r), r * r * std::log(r)); };
    auto row_du = [](double r) { return Eigen::RowVector4d(0, 2 * r, 1 / r, 2 * r * std::log(r) + r); };
    Eigen::Matrix4d A;
    A << row_u(a), row_du(a), row_u(b), row_du(b);
    c = A.fullPivLu().solve(Eigen::Vector4d(lift, 0, 0, 0));
  }
  double u(double r) const { return c(0) + c(1) * r * r + c(2) * std::log(r) + c(3) * r * r * std::log(r); }
  // Delta u = u'' + u'/r = 4 c2 + c4 (4 ln r + 4).
  double laplacian(double r) const { return 4 * c(1) + c(3) * (4 * std::log(r) + 4); }
};

struct DiskRun {
  TriMesh mesh;
  Eigen::MatrixXd X;
  double h;
};

DiskRun lift_disk(double h, int order) {
  DiskRun d;
  d.h = h;
  d.mesh = ring_disk(h, static_cast<int>(std::lround(kOuter / h)));
  const std::vector<int> handle = ring_band(d.mesh, 0, kA, h), fixed = ring_band(d.mesh, kB, kOuter, h);
  VariationalDeform deform(d.mesh.V, d.mesh.F, fixed, handle, {order});
  d.X = deform.solve(handle_translation(Eigen::RowVector3d(0, 0, kLift)));
  return d;
}

// The mean height of the ring at radius r (the meshes are not exactly rotation symmetric).
double ring_height(const DiskRun& d, double r) {
  double sum = 0;
  int n = 0;
  for (int i = 0; i < d.mesh.V.rows(); ++i)
    if (std::abs(d.mesh.V.row(i).head<2>().norm() - r) < 0.25 * d.h) sum += d.X(i, 2), ++n;
  REQUIRE(n > 0);
  return sum / n;
}

}  // namespace

TEST_CASE("variational deform: fixed vertices bit for bit, handle vertices exactly their affine map", "[sculpt]") {
  TriMesh m = ring_disk(1.0 / 8, 10);
  for (int i = 0; i < m.V.rows(); ++i) m.V(i, 2) = 0.1 * std::sin(3 * m.V(i, 0)) * std::cos(2 * m.V(i, 1));  // not flat
  const double h = 1.0 / 8;
  const std::vector<int> handle = ring_band(m, 0, 0.25, h), fixed = ring_band(m, 1.0, 1.25, h);
  for (int order : {2, 3}) {
    VariationalDeform deform(m.V, m.F, fixed, handle, {order});
    HandleTransform T;
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    T.topRows(3) = 1.2 * R.transpose();
    T.row(3) = Eigen::RowVector3d(0.1, -0.2, 0.3);
    const Eigen::MatrixXd X = deform.solve(T);
    for (int i : fixed)
      for (int c = 0; c < 3; ++c) REQUIRE(X(i, c) == m.V(i, c));  // bit for bit
    double worst = 0;
    for (int i : handle) {
      const Eigen::RowVector3d p = m.V.row(i);
      worst = std::max(worst, (X.row(i) - (p * 1.2 * R.transpose() + Eigen::RowVector3d(0.1, -0.2, 0.3))).norm());
    }
    CHECK(worst < 1e-15);
    // The free region moved and stays finite.
    CHECK(X.allFinite());
    CHECK((X - m.V).norm() > 0.1);
  }
}

TEST_CASE("variational deform: a lifted disk centre is the closed-form biharmonic annulus and converges", "[sculpt]") {
  const RadialBiharmonic exact(kA, kB, kLift);
  // Largest error at the free vertices against a closed form.
  auto error = [](const DiskRun& d, const RadialBiharmonic& u) {
    double e = 0;
    for (int i = 0; i < d.mesh.V.rows(); ++i) {
      const double r = d.mesh.V.row(i).head<2>().norm();
      if (r > kA + 0.25 * d.h && r < kB - 0.25 * d.h) e = std::max(e, std::abs(d.X(i, 2) - u.u(r)));
    }
    return e;
  };
  const double finest_h = 1.0 / 64;
  const DiskRun finest = lift_disk(finest_h, 2);
  std::vector<double> against_finest, shifted;
  for (double h : {1.0 / 8, 1.0 / 16, 1.0 / 32, 1.0 / 64}) {
    const DiskRun d = h == finest_h ? finest : lift_disk(h, 2);
    // The error against the finest at the coarse rings (radii multiples of 1/8).
    double e = 0;
    for (double r = kA + 0.125; r < kB - 1e-9; r += 0.125) e = std::max(e, std::abs(ring_height(d, r) - ring_height(finest, r)));
    // Region conditions act as if the regions' edges lay half a ring inside them (at a - h/2 and b + h/2,
    // between the last known ring and the first free one): against that annulus the error is second order.
    const double e_shift = error(d, RadialBiharmonic(kA - 0.5 * h, kB + 0.5 * h, kLift));
    std::printf("biharmonic disk, h = 1/%d: error (of the lift) against the closed form %.4f, against h = 1/64 at "
                "the coarse rings %.4f, against the closed form with the edges at a - h/2, b + h/2 %.5f\n",
                static_cast<int>(std::lround(1 / h)), error(d, exact) / kLift, e / kLift, e_shift / kLift);
    if (h != finest_h) against_finest.push_back(e);
    shifted.push_back(e_shift);
  }
  CHECK(error(finest, exact) < 0.01 * kLift);
  // Halving h at least halves the error (3.4.1 proves convergence; the rate seen is h^1 against the
  // nominal edges, h^2 against the shifted ones).
  CHECK(against_finest[1] <= 0.5 * against_finest[0]);
  CHECK(against_finest[2] <= 0.5 * against_finest[1]);
  for (size_t k = 1; k < shifted.size(); ++k) CHECK(shifted[k] <= 0.4 * shifted[k - 1]);
}

TEST_CASE("variational deform: triharmonic is C2 across the fixed region's boundary, biharmonic only C1", "[sculpt]") {
  // The jump of the mean curvature normal across r = b. Its height component is about Delta u for this
  // small lift; the fixed side is flat (0), the free side's limit at b is extrapolated from the rings
  // b - h and b - 2h, with Delta u from finite differences of the ring heights (a reference that does
  // not use the solver's operators). C1 (order 2): the jump tends to the closed form's Delta u(b^-) != 0;
  // C2 (order 3): it tends to 0, like h.
  auto jump = [&](double h, int order) {
    const DiskRun d = lift_disk(h, order);
    auto lap = [&](double r) {
      const double um = ring_height(d, r - h), u0 = ring_height(d, r), up = ring_height(d, r + h);
      return (up - 2 * u0 + um) / (h * h) + (up - um) / (2 * h) / r;
    };
    return std::abs(2 * lap(kB - h) - lap(kB - 2 * h));
  };
  const RadialBiharmonic exact(kA, kB, kLift);
  double bi[2], tri[2];
  for (int k = 0; k < 2; ++k) {
    const double h = k == 0 ? 1.0 / 32 : 1.0 / 64;
    bi[k] = jump(h, 2), tri[k] = jump(h, 3);
    std::printf("jump of the mean curvature normal (Delta u) across r = b, h = 1/%d: biharmonic %.4g (closed form "
                "%.4g), triharmonic %.4g\n",
                k == 0 ? 32 : 64, bi[k], std::abs(exact.laplacian(kB)), tri[k]);
  }
  CHECK(std::abs(bi[1] - std::abs(exact.laplacian(kB))) < 0.1 * std::abs(exact.laplacian(kB)));
  CHECK(tri[1] < 0.6 * tri[0]);  // vanishing under refinement
  CHECK(tri[1] < 0.3 * bi[1]);
}

TEST_CASE("variational deform: hostile regions are refused with a message, nothing computed", "[sculpt][hostile]") {
  const TriMesh m = ring_disk(1.0 / 4, 4);
  const int nv = static_cast<int>(m.V.rows());
  const std::vector<int> handle{0}, fixed = ring_band(m, 1.0, 1.0, 0.25);
  auto message = [&](const std::vector<int>& f, const std::vector<int>& hd, int order = 2) {
    try {
      VariationalDeform(m.V, m.F, f, hd, {order});
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK_THAT(message(fixed, {nv}), Catch::Contains("handle vertex " + std::to_string(nv) + " out of range"));
  CHECK_THAT(message({-1}, handle), Catch::Contains("fixed vertex -1 out of range"));
  CHECK_THAT(message({0}, handle), Catch::Contains("both fixed and in the handle"));
  CHECK_THAT(message(fixed, {}), Catch::Contains("handle region is empty"));
  std::vector<int> all;
  for (int i = 1; i < nv; ++i) all.push_back(i);
  CHECK_THAT(message(all, handle), Catch::Contains("free region is empty"));
  CHECK_THAT(message(fixed, handle, 4), Catch::Contains("order must be 2"));
  // A second disk nothing holds: its vertices are free and unreachable.
  TriMesh two = m;
  two.V.conservativeResize(2 * nv, 3);
  two.V.bottomRows(nv) = m.V.rowwise() + Eigen::RowVector3d(5, 0, 0);
  two.F.conservativeResize(2 * m.F.rows(), 3);
  two.F.bottomRows(m.F.rows()) = m.F.array() + nv;
  try {
    VariationalDeform(two.V, two.F, fixed, handle);
    FAIL("an unreachable free region was accepted");
  } catch (const Error& e) {
    CHECK_THAT(std::string(e.what()), Catch::Contains(std::to_string(nv) + " free vertices have no path"));
  }
}
