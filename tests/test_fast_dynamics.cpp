// FAST with dynamics (Jacobson 2013, 7.7): the momentum term of Eq. 7.36 in the reduced
// local-global solve. References are written here: a lumped mass from triangle areas, kinetic energy
// from vertex velocities, the static FAST solve (7.3.1) as the equilibrium.
#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "core/bind/bind.h"
#include "core/mesh/io.h"
#include "core/pose/fast_dynamics.h"
#include "core/pose/fast_model.h"
#include "core/pose/fast_solver.h"
#include "core/rig/rig.h"
#include "core/skin/lbs.h"
#include "core/util/error.h"
#include "tests/test_gltf_fixtures.h"
#include "tests/test_support.h"

using namespace dfm;
using Eigen::MatrixXd;
using Eigen::Vector3d;

namespace {

// Hat weights along x for handles at x = 0, L/2, L (as test_fast's tube).
MatrixXd hat_weights(const MatrixXd& V, double L) {
  MatrixXd W = MatrixXd::Zero(V.rows(), 3);
  for (int i = 0; i < V.rows(); ++i) {
    const double s = std::clamp(V(i, 0) / (L / 2), 0.0, 2.0);
    if (s <= 1) W(i, 0) = 1 - s, W(i, 1) = s;
    else W(i, 1) = 2 - s, W(i, 2) = s - 1;
  }
  return W;
}

// A third of each triangle's area per vertex (2.1.3), written out here.
Eigen::VectorXd area_mass(const MatrixXd& V, const Eigen::MatrixXi& F) {
  Eigen::VectorXd m = Eigen::VectorXd::Zero(V.rows());
  for (int f = 0; f < F.rows(); ++f) {
    const Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const double A = 0.5 * (b - a).cross(c - a).norm();
    for (int k = 0; k < 3; ++k) m(F(f, k)) += A / 3;
  }
  return m;
}

double kinetic(const Eigen::VectorXd& m, const MatrixXd& U1, const MatrixXd& U0, double h) {
  return 0.5 * (m.asDiagonal() * ((U1 - U0) / h).rowwise().squaredNorm()).sum();
}

double diagonal(const MatrixXd& V) { return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm(); }

// The tube of test_fast: handle 0 fixed at rest, 1 free, 2 position-constrained at x = L.
struct Tube {
  TriMesh mesh = test::tube(13, 10, 4.0, 0.4);
  MatrixXd W = hat_weights(mesh.V, 4.0);
  FastModel model = fast_model(mesh.V, mesh.F, W);
  std::vector<FastConstraint> constraints() const {
    std::vector<FastConstraint> c(3);
    c[1].state = HandleConstraint::Free;
    c[2].state = HandleConstraint::Position;
    c[2].anchor = Vector3d(4, 0, 0);
    return c;
  }
  std::vector<Vector3d> jumped() const { return {Vector3d::Zero(), Vector3d::Zero(), Vector3d(3.6, 1.2, 0.4)}; }
};

// The static FAST solve (7.3.1) from the rest pose.
Pose static_solve(const Tube& t, int iterations) {
  FastSolver s(t.model, t.constraints());
  Pose p = identity_pose(3);
  s.set_targets(p, t.jumped());
  s.iterate(p, iterations);
  return p;
}

double relative_gap(const Pose& a, const Pose& b) {
  const MatrixXd A = pose_matrix(a), B = pose_matrix(b);
  return (A - B).norm() / B.norm();
}

}  // namespace

TEST_CASE("dynamics, 7.7: with mass 0 or a huge time step a step is the static FAST solve", "[fast][dynamics]") {
  const Tube t;
  const Pose reference = static_solve(t, 12);
  for (const auto& [density, h] : {std::pair{0.0, 1.0 / 60}, std::pair{1.0, 1e7}}) {
    const FastMass mass = fast_mass(t.mesh.V, t.mesh.F, t.W, density);
    FastDynamicsOptions o;
    o.dt = h;
    o.damping = 0;  // damping's term is c/h: only the mass term vanishes like 1/h^2
    o.iterations = 12;
    FastDynamics dyn(t.model, mass, t.constraints(), {}, o, identity_pose(3));
    Pose p = identity_pose(3);
    dyn.step(p, t.jumped());
    INFO("density " << density << ", h " << h);
    CHECK(relative_gap(p, reference) < 1e-9);
  }
}

TEST_CASE("dynamics, 7.7: no motion of the constraints, no gravity, no damping: rest stays rest", "[fast][dynamics]") {
  const Tube t;
  const FastMass mass = fast_mass(t.mesh.V, t.mesh.F, t.W);
  FastDynamicsOptions o;
  o.damping = 0;
  FastDynamics dyn(t.model, mass, t.constraints(), {}, o, identity_pose(3));
  const std::vector<Vector3d> rest_targets{Vector3d::Zero(), Vector3d::Zero(), Vector3d(4, 0, 0)};
  Pose p = identity_pose(3);
  for (int s = 0; s < 100; ++s) dyn.step(p, rest_targets);
  // Rounding only: each step's solve reproduces the identity to ~1e-13.
  CHECK(relative_gap(p, identity_pose(3)) < 1e-10);
  CHECK(dyn.kinetic_energy() <= 1e-20);
}

TEST_CASE("dynamics, 7.7: the lumped mass in the subspace is W^T M W (7.7.2)", "[fast][dynamics]") {
  const Tube t;
  Eigen::VectorXd mask = Eigen::VectorXd::Ones(t.mesh.V.rows());
  mask.head(20).setConstant(3.0);
  const FastMass mass = fast_mass(t.mesh.V, t.mesh.F, t.W, 2.0, mask);
  const double d = diagonal(t.mesh.V);
  const Eigen::VectorXd m = 2.0 / (d * d) * area_mass(t.mesh.V, t.mesh.F).cwiseProduct(mask);
  CHECK(mass.total == Approx(m.sum()).epsilon(1e-12));
  // 1/2 tr(S^T Mt S) is the vertices' kinetic energy for any transform velocity S.
  const MatrixXd S = MatrixXd::Random(12, 3), M = lbs_matrix(t.mesh.V, t.W);
  CHECK(0.5 * (S.transpose() * mass.Mt * S).trace() ==
        Approx(0.5 * (m.asDiagonal() * (M * S).rowwise().squaredNorm()).sum()).epsilon(1e-10));
  // Tets: a quarter of each volume per vertex; the unit tet has volume 1/6 and diagonal sqrt(3).
  MatrixXd Vt(4, 3);
  Vt << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  const FastMass tet = fast_mass(Vt, Eigen::RowVector4i(0, 1, 2, 3), MatrixXd::Ones(4, 1));
  CHECK(tet.total == Approx(1.0 / 6 / 3).epsilon(1e-12));
  CHECK(tet.moments(3) == Approx(1.0 / 6 / 3).epsilon(1e-12));  // W^T M 1: the translation row
  CHECK_THROWS_WITH(fast_mass(t.mesh.V, t.mesh.F, t.W, 1.0, Eigen::VectorXd::Ones(3)),
                    Catch::Contains("mass mask of 3 values"));
  FastDynamicsOptions bad;
  bad.dt = 0;
  CHECK_THROWS_WITH(FastDynamics(t.model, mass, t.constraints(), {}, bad, identity_pose(3)),
                    Catch::Contains("time step must be > 0"));
}

TEST_CASE("dynamics, 7.7: damped, a step input's kinetic energy decays to the static solve", "[fast][dynamics]") {
  const Tube t;
  const Eigen::VectorXd m = area_mass(t.mesh.V, t.mesh.F) / std::pow(diagonal(t.mesh.V), 2);
  const FastMass mass = fast_mass(t.mesh.V, t.mesh.F, t.W);
  FastDynamicsOptions o;  // default damping
  FastDynamics dyn(t.model, mass, t.constraints(), {}, o, identity_pose(3));
  Pose p = identity_pose(3);
  MatrixXd U0 = t.mesh.V;
  std::vector<double> ke;
  const int steps = 600;  // 10 s at 60 Hz
  for (int s = 0; s < steps; ++s) {
    dyn.step(p, t.jumped());
    const MatrixXd U = lbs(t.mesh.V, t.W, p);
    ke.push_back(kinetic(m, U, U0, o.dt));
    U0 = U;
  }
  const double peak = *std::max_element(ke.begin(), ke.end());
  CHECK(ke.back() < 1e-8 * peak);
  // Decays: each second's largest kinetic energy below the previous second's.
  for (int sec = 1; sec < 10; ++sec)
    CHECK(*std::max_element(ke.begin() + 60 * sec, ke.begin() + 60 * (sec + 1)) <
          *std::max_element(ke.begin() + 60 * (sec - 1), ke.begin() + 60 * sec));
  const MatrixXd U_static = lbs(t.mesh.V, t.W, static_solve(t, 200));
  const double gap = (U0 - U_static).rowwise().norm().maxCoeff() / diagonal(t.mesh.V);
  WARN("tube step: kinetic peak " << peak << ", after 10 s " << ke.back() << "; final frame to static " << gap
                                  << " of the diagonal");
  CHECK(gap < 1e-3);
}

TEST_CASE("dynamics, 7.7: undamped, the discrete energy does not grow over 500 steps", "[fast][dynamics]") {
  const Tube t;
  const Eigen::VectorXd m = area_mass(t.mesh.V, t.mesh.F) / std::pow(diagonal(t.mesh.V), 2);
  const FastMass mass = fast_mass(t.mesh.V, t.mesh.F, t.W);
  FastDynamicsOptions o;
  o.damping = 0;
  o.iterations = 8;
  FastDynamics dyn(t.model, mass, t.constraints(), {}, o, identity_pose(3));
  Pose p = identity_pose(3);
  MatrixXd U0 = t.mesh.V;
  double first = 0, last = 0, largest_rise = 0;
  for (int s = 0; s < 500; ++s) {
    dyn.step(p, t.jumped());  // the jump at step 0 puts energy in; after it the system is autonomous
    const MatrixXd U = lbs(t.mesh.V, t.W, p);
    const double e = kinetic(m, U, U0, o.dt) + fast_energy(t.model, p);
    U0 = U;
    if (s == 0) first = e;
    else largest_rise = std::max(largest_rise, (e - last) / first);
    last = e;
  }
  WARN("undamped tube: energy after the jump " << first << ", after 500 steps " << last << ", largest rise "
                                               << largest_rise << " of it");
  CHECK(last <= first);
  CHECK(largest_rise < 1e-6);
}

TEST_CASE("dynamics on the arm: a free handle between a pinned shoulder and a jumped hand overshoots and settles",
          "[fast][dynamics][data]") {
  DFM_DATA_OR_SKIP(obj, "arm.obj");
  const TriMesh arm = read_surface(obj);
  // Four point handles at arm.tgf's joints: two at the shoulder, one at the elbow (free), the hand.
  Rig rig;
  for (const Vector3d& p : {Vector3d(-0.7296, 0.0117, -0.1328), Vector3d(-0.7832, 0.2166, -0.0075),
                            Vector3d(0.0814, 0.1852, -0.0425), Vector3d(0.7357, -0.1752, 0.0902)})
    rig.points.push_back({p, ""});
  const BindResult bind = bind_surface(arm, rig);
  const FastModel model = fast_model(arm.V, arm.F, bind.weights);
  std::vector<FastConstraint> c(4);  // 0, 1 fixed at rest (pinned)
  c[2].state = HandleConstraint::Free;
  c[3].state = HandleConstraint::Position;
  c[3].anchor = rig.points[3].position;
  const double diag = diagonal(arm.V);
  std::vector<Vector3d> targets(4, Vector3d::Zero());
  targets[3] = rig.points[3].position + Vector3d(0, 0, 0.25 * diag);  // sideways, a quarter of the diagonal

  FastSolver statics(model, c);
  Pose rest = identity_pose(4), p_static = rest;
  statics.set_targets(p_static, targets);
  statics.iterate(p_static, 300);
  const MatrixXd U_static = lbs(arm.V, bind.weights, p_static);
  // The free region: where the elbow handle's weight leads.
  std::vector<int> region;
  for (int i = 0; i < arm.V.rows(); ++i) {
    Eigen::Index best;
    bind.weights.row(i).maxCoeff(&best);
    if (best == 2) region.push_back(i);
  }
  REQUIRE(region.size() > 10);
  auto centroid = [&](const MatrixXd& U) {
    Vector3d s = Vector3d::Zero();
    for (int i : region) s += U.row(i).transpose();
    return Vector3d(s / region.size());
  };
  const Vector3d c0 = centroid(arm.V), c_static = centroid(U_static), dir = (c_static - c0).normalized();
  const double travel = (c_static - c0).norm();

  const FastMass mass = fast_mass(arm.V, arm.F, bind.weights);
  FastDynamicsOptions o;  // defaults: h = 1/60, default damping
  FastDynamics dyn(model, mass, c, {}, o, rest);
  Pose p = rest;
  double overshoot = 0, settled_at = 0;
  MatrixXd U;
  const int steps = 480;  // 8 s
  for (int s = 0; s < steps; ++s) {
    dyn.step(p, targets);
    U = lbs(arm.V, bind.weights, p);
    const Vector3d ci = centroid(U);
    overshoot = std::max(overshoot, (ci - c0).dot(dir) / travel - 1);
    if ((ci - c_static).norm() > 0.02 * travel) settled_at = (s + 1) * o.dt;  // last time outside 2%
  }
  const double gap = (U - U_static).rowwise().norm().maxCoeff() / diag;
  WARN("arm step (hand " << 0.25 * diag << " sideways, free region " << region.size() << " vertices, travel "
                         << travel / diag << " of the diagonal): overshoot " << 100 * overshoot
                         << "% of the travel, settled within 2% at " << settled_at << " s; final frame to static "
                         << gap << " of the diagonal");
  CHECK(overshoot > 0.05);
  CHECK(settled_at < 5.0);
  CHECK(gap < 1e-3);
}

TEST_CASE("dynamics, 7.7.2: with every handle free, gravity is free fall (backward Euler's x_n)", "[fast][dynamics]") {
  // Translations cost no ARAP energy, so the body falls rigidly: v_n = n h g, x_n = x_0 + h^2 g n(n+1)/2.
  const Tube t;
  const FastMass mass = fast_mass(t.mesh.V, t.mesh.F, t.W);
  FastDynamicsOptions o;
  o.damping = 0;
  o.gravity = Vector3d(0, -9.81, 0);
  std::vector<FastConstraint> free(3);
  for (auto& c : free) c.state = HandleConstraint::Free;
  FastDynamics dyn(t.model, mass, free, {}, o, identity_pose(3));
  Pose p = identity_pose(3);
  const int n = 30;
  for (int s = 0; s < n; ++s) dyn.step(p, {});
  const MatrixXd U = lbs(t.mesh.V, t.W, p);
  const Vector3d drop = o.dt * o.dt * o.gravity * n * (n + 1) / 2;
  const double err = (U - (t.mesh.V.rowwise() + drop.transpose())).rowwise().norm().maxCoeff();
  INFO("drop " << drop.transpose() << ", largest vertex error " << err);
  CHECK(err < 1e-9 * drop.norm());
}
