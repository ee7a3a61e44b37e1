// As-rigid-as-possible interpolation (Alexa 2002, 4.4) on tets: keys hit exactly; a rigid turn stays
// rigid in between (edge lengths kept, where the linear blend shrinks them); a 270 degree twist turns
// the far end by 135 degrees halfway, not by -45 (the rotation branch chosen across neighbours).
#include <cmath>

#include <catch2/catch.hpp>
#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "core/anim/arap_interpolation.h"
#include "core/anim/surface_checks.h"
#include "core/util/error.h"

using namespace dfm;

namespace {

// A closed cylinder along x from 0 to L, radius r, capped by a centre vertex at each end.
TriMesh capped_cylinder(int rings, int around, double L, double r) {
  TriMesh m;
  m.V.resize(rings * around + 2, 3);
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < around; ++j) {
      const double a = 2 * M_PI * j / around;
      m.V.row(i * around + j) << L * i / (rings - 1), r * std::cos(a), r * std::sin(a);
    }
  const int c0 = rings * around, c1 = c0 + 1;
  m.V.row(c0) << 0, 0, 0;
  m.V.row(c1) << L, 0, 0;
  std::vector<Eigen::Vector3i> F;
  for (int i = 0; i + 1 < rings; ++i)
    for (int j = 0; j < around; ++j) {
      const int a = i * around + j, b = i * around + (j + 1) % around, c = a + around, d = b + around;
      F.push_back({a, b, c});
      F.push_back({b, d, c});
    }
  for (int j = 0; j < around; ++j) {
    F.push_back({c0, (j + 1) % around, j});
    F.push_back({c1, (rings - 1) * around + j, (rings - 1) * around + (j + 1) % around});
  }
  m.F.resize(F.size(), 3);
  for (size_t f = 0; f < F.size(); ++f) m.F.row(f) = F[f].transpose();
  return m;
}

Eigen::MatrixXd twisted(const Eigen::MatrixXd& V, double L, double total) {
  Eigen::MatrixXd out = V;
  for (int i = 0; i < V.rows(); ++i) {
    const double a = total * V(i, 0) / L;
    out(i, 1) = std::cos(a) * V(i, 1) - std::sin(a) * V(i, 2);
    out(i, 2) = std::sin(a) * V(i, 1) + std::cos(a) * V(i, 2);
  }
  return out;
}

// The bar bent by 90 degrees about z over x in [c - h, c + h]: that part follows a quarter circle of the
// same centre-line length (radius 4h / pi), the rest is carried rigidly. By Pappus the bend keeps the
// volume of a symmetric cross-section.
Eigen::MatrixXd bent(const Eigen::MatrixXd& V, double c, double h) {
  const double R = 4 * h / M_PI, x0 = c - h;
  Eigen::MatrixXd out = V;
  for (int i = 0; i < V.rows(); ++i) {
    const double x = V(i, 0), y = V(i, 1);
    if (x <= x0) continue;
    const double phi = std::min(x - x0, 2 * h) / R;  // the turn reached at x
    out(i, 0) = x0 + (R - y) * std::sin(phi);
    out(i, 1) = R - (R - y) * std::cos(phi);
    if (x > c + h) out(i, 1) += x - (c + h);  // past the bend: straight on along +y
  }
  return out;
}

double max_edge_length_ratio_error(const TriMesh& m, const Eigen::MatrixXd& U) {
  double err = 0;
  for (int f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = m.F(f, k), b = m.F(f, (k + 1) % 3);
      err = std::max(err, std::abs((U.row(a) - U.row(b)).norm() / (m.V.row(a) - m.V.row(b)).norm() - 1.0));
    }
  return err;
}

}  // namespace

TEST_CASE("ARAP interpolation hits both keys and keeps a rigid turn rigid", "[anim][arap]") {
  const TriMesh k0 = capped_cylinder(9, 12, 2.0, 0.3);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(2.2, Eigen::Vector3d(0.3, 1.0, 0.4).normalized()).toRotationMatrix();
  const Eigen::MatrixXd k1 = (k0.V * R.transpose()).rowwise() + Eigen::RowVector3d(1.0, -0.5, 0.2);
  const ArapInterpolation arap(k0, k1);
  CHECK(arap.stats().tets > 0);
  CHECK(arap.at(0.0) == k0.V);
  CHECK(arap.at(1.0) == k1);
  CHECK((arap.at(1e-9) - k0.V).cwiseAbs().maxCoeff() < 1e-6);  // the path is continuous at the keys
  CHECK((arap.at(1.0 - 1e-9) - k1).cwiseAbs().maxCoeff() < 1e-6);
  for (double t : {0.25, 0.5, 0.8}) {
    CHECK(max_edge_length_ratio_error(k0, arap.at(t)) < 1e-6);
    // Halfway the body has turned by half the angle: compare with the rotation by t * 2.2 directly.
    const Eigen::Matrix3d Rt = Eigen::AngleAxisd(2.2 * t, Eigen::Vector3d(0.3, 1.0, 0.4).normalized()).toRotationMatrix();
    const Eigen::MatrixXd U = arap.at(t);
    const Eigen::MatrixXd expect = k0.V * Rt.transpose();
    const Eigen::RowVector3d shift = (U - expect).colwise().mean();
    CHECK(((U - expect).rowwise() - shift).cwiseAbs().maxCoeff() < 1e-6);
  }
  CHECK(max_edge_length_ratio_error(k0, linear_interpolation(k0.V, k1, 0.5)) > 0.3);  // the linear blend shrinks
  CHECK_THROWS_WITH(ArapInterpolation(k0, k1.topRows(10)), Catch::Contains("must share one triangle list"));
}

TEST_CASE("ARAP interpolation takes a 270 degree twist the long way: 135 degrees halfway", "[anim][arap]") {
  const double L = 3.0;
  const TriMesh k0 = capped_cylinder(31, 12, L, 0.3);
  const Eigen::MatrixXd k1 = twisted(k0.V, L, 1.5 * M_PI);
  const ArapInterpolation arap(k0, k1);
  const Eigen::MatrixXd mid = arap.at(0.5);
  // The far ring (x = L): its turn about x relative to the near ring, unwrapped to (-pi, pi].
  const int around = 12, far = 30 * around;
  auto ring_angle = [&](const Eigen::MatrixXd& U, int first) {
    double s = 0, c = 0;
    for (int j = 0; j < around; ++j) {
      const double a0 = std::atan2(k0.V(first + j, 2), k0.V(first + j, 1)), a = std::atan2(U(first + j, 2), U(first + j, 1));
      s += std::sin(a - a0), c += std::cos(a - a0);
    }
    return std::atan2(s, c);
  };
  const double turn = ring_angle(mid, far) - ring_angle(mid, 0);
  const double turn_deg = std::remainder(turn, 2 * M_PI) * 180 / M_PI;
  WARN("270 degree twist, halfway: far ring turned " << turn_deg << " degrees relative to the near ring");
  CHECK(turn_deg == Approx(135).margin(10));
  // The cross-sections keep their radius (the linear blend of a 270 degree turn pulls them in to 0.71 r).
  // Cross-sections keep their radius along the bar; the end ring, where the sheared tets meet the
  // cap, pulls in a little (0.26 of 0.30) but stays far from the linear blend's 0.71 r.
  auto ring_radius = [&](const Eigen::MatrixXd& U, int ring) {
    double r = 0;
    for (int j = 0; j < around; ++j) r += U.row(ring * around + j).tail<2>().norm() / around;
    return r;
  };
  for (int ring = 0; ring <= 25; ring += 5) CHECK(ring_radius(mid, ring) == Approx(0.3).epsilon(0.01));
  CHECK(ring_radius(mid, 30) > 0.25);
  CHECK(ring_radius(linear_interpolation(k0.V, k1, 0.5), 30) < 0.22);
}

TEST_CASE("ARAP interpolation of a bar bent by 90 degrees keeps its volume within 1% at every in-between",
          "[anim][arap]") {
  const double L = 3.0;
  const TriMesh k0 = capped_cylinder(31, 12, L, 0.3);
  const Eigen::MatrixXd k1 = bent(k0.V, 1.5, 0.5);
  const double v0 = enclosed_volume(k0.V, k0.F), v1 = enclosed_volume(k1, k0.F);
  REQUIRE(v1 == Approx(v0).epsilon(0.005));  // the keys themselves agree (Pappus, up to the chords)
  const ArapInterpolation arap(k0, k1);
  double worst_arap = 0, worst_linear = 0;
  for (int j = 1; j < 10; ++j) {
    const double t = 0.1 * j;
    worst_arap = std::max(worst_arap, std::abs(enclosed_volume(arap.at(t), k0.F) / v0 - 1));
    worst_linear = std::max(worst_linear, std::abs(enclosed_volume(linear_interpolation(k0.V, k1, t), k0.F) / v0 - 1));
  }
  WARN("bar bent by 90 degrees: worst volume change over t = 0.1 .. 0.9: ARAP " << 100 * worst_arap << "%, linear "
       << 100 * worst_linear << "%");
  CHECK(worst_arap < 0.01);
  CHECK(worst_linear > worst_arap);
}

TEST_CASE("symmetric ARAP (Eq. 4.28): keys exact, a rigid turn rigid, one tet against its closed form, "
          "a bent bar's volume kept", "[anim][arap]") {
  const double L = 3.0;
  const TriMesh k0 = capped_cylinder(31, 12, L, 0.3);
  ArapInterpolationOptions sym;
  sym.symmetric = true;
  // A rigid turn stays rigid.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(2.0, Eigen::Vector3d(0.2, 0.3, 1.0).normalized()).toRotationMatrix();
  const Eigen::MatrixXd turned = k0.V * R.transpose();
  const ArapInterpolation rigid(k0, turned, sym);
  CHECK(rigid.at(0.0) == k0.V);
  CHECK(rigid.at(1.0) == turned);
  CHECK(max_edge_length_ratio_error(k0, rigid.at(0.4)) < 1e-6);

  // One tetrahedron and an affine copy of it (turned and stretched unevenly): with a single tet the
  // minimizer has a closed form. B, the intermediate's linear map, minimizes
  //   (1 - t) vol0 |A->(t) - B|^2 + t vol1 |A<-(1 - t) - B F^-1|^2,
  // A->(t) = R(t)((1 - t) I + t S) from F = R S, A<-(u) the same for F^-1 (Eqs. 4.28-4.30).
  TriMesh tet;
  tet.V.resize(4, 3);
  tet.V << 1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1;
  tet.F.resize(4, 3);
  tet.F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  if (enclosed_volume(tet.V, tet.F) < 0) tet.F.col(1).swap(tet.F.col(2));
  const Eigen::Matrix3d F = Eigen::AngleAxisd(2.3, Eigen::Vector3d(1, 2, 0.5).normalized()).toRotationMatrix() *
                            Eigen::Vector3d(2.5, 0.7, 1.2).asDiagonal();
  const Eigen::MatrixXd moved = (tet.V * F.transpose()).rowwise() + Eigen::RowVector3d(0.3, 0.1, -0.2);
  const ArapInterpolation one(tet, moved, sym);
  REQUIRE(one.stats().tets == 1);
  auto interpolated = [](const Eigen::Matrix3d& M, double u) {
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::Matrix3d Rm = svd.matrixU() * svd.matrixV().transpose();  // det > 0 here
    const Eigen::Matrix3d Sm = svd.matrixV() * svd.singularValues().asDiagonal() * svd.matrixV().transpose();
    const Eigen::AngleAxisd aa(Rm);
    return Eigen::Matrix3d(Eigen::AngleAxisd(u * aa.angle(), aa.axis()).toRotationMatrix() *
                           ((1 - u) * Eigen::Matrix3d::Identity() + u * Sm));
  };
  const double vol0 = enclosed_volume(tet.V, tet.F), vol1 = enclosed_volume(moved, tet.F);
  for (double t : {0.3, 0.5, 0.8}) {
    const Eigen::Matrix3d Af = interpolated(F, t), Ab = interpolated(F.inverse(), 1 - t), Fi = F.inverse();
    // Normal equations for the 9 entries of B, row by row: B ((1-t) vol0 I + t vol1 Fi Fi^T) = (1-t) vol0 Af + t vol1 Ab Fi^T.
    const Eigen::Matrix3d M = (1 - t) * vol0 * Eigen::Matrix3d::Identity() + t * vol1 * Fi * Fi.transpose();
    const Eigen::Matrix3d B = ((1 - t) * vol0 * Af + t * vol1 * Ab * Fi.transpose()) * M.inverse();
    const Eigen::MatrixXd got = one.at(t);
    const Eigen::MatrixXd expect = tet.V * B.transpose();
    const Eigen::MatrixXd d = (got.rowwise() - got.colwise().mean()) - (expect.rowwise() - expect.colwise().mean());
    CHECK(d.cwiseAbs().maxCoeff() < 1e-9);
    // The one-sided form matches A->(t) alone, a different shape here.
    const Eigen::MatrixXd plain = ArapInterpolation(tet, moved).at(t), expect_plain = tet.V * Af.transpose();
    CHECK(((plain.rowwise() - plain.colwise().mean()) - (expect_plain.rowwise() - expect_plain.colwise().mean()))
              .cwiseAbs().maxCoeff() < 1e-9);
    // Per tet the two targets agree, A<-(1 - t) = A->(t) F^-1 (4.1.1 read backwards), so B = A->(t):
    // a wrong reverse target or weight would pull the symmetric result away from it.
    CHECK((Ab - Af * Fi).cwiseAbs().maxCoeff() < 1e-12);
    CHECK((B - Af).cwiseAbs().maxCoeff() < 1e-12);
  }
  // Across many tets the blend keeps the bent bar's volume as the one-sided form does.
  const TriMesh bar = capped_cylinder(31, 12, L, 0.3);
  const Eigen::MatrixXd bar1 = bent(bar.V, 1.5, 0.5);
  const ArapInterpolation bend(bar, bar1, sym);
  const double v0 = enclosed_volume(bar.V, bar.F);
  for (double t : {0.25, 0.5, 0.75}) CHECK(enclosed_volume(bend.at(t), bar.F) == Approx(v0).epsilon(0.01));
}
