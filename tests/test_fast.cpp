// FAST (Jacobson 2013, ch. 7): the ARAP element coefficients against closed forms, the local step
// against brute force, and the solver's invariants (7.3.1, 7.3.3): fixed handles untouched,
// translation covariance, monotone energy, rigid motions reproduced, and a bent arm whose ARAP
// energy, recomputed here with per-vertex best-fit rotations, is below plain LBS's.
#include <cmath>
#include <random>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "core/bind/bind.h"
#include "core/mesh/io.h"
#include "core/pose/arap_elements.h"
#include "core/pose/best_rotation.h"
#include "core/pose/fast_model.h"
#include "core/pose/fast_posing.h"
#include "core/pose/fast_solver.h"
#include "core/pose/weight_clusters.h"
#include "core/rig/rig_io.h"
#include "core/skin/lbs.h"
#include "core/util/error.h"
#include "tests/test_gltf_fixtures.h"
#include "tests/test_support.h"

using namespace dfm;
using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;

namespace {

Matrix3d random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> g;
  Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  return q.normalized().toRotationMatrix();
}

double angle_between(const Vector3d& a, const Vector3d& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

// Spokes-and-rims ARAP energy with each vertex's own best-fit rotation, written from Eq. 7.4 with
// angles and a plain SVD: the independent yardstick for the FAST results.
double per_vertex_arap_energy(const MatrixXd& V, const Eigen::MatrixXi& F, const MatrixXd& U) {
  std::vector<Matrix3d> S(V.rows(), Matrix3d::Zero());
  auto edge_weight = [&](int f, int corner) {  // cot(angle at corner) / 2, for the opposite edge
    const Vector3d p = V.row(F(f, corner)), a = V.row(F(f, (corner + 1) % 3)), b = V.row(F(f, (corner + 2) % 3));
    return 0.5 / std::tan(angle_between(a - p, b - p));
  };
  for (int pass = 0; pass < 2; ++pass) {
    double E = 0;
    std::vector<Matrix3d> R(V.rows());
    if (pass == 1)
      for (int v = 0; v < V.rows(); ++v) {
        Eigen::JacobiSVD<Matrix3d> svd(S[v], Eigen::ComputeFullU | Eigen::ComputeFullV);
        Matrix3d W = svd.matrixV();
        if ((W * svd.matrixU().transpose()).determinant() < 0) W.col(2) *= -1;
        R[v] = W * svd.matrixU().transpose();
      }
    for (int f = 0; f < F.rows(); ++f)
      for (int corner = 0; corner < 3; ++corner) {
        const int i = F(f, (corner + 1) % 3), j = F(f, (corner + 2) % 3);
        const double c = edge_weight(f, corner);
        const Vector3d d = (V.row(i) - V.row(j)).transpose(), dp = (U.row(i) - U.row(j)).transpose();
        for (int k = 0; k < 3; ++k) {
          const int owner = F(f, k);
          if (pass == 0) S[owner] += c * d * dp.transpose();
          else E += 0.5 * c * (dp - R[owner] * d).squaredNorm();
        }
      }
    if (pass == 1) return E;
  }
  return 0;
}

// Piecewise-linear hat weights along x for handles at x = 0, L/2, L (a partition of unity, 1 at each
// handle's own position).
MatrixXd hat_weights(const MatrixXd& V, double L) {
  MatrixXd W = MatrixXd::Zero(V.rows(), 3);
  for (int i = 0; i < V.rows(); ++i) {
    const double s = std::clamp(V(i, 0) / (L / 2), 0.0, 2.0);
    if (s <= 1) W(i, 0) = 1 - s, W(i, 1) = s;
    else W(i, 1) = 2 - s, W(i, 2) = s - 1;
  }
  return W;
}

struct Tube {
  TriMesh mesh = test::tube(25, 16, 4.0, 0.4);
  MatrixXd W = hat_weights(mesh.V, 4.0);
  std::vector<Vector3d> anchors{Vector3d(0, 0, 0), Vector3d(2, 0, 0), Vector3d(4, 0, 0)};
};

// Handle 0 fixed to `fixed0`, 1 free, 2 position-constrained to `target2`.
std::vector<FastConstraint> fixed_free_position(const Tube& t) {
  std::vector<FastConstraint> c(3);
  c[1].state = HandleConstraint::Free;
  c[2].state = HandleConstraint::Position;
  c[2].anchor = t.anchors[2];
  return c;
}

}  // namespace

TEST_CASE("best_rotation maximizes tr(R S) over rotations (brute force), never a reflection", "[fast]") {
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 20; ++trial) {
    Matrix3d S;
    for (int i = 0; i < 9; ++i) S(i) = g(rng);
    if (trial == 0) S = Eigen::Vector3d(3, 2, -1).asDiagonal();  // the reflection would win without the fix
    const Matrix3d R = best_rotation(S);
    CHECK(R.determinant() == Approx(1.0).margin(1e-12));
    CHECK((R.transpose() * R - Matrix3d::Identity()).norm() < 1e-12);
    const double best = (R * S).trace();
    for (int k = 0; k < 3000; ++k) CHECK((random_rotation(rng) * S).trace() <= best + 1e-12);
  }
  // S built from a rotated point cloud recovers that rotation (Eq. 7.13's S_k with R_k = R0).
  const Matrix3d R0 = random_rotation(rng);
  Matrix3d S = Matrix3d::Zero();
  for (int i = 0; i < 10; ++i) {
    const Vector3d y(g(rng), g(rng), g(rng));
    S += y * (R0 * y).transpose();
  }
  CHECK((best_rotation(S) - R0).norm() < 1e-12);
}

TEST_CASE("ARAP element coefficients: cot/2 on triangles, (l/6) cot(dihedral) on tets", "[fast]") {
  MatrixXd V(4, 3);
  V << 0.1, 0.2, 0, 1.3, 0.1, 0.2, 0.4, 1.1, -0.1, 0.3, 0.35, 0.9;
  Eigen::MatrixXi tri(1, 3), tet(1, 4);
  tri << 0, 1, 2;
  tet << 0, 1, 2, 3;
  const MatrixXd Lt = arap_element_matrices(V, tri), Lk = arap_element_matrices(V, tet);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      if (i == j) continue;
      const int o = 3 - i - j;
      const Vector3d p = V.row(o), a = V.row(i), b = V.row(j);
      CHECK(-Lt(i + 3 * j, 0) == Approx(0.5 / std::tan(angle_between(a - p, b - p))).epsilon(1e-12));
    }
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      if (i == j) continue;
      int k = -1, l = -1;
      for (int c = 0; c < 4; ++c)
        if (c != i && c != j) (k < 0 ? k : l) = c;
      const Vector3d pk = V.row(k), pl = V.row(l), e = (pl - pk).normalized();
      auto perp = [&](const Vector3d& p) { return Vector3d((p - pk) - (p - pk).dot(e) * e); };
      const double theta = angle_between(perp(V.row(i)), perp(V.row(j)));
      CHECK(-Lk(i + 4 * j, 0) == Approx((pl - pk).norm() / 6.0 / std::tan(theta)).epsilon(1e-10));
    }
  CHECK(Eigen::Map<const MatrixXd>(Lk.data(), 4, 4).rowwise().sum().norm() < 1e-12);
  MatrixXd flat = V;
  flat.row(2) = 0.5 * (V.row(0) + V.row(1));
  CHECK_THROWS_WITH(arap_element_matrices(flat, tri), Catch::Contains("triangle 0 is degenerate"));
}

TEST_CASE("weight clusters: identical rows share a cluster, separated groups split", "[fast]") {
  MatrixXd W(6, 2);
  W << 1, 0, 1, 0, 1, 0, 0, 1, 0, 1, 0.5, 0.5;
  const WeightClusters c = weight_clusters(W, 3);
  CHECK(c.count == 3);
  CHECK(c.cluster(0) == c.cluster(1));
  CHECK(c.cluster(1) == c.cluster(2));
  CHECK(c.cluster(3) == c.cluster(4));
  CHECK(c.cluster(0) != c.cluster(3));
  CHECK(c.cluster(5) != c.cluster(0));
  CHECK(c.cluster(5) != c.cluster(3));
  CHECK(weight_clusters(W, 10).count == 3);  // never more clusters than distinct rows
}

TEST_CASE("FAST: fixed handles stay exactly as given; energy never increases", "[fast]") {
  const Tube t;
  const FastModel model = fast_model(t.mesh.V, t.mesh.F, t.W);
  CHECK(model.clusters == 6);
  FastSolver solver(model, fixed_free_position(t));
  Pose pose = identity_pose(3);
  pose.transforms[0] = Eigen::AngleAxisd(0.3, Vector3d::UnitZ()) * Eigen::Translation3d(0, 0.1, 0);
  const Eigen::Affine3d fixed0 = pose.transforms[0];
  std::vector<Vector3d> targets(3, Vector3d::Zero());
  targets[2] = Vector3d(3.0, 1.8, 0.3);
  solver.set_targets(pose, targets);
  double last = std::numeric_limits<double>::infinity();
  for (int it = 0; it < 60; ++it) {
    const double E = solver.iterate(pose);
    CHECK(E <= last + 1e-12 * std::abs(last));
    CHECK(E >= -1e-12);
    last = E;
  }
  CHECK(pose.transforms[0].matrix() == fixed0.matrix());
  CHECK((pose.transforms[2] * t.anchors[2] - targets[2]).norm() < 1e-10);  // the position constraint holds
  // The converged energy matches an independent evaluation of E(T, best R) for the same transforms.
  CHECK(fast_energy(model, pose) == Approx(last).epsilon(1e-6));
  // Every handle fixed: nothing to solve, the pose comes back unchanged (plain LBS).
  std::vector<FastConstraint> all_fixed(3);
  FastSolver fixed(model, all_fixed);
  Pose p2 = pose;
  fixed.set_targets(p2, targets);
  fixed.iterate(p2);
  for (int h = 0; h < 3; ++h) CHECK(p2.transforms[h].matrix() == pose.transforms[h].matrix());
}

TEST_CASE("FAST: joint rows keep two solved handles meeting at their joint, and a free one on a fixed one",
          "[fast]") {
  const Tube t;
  const FastModel model = fast_model(t.mesh.V, t.mesh.F, t.W);
  std::vector<FastConstraint> c = fixed_free_position(t);
  // Joints at x = 1 (handles 0 and 1: fixed and free) and x = 3 (handles 1 and 2: free and position).
  const Vector3d j01(1, 0, 0), j12(3, 0, 0);
  const std::vector<FastJoint> joints{{1, 0, j01}, {2, 1, j12}};
  FastSolver with(model, c, joints), without(model, c);
  Pose pose = identity_pose(3), loose = identity_pose(3);
  pose.transforms[0] = loose.transforms[0] = Eigen::AngleAxisd(0.3, Vector3d::UnitZ()) * Eigen::Translation3d(0, 0.1, 0);
  std::vector<Vector3d> targets(3, Vector3d::Zero());
  targets[2] = Vector3d(3.0, 1.8, 0.3);
  with.set_targets(pose, targets);
  without.set_targets(loose, targets);
  with.iterate(pose, 30);
  without.iterate(loose, 30);
  const double gap01 = (pose.transforms[1] * j01 - pose.transforms[0] * j01).norm();
  const double gap12 = (pose.transforms[2] * j12 - pose.transforms[1] * j12).norm();
  CHECK(gap01 < 1e-10);
  CHECK(gap12 < 1e-10);
  CHECK((pose.transforms[2] * t.anchors[2] - targets[2]).norm() < 1e-10);  // the position row still holds
  // Without the rows the handles drift apart at the joints: the rows are what holds them.
  CHECK((loose.transforms[1] * j01 - loose.transforms[0] * j01).norm() + (loose.transforms[2] * j12 - loose.transforms[1] * j12).norm() > 1e-3);
  // A joint whose child is fixed adds no row (the child follows afterwards): the same solver as none.
  std::vector<FastConstraint> c2(3);
  c2[0].state = HandleConstraint::Free;
  FastSolver child_fixed(model, c2, {{1, 0, j01}}), plain(model, c2);
  Pose a = identity_pose(3), b = identity_pose(3);
  a.transforms[1] = b.transforms[1] = Eigen::Affine3d(Eigen::Translation3d(0, 0.5, 0));
  child_fixed.set_targets(a, targets);
  plain.set_targets(b, targets);
  child_fixed.iterate(a, 5);
  plain.iterate(b, 5);
  CHECK((a.transforms[0].matrix() - b.transforms[0].matrix()).norm() < 1e-12);
  CHECK_THROWS_AS(FastSolver(model, c, {{1, 1, j01}}), Error);
}

TEST_CASE("FAST: translating every constraint by t translates the result by t (7.3.3)", "[fast]") {
  const Tube t;
  const FastModel model = fast_model(t.mesh.V, t.mesh.F, t.W);
  FastSolver solver(model, fixed_free_position(t));
  const Vector3d shift(0.7, -1.1, 2.3);
  Pose a = identity_pose(3), b = identity_pose(3);
  a.transforms[0] = Eigen::AngleAxisd(-0.4, Vector3d::UnitY()) * Eigen::Affine3d::Identity();
  b.transforms[0] = Eigen::Translation3d(shift) * a.transforms[0];
  for (int h = 1; h < 3; ++h) b.transforms[h] = Eigen::Translation3d(shift) * a.transforms[h];
  std::vector<Vector3d> ta(3, Vector3d::Zero()), tb(3, Vector3d::Zero());
  ta[2] = Vector3d(3.2, -1.5, 0.8);
  tb[2] = ta[2] + shift;
  for (int it = 0; it < 30; ++it) {
    solver.set_targets(a, ta);
    solver.iterate(a);
    solver.set_targets(b, tb);
    solver.iterate(b);
  }
  const MatrixXd Ua = lbs(t.mesh.V, t.W, a), Ub = lbs(t.mesh.V, t.W, b);
  CHECK(((Ub.rowwise() - shift.transpose()) - Ua).cwiseAbs().maxCoeff() < 1e-9);
}

TEST_CASE("FAST: a frame's iterations in one call equal as many single iterations", "[fast]") {
  // Two free handles and one pinned by position: 3r = 18 rows < 2 * 12 unknowns, so the batched call
  // stays in rotation space between its first and last iteration.
  const Tube t;
  const FastModel model = fast_model(t.mesh.V, t.mesh.F, t.W);
  std::vector<FastConstraint> c = fixed_free_position(t);
  c[0].state = HandleConstraint::Free;
  FastSolver solver(model, c);
  Pose single = identity_pose(3);
  std::vector<Vector3d> targets(3, Vector3d::Zero());
  targets[2] = Vector3d(3.0, 1.8, 0.3);
  solver.set_targets(single, targets);
  Pose batched = single;
  for (int frame = 0; frame < 3; ++frame) {
    for (int it = 0; it < 8; ++it) solver.iterate(single, false);
    solver.iterate(batched, 8);
    for (int h = 0; h < 3; ++h)
      CHECK((single.transforms[h].matrix() - batched.transforms[h].matrix()).cwiseAbs().maxCoeff() < 1e-9);
  }
  // The batch moved the pose (not a no-op).
  CHECK((batched.transforms[1].matrix() - Eigen::Matrix4d::Identity()).norm() > 1e-3);
}

TEST_CASE("FAST: a rigid motion of every constraint gives that rigid motion", "[fast]") {
  const Tube t;
  const FastModel model = fast_model(t.mesh.V, t.mesh.F, t.W);
  FastSolver solver(model, fixed_free_position(t));
  const Eigen::Affine3d Q = Eigen::Translation3d(0.5, 2.0, -1.0) * Eigen::AngleAxisd(1.1, Vector3d(1, 2, 3).normalized());
  Pose pose = identity_pose(3);
  pose.transforms[0] = Q;
  std::vector<Vector3d> targets(3, Vector3d::Zero());
  targets[2] = Q * t.anchors[2];
  solver.set_targets(pose, targets);
  double E = 0;
  for (int it = 0; it < 300; ++it) E = solver.iterate(pose);
  const MatrixXd U = lbs(t.mesh.V, t.W, pose);
  const MatrixXd rigid = (t.mesh.V * Q.linear().transpose()).rowwise() + Q.translation().transpose();
  CHECK((U - rigid).cwiseAbs().maxCoeff() < 1e-4);
  CHECK(E < 1e-8);
  // The rigid motion is a fixed point: one more iteration from it changes nothing.
  Pose exact = identity_pose(3);
  for (auto& T : exact.transforms) T = Q;
  solver.iterate(exact);
  for (const auto& T : exact.transforms) CHECK((T.matrix() - Q.matrix()).norm() < 1e-9);
}

TEST_CASE("FAST on the arm: drag the hand, pin the shoulder, free elbow: it bends, ARAP below LBS",
          "[fast][data]") {
  DFM_DATA_OR_SKIP(obj, "arm.obj");
  DFM_DATA_OR_SKIP(tgf, "arm.tgf");
  const TriMesh arm = read_surface(obj);
  const TgfData skeleton = read_tgf(tgf);
  Rig rig;
  for (int j : {1, 2, 4}) rig.points.push_back({skeleton.joints.row(j).transpose(), "joint " + std::to_string(j)});
  const BindResult bind = bind_surface(arm, rig);
  const FastModel model = fast_model(arm.V, arm.F, bind.weights);
  std::vector<FastConstraint> c(3);
  c[1].state = HandleConstraint::Free;
  c[2].state = HandleConstraint::Position;
  c[2].anchor = rig.points[2].position;
  FastSolver solver(model, c);
  // Drag the hand up by a third of the arm's length.
  const double length = (rig.points[2].position - rig.points[0].position).norm();
  std::vector<Vector3d> targets(3, Vector3d::Zero());
  targets[2] = rig.points[2].position + Vector3d(0, length / 3, 0);
  Pose lbs_pose = identity_pose(3);
  lbs_pose.transforms[2] = Eigen::Translation3d(targets[2] - rig.points[2].position);
  Pose pose = lbs_pose;
  solver.set_targets(pose, targets);
  for (int it = 0; it < 40; ++it) solver.iterate(pose);
  const MatrixXd U_fast = lbs(arm.V, bind.weights, pose), U_lbs = lbs(arm.V, bind.weights, lbs_pose);
  const double e_fast = per_vertex_arap_energy(arm.V, arm.F, U_fast);
  const double e_lbs = per_vertex_arap_energy(arm.V, arm.F, U_lbs);
  WARN("arm drag: ARAP energy FAST " << e_fast << ", LBS " << e_lbs);
  CHECK(e_fast < 0.5 * e_lbs);
  // It bends: the free elbow moved and the hand handle turned.
  CHECK((pose.transforms[1] * rig.points[1].position - rig.points[1].position).norm() > 0.02 * length);
  CHECK(Eigen::AngleAxisd(best_rotation(pose.transforms[2].linear().transpose())).angle() > 0.1);
}

TEST_CASE("FastPosing: solved transforms land in the params, caches rebuild only when they must", "[fast]") {
  const Tube t;
  Rig rig;
  for (int h = 0; h < 3; ++h) rig.points.push_back({t.anchors[h], "point " + std::to_string(h + 1)});
  std::vector<HandleConstraint> states = default_constraint_states(rig);
  REQUIRE(states == std::vector<HandleConstraint>(3, HandleConstraint::Position));
  states[0] = parse_constraint_state("pinned");
  states[1] = parse_constraint_state("free");
  CHECK_THROWS_WITH(parse_constraint_state("loose"), Catch::Contains("unknown handle state 'loose'"));
  PoseParams params = rest_pose_params(rig);
  params.point_translation[2] = Vector3d(-0.5, 1.5, 0.2);
  FastPosing fast;
  const FastSolveReport first = fast.solve(rig, t.mesh.V, t.mesh.F, t.W, states, 10, params);
  CHECK(first.precomputed);
  CHECK(first.switched);
  CHECK(params.solved.size() == 2);
  CHECK(params.solved.count(0) == 0);
  const Pose posed = evaluate_pose(rig, params);
  CHECK((posed.transforms[2] * t.anchors[2] - (t.anchors[2] + params.point_translation[2])).norm() < 1e-10);
  CHECK(posed.transforms[0].matrix() == Eigen::Matrix4d::Identity());
  // Same inputs: warm start from the solved transforms, nothing rebuilt, the energy does not rise.
  const FastSolveReport again = fast.solve(rig, t.mesh.V, t.mesh.F, t.W, states, 10, params);
  CHECK(!again.precomputed);
  CHECK(!again.switched);
  CHECK(again.energy <= first.energy * (1 + 1e-12));
  states[1] = HandleConstraint::Position;
  const FastSolveReport switched = fast.solve(rig, t.mesh.V, t.mesh.F, t.W, states, 1, params);
  CHECK(switched.switched);
  CHECK(!switched.precomputed);
  // New weights in the same matrix (what a rebind does): the fingerprint notices.
  MatrixXd W = t.W;
  CHECK(fast.solve(rig, t.mesh.V, t.mesh.F, W, states, 1, params).precomputed);  // another matrix: rebuilt
  CHECK(!fast.solve(rig, t.mesh.V, t.mesh.F, W, states, 1, params).precomputed);
  W = hat_weights(t.mesh.V * 1.1, 4.0);
  CHECK(fast.solve(rig, t.mesh.V, t.mesh.F, W, states, 1, params).precomputed);
}
