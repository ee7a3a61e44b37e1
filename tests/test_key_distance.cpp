// The keys' signed distance (core/anim/key_distance.h): its magnitude against a box's closed form,
// its sign against the winding number summed here triangle by triangle (Van Oosterom and Strackee's
// solid angle), at random points and just off the surface of a torus and two spheres; the rounded
// distance (core/anim/rounded_distance.h) against the box's closed form averaged over the octahedron.
#include <cmath>
#include <random>

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "core/anim/key_distance.h"
#include "core/anim/rounded_distance.h"
#include "tests/key_mesh_test_meshes.h"
#include "tests/transition_test_meshes.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;

namespace {

double brute_winding_number(const TriMesh& m, const Eigen::Vector3d& p) {
  double sum = 0;
  for (int f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d a = m.V.row(m.F(f, 0)).transpose() - p, b = m.V.row(m.F(f, 1)).transpose() - p,
                          c = m.V.row(m.F(f, 2)).transpose() - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    sum += 2 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
  }
  return sum / (4 * M_PI);
}

double brute_distance(const TriMesh& m, const Eigen::Vector3d& p) {
  double d = INFINITY;
  for (int f = 0; f < m.F.rows(); ++f)
    d = std::min(d, dfm::test::point_triangle_distance(p, m.V.row(m.F(f, 0)).transpose(), m.V.row(m.F(f, 1)).transpose(),
                                                       m.V.row(m.F(f, 2)).transpose()));
  return d;
}

// Random points in the box around m, and each vertex moved off the surface both ways by `off`
// along its normal (the mean of its faces' normals).
Eigen::MatrixXd probes(const TriMesh& m, int random, double off) {
  std::mt19937 rng(7);
  const Eigen::RowVector3d lo = m.V.colwise().minCoeff().array() - 0.3, hi = m.V.colwise().maxCoeff().array() + 0.3;
  std::uniform_real_distribution<double> u(0, 1);
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(m.V.rows(), 3);
  for (int f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    for (int j = 0; j < 3; ++j) N.row(m.F(f, j)) += n.transpose();
  }
  N.rowwise().normalize();
  Eigen::MatrixXd P(random + 2 * m.V.rows(), 3);
  for (int i = 0; i < random; ++i)
    for (int k = 0; k < 3; ++k) P(i, k) = lo[k] + (hi[k] - lo[k]) * u(rng);
  P.middleRows(random, m.V.rows()) = m.V + off * N;
  P.bottomRows(m.V.rows()) = m.V - off * N;
  return P;
}

// The box [-1, 1]^3 with outward triangles.
TriMesh unit_box() {
  TriMesh box;
  box.V.resize(8, 3);
  for (int i = 0; i < 8; ++i) box.V.row(i) << (i & 1 ? 1 : -1), (i & 2 ? 1 : -1), (i & 4 ? 1 : -1);
  box.F.resize(12, 3);
  box.F << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5;
  return box;
}

// Its signed distance in closed form: outside, the distance to the nearest face, edge or corner;
// inside, minus the distance to the nearest face.
double box_distance(const Eigen::Vector3d& p) {
  const Eigen::Array3d q = p.array().abs() - 1.0;
  return q.max(0.0).matrix().norm() + std::min(q.maxCoeff(), 0.0);
}

// The octahedron average of the box's closed-form distance (rounded_distance.h's rule, c = r).
double box_rounded(const Eigen::Vector3d& p, double r) {
  const double s = r * std::abs(box_distance(p));
  double mean = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {-1.0, 1.0}) mean += box_distance(p + side * s * Eigen::Vector3d::Unit(axis)) / 6;
  return mean;
}

// g's central differences at p with step e.
template <class Function>
Eigen::Vector3d central_difference(const Function& g, const Eigen::Vector3d& p, double e) {
  Eigen::Vector3d out;
  for (int k = 0; k < 3; ++k)
    out[k] = (g(Eigen::Vector3d(p + e * Eigen::Vector3d::Unit(k))) - g(Eigen::Vector3d(p - e * Eigen::Vector3d::Unit(k)))) / (2 * e);
  return out;
}

// Random points in [-2.5, 2.5]^3.
Eigen::MatrixXd box_probes(int n) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2.5, 2.5);
  Eigen::MatrixXd P(n, 3);
  for (int i = 0; i < P.rows(); ++i) P.row(i) << u(rng), u(rng), u(rng);
  return P;
}

}  // namespace

TEST_CASE("key distance: a box's signed distance, edges and corners nearest included", "[transition]") {
  const TriMesh box = unit_box();
  const SignedDistance d(box.V, box.F);
  const Eigen::MatrixXd P = box_probes(3000);
  const Eigen::VectorXd got = d(P);
  int outside_corner = 0;
  for (int i = 0; i < P.rows(); ++i) {
    outside_corner += (P.row(i).array().abs() > 1.0).all();
    CHECK(got[i] == Approx(box_distance(P.row(i).transpose())).margin(1e-12));
  }
  CHECK(outside_corner > 100);  // many points whose nearest feature is a corner
}

TEST_CASE("key distance: signs agree with the winding number on curved, non-convex and two-piece keys", "[transition]") {
  const TriMesh shapes[] = {dfm::test::torus(Eigen::Vector3d::Zero(), 0.32, 0.12, 40, 20),
                            dfm::test::concat(dfm::test::icosphere(Eigen::Vector3d(-0.22, 0, 0), 0.2, 2),
                                              dfm::test::icosphere(Eigen::Vector3d(0.22, 0, 0.01), 0.2, 2))};
  for (const TriMesh& m : shapes) {
    const SignedDistance d(m.V, m.F);
    const Eigen::MatrixXd P = probes(m, 2000, 1e-4);
    const Eigen::VectorXd got = d(P);
    int wrong = 0;
    for (int i = 0; i < P.rows(); ++i) {
      const bool inside = brute_winding_number(m, P.row(i).transpose()) > 0.5;
      wrong += inside != (got[i] < 0);
      CHECK(std::abs(got[i]) == Approx(brute_distance(m, P.row(i).transpose())).margin(1e-12));
    }
    CHECK(wrong == 0);
  }
}

TEST_CASE("rounded distance: the box's distance averaged over the octahedron at half its value", "[transition]") {
  const TriMesh box = unit_box();
  const SignedDistance d(box.V, box.F);
  const Eigen::MatrixXd P = box_probes(400);
  const Eigen::VectorXd dp = d(P), s = rounded_distance(d, P, 0.5);
  for (int i = 0; i < P.rows(); ++i) {
    const Eigen::Vector3d p = P.row(i).transpose();
    INFO("point " << p.transpose());
    CHECK(s[i] == Approx(box_rounded(p, 0.5)).margin(1e-9));
    CHECK((s[i] < 0) == (dp[i] < 0));  // the octahedron stays on the point's side
  }
  // The centre's crease (six faces nearest at once) is rounded: d = -1 there, s = -1/2.
  const Eigen::MatrixXd centre = Eigen::RowVector3d::Zero();
  CHECK(rounded_distance(d, centre, 0.5)[0] == Approx(-0.5).margin(1e-12));
  // Where d is linear (near the middle of a face, inside and out) the rule returns d.
  Eigen::MatrixXd faces(2, 3);
  faces << 0.1, -0.05, 1.3, 0.05, 0.1, 0.7;
  const Eigen::VectorXd df = d(faces);
  CHECK(rounded_distance(d, faces, 0.5).isApprox(df, 1e-12));
  // No rounding is d itself; on the surface the value is 0.
  CHECK(rounded_distance(d, P, 0.0) == dp);
  Eigen::MatrixXd on_face(1, 3);
  on_face << 1, 0.2, -0.3;
  CHECK(std::abs(rounded_distance(d, on_face, 0.5)[0]) < 1e-12);
  CHECK_THROWS_WITH(rounded_distance(d, P, 1.0), Catch::Contains("[0, 1)"));
  CHECK_THROWS_WITH(rounded_distance(d, P.leftCols(2), 0.5), Catch::Contains("#P x 3"));
}

TEST_CASE("key distance and rounded distance: gradients match the box's closed forms' differences", "[transition]") {
  const TriMesh box = unit_box();
  const SignedDistance d(box.V, box.F);
  const Eigen::MatrixXd P = box_probes(400);
  Eigen::MatrixXd gd, gs;
  d(P, &gd);
  rounded_distance(d, P, 0.5, &gs);
  int smooth_d = 0, smooth_s = 0;
  for (int i = 0; i < P.rows(); ++i) {
    const Eigen::Vector3d p = P.row(i).transpose();
    INFO("point " << p.transpose());
    auto plain = [](const Eigen::Vector3d& x) { return box_distance(x); };
    auto rounded = [](const Eigen::Vector3d& x) { return box_rounded(x, 0.5); };
    // Compared where the closed form is smooth: two step sizes agree (no crease within reach).
    const Eigen::Vector3d a = central_difference(plain, p, 1e-5), b = central_difference(plain, p, 1e-6);
    if ((a - b).norm() < 1e-6) {
      ++smooth_d;
      CHECK((gd.row(i).transpose() - b).norm() < 1e-6);
    }
    const Eigen::Vector3d c = central_difference(rounded, p, 1e-5), e = central_difference(rounded, p, 1e-6);
    if ((c - e).norm() < 1e-6) {
      ++smooth_s;
      CHECK((gs.row(i).transpose() - e).norm() < 1e-6);
    }
  }
  CHECK(smooth_d > 300);
  CHECK(smooth_s > 300);
  // No rounding: the gradient is d's. On a face the gradient is its outward normal.
  Eigen::MatrixXd g0;
  rounded_distance(d, P, 0.0, &g0);
  CHECK(g0 == gd);
  Eigen::MatrixXd on_face(1, 3), gf;
  on_face << 1, 0.2, -0.3;
  d(on_face, &gf);
  CHECK(gf.row(0).isApprox(Eigen::RowVector3d(1, 0, 0), 1e-12));
}
