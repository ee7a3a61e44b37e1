// CPU skinning references: LBS, DQS, STBS and k-influence truncation, against independent checks.
#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "core/rig/forward_kinematics.h"
#include "core/rig/pose_params.h"
#include "core/skin/skin.h"
#include "core/util/error.h"

using namespace dfm;
using Eigen::MatrixXd;
using Eigen::Vector3d;

static const double kPi = 3.14159265358979323846;

// Random points and random rows of positive weights summing to one (a few zero entries too).
static MatrixXd random_points(int n, unsigned seed) {
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  MatrixXd V(n, 3);
  for (int i = 0; i < n; ++i) V.row(i) << u(g), u(g), u(g);
  return V;
}
static MatrixXd random_weights(int n, int h, unsigned seed) {
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> u(0, 1);
  MatrixXd W(n, h);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < h; ++j) W(i, j) = u(g) < 0.3 ? 0.0 : u(g);
    if (W.row(i).sum() == 0) W(i, i % h) = 1;
    W.row(i) /= W.row(i).sum();
  }
  return W;
}
static Eigen::Affine3d random_rigid(std::mt19937& g) {
  std::normal_distribution<double> n(0, 1);
  Eigen::Quaterniond q(n(g), n(g), n(g), n(g));
  q.normalize();
  return Eigen::Translation3d(n(g), n(g), n(g)) * q;
}
static Pose random_rigid_pose(int h, unsigned seed) {
  std::mt19937 g(seed);
  Pose p;
  for (int j = 0; j < h; ++j) p.transforms.push_back(random_rigid(g));
  return p;
}

// A rig of `h` bones, each a separate segment: enough for per-handle STBS data.
static Rig bones_rig(int h) {
  Rig r;
  r.skeleton.joints.resize(2 * h, 3);
  for (int j = 0; j < h; ++j) {
    r.skeleton.joints.row(2 * j) << -1, 0.1 * j, 0;
    r.skeleton.joints.row(2 * j + 1) << 1, 0.1 * j, 0;
    r.skeleton.bones.push_back({2 * j, 2 * j + 1});
  }
  compute_bone_parents(r.skeleton);
  return r;
}

TEST_CASE("influences: k largest, sorted, renormalized; dense round trip", "[skin][influences]") {
  MatrixXd W(2, 4);
  W << 0.1, 0.4, 0.2, 0.3, 0.25, 0.25, 0.5, 0.0;
  Influences inf = top_influences(W, 2);
  REQUIRE(inf.k() == 2);
  REQUIRE(inf.index(0, 0) == 1);
  REQUIRE(inf.index(0, 1) == 3);
  REQUIRE(inf.weight(0, 0) == Approx(4.0 / 7));
  REQUIRE(inf.index(1, 0) == 2);
  REQUIRE(inf.index(1, 1) == 0);  // tie 0.25 / 0.25: lower handle first
  REQUIRE(inf.weight.rowwise().sum().isApprox(Eigen::VectorXd::Ones(2)));
  // k > #handles pads with zero weights; all_influences keeps everything unchanged.
  inf = top_influences(W, 6, false);
  REQUIRE(inf.k() == 6);
  REQUIRE(inf.weight(0, 5) == 0);
  REQUIRE(influences_to_dense(all_influences(W), 4) == W);
  REQUIRE(influences_to_dense(inf, 4) == W);
  REQUIRE_THROWS_AS(top_influences(W, 0), Error);
}

TEST_CASE("sparse influences: every nonzero weight in rows, largest first (the GPU layout)", "[skin][influences]") {
  MatrixXd W(4, 5);
  W << 0.1, 0.0, 0.6, 0.0, 0.3,  // 3 nonzeros
      0.0, 0.0, 0.0, 0.0, 0.0,   // none: an empty row
      0.2, 0.2, 0.2, 0.2, 0.2,   // all 5
      0.0, 0.0, 0.0, -0.1, 1.1;  // a negative weight is kept
  MatrixXd E = MatrixXd::Zero(4, 5);
  E(0, 0) = 0.5;  // endpoint weight of vertex 0's largest influence (handle 2)
  const Influences inf = all_influences(W);
  const SparseInfluences s = sparse_influences(inf, E);
  REQUIRE(s.offsets == std::vector<int>{0, 3, 3, 8, 10});
  REQUIRE(s.num_entries() == 10);
  REQUIRE(s.max_row == 5);
  REQUIRE(s.handle[0] == 2);
  REQUIRE(s.weight[0] == 0.6);
  REQUIRE(s.endpoint[0] == 0.5);
  REQUIRE(s.handle[1] == 4);
  REQUIRE(s.handle[2] == 0);
  REQUIRE(s.handle[8] == 4);
  REQUIRE(s.weight[9] == -0.1);
  // Back to dense: exactly W.
  MatrixXd D = MatrixXd::Zero(4, 5);
  for (int i = 0; i < 4; ++i)
    for (int e = s.offsets[i]; e < s.offsets[i + 1]; ++e) D(i, s.handle[e]) += s.weight[e];
  REQUIRE(D == W);
  // A k-truncation's sparse rows hold at most k.
  REQUIRE(sparse_influences(top_influences(W, 2)).max_row == 2);
  REQUIRE(sparse_influences(inf).endpoint == std::vector<double>(10, 0.0));
  REQUIRE_THROWS_AS(sparse_influences(inf, MatrixXd::Zero(4, 2)), Error);
}

TEST_CASE("LBS: identity pose reproduces the rest mesh", "[skin][lbs]") {
  const MatrixXd V = random_points(500, 1), W = random_weights(500, 7, 2);
  const MatrixXd U = lbs(V, W, identity_pose(7));
  REQUIRE((U - V).cwiseAbs().maxCoeff() <= 4 * std::numeric_limits<double>::epsilon());
}

TEST_CASE("LBS equals libigl's dense formulation U = M T", "[skin][lbs]") {
  const MatrixXd V = random_points(300, 3), W = random_weights(300, 6, 4);
  Pose pose = random_rigid_pose(6, 5);
  pose.transforms[2].linear() *= Eigen::Vector3d(1.5, 0.5, 2.0).asDiagonal();  // non-rigid handle too
  const MatrixXd dense = lbs_matrix(V, W) * pose_matrix(pose);
  REQUIRE((lbs(V, W, pose) - dense).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("partition of unity: one affine on every handle moves the mesh by it", "[skin]") {
  const int h = 5;
  const MatrixXd V = random_points(400, 6), W = random_weights(400, h, 7);
  const Rig rig = bones_rig(h);
  std::mt19937 g(8);
  Eigen::Affine3d A = random_rigid(g);
  A.linear() = A.linear() * (Eigen::Matrix3d() << 1.3, 0.2, 0, 0, 0.7, 0.1, 0.3, 0, 1.1).finished();  // shear, scale
  Pose pose;
  pose.transforms.assign(h, A);
  const SkinBinding b = make_skin_binding(V, MatrixXd(), W, rig, 0);
  const MatrixXd expected = ((A.linear() * V.transpose()).colwise() + A.translation()).transpose();
  for (SkinMethod m : {SkinMethod::LBS, SkinMethod::DQS, SkinMethod::STBS}) {
    INFO(skin_method_name(m));
    REQUIRE((skin(m, b, pose).V - expected).cwiseAbs().maxCoeff() < 1e-12);
  }
}

TEST_CASE("DQS: identity pose is exact; a rigid pose moves every vertex rigidly", "[skin][dqs]") {
  const int h = 6;
  const MatrixXd W = random_weights(50, h, 9);
  // Each vertex i gets a little tetrahedron of 4 points sharing its weight row: under a per-vertex
  // rigid motion their pairwise distances survive; under LBS they do not.
  const MatrixXd C = random_points(50, 10);
  MatrixXd V(200, 3), W4(200, h);
  const Vector3d off[4] = {{0, 0, 0}, {0.1, 0, 0}, {0, 0.1, 0}, {0, 0, 0.1}};
  for (int i = 0; i < 50; ++i)
    for (int c = 0; c < 4; ++c) {
      V.row(4 * i + c) = C.row(i) + off[c].transpose();
      W4.row(4 * i + c) = W.row(i);
    }
  MatrixXd U;
  dqs(V, MatrixXd(), all_influences(W4), identity_pose(h), U);
  REQUIRE(U == V);
  const Pose pose = random_rigid_pose(h, 11);
  dqs(V, MatrixXd(), all_influences(W4), pose, U);
  const MatrixXd L = lbs(V, W4, pose);
  double dqs_err = 0, lbs_err = 0;
  for (int i = 0; i < 50; ++i)
    for (int a = 0; a < 4; ++a)
      for (int c = a + 1; c < 4; ++c) {
        const double rest = (V.row(4 * i + a) - V.row(4 * i + c)).norm();
        dqs_err = std::max(dqs_err, std::abs((U.row(4 * i + a) - U.row(4 * i + c)).norm() - rest));
        lbs_err = std::max(lbs_err, std::abs((L.row(4 * i + a) - L.row(4 * i + c)).norm() - rest));
      }
  REQUIRE(dqs_err < 1e-12);
  REQUIRE(lbs_err > 1e-3);  // the check itself can fail
}

TEST_CASE("DQS: hemisphere sign fix blends +179 and -179 degrees into 180", "[skin][dqs]") {
  MatrixXd V(1, 3), W(1, 2);
  V << 1, 0, 0;
  W << 0.5, 0.5;
  Pose pose;
  pose.transforms.push_back(Eigen::Affine3d(Eigen::AngleAxisd(kPi * 179 / 180, Vector3d::UnitZ())));
  pose.transforms.push_back(Eigen::Affine3d(Eigen::AngleAxisd(-kPi * 179 / 180, Vector3d::UnitZ())));
  MatrixXd U;
  dqs(V, MatrixXd(), all_influences(W), pose, U);
  REQUIRE((U.row(0) - Eigen::RowVector3d(-1, 0, 0)).norm() < 1e-12);
}

TEST_CASE("normals: cofactor transform matches the normals of the skinned mesh", "[skin]") {
  // A tetrahedron under one non-uniform affine: per-vertex area-weighted normals of the deformed
  // mesh are exactly the cofactor-transformed rest normals.
  MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  Eigen::MatrixXi F(4, 3);
  F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  const MatrixXd N = vertex_normals(V, F);
  Eigen::Affine3d A = Eigen::Affine3d::Identity();
  A.linear() << 2, 0.5, 0, 0, 0.5, 0, 0.2, 0, 1;
  A.translation() << 1, 2, 3;
  Pose pose;
  pose.transforms = {A, A};
  MatrixXd W(4, 2);
  W << 0.5, 0.5, 1, 0, 0, 1, 0.2, 0.8;
  const Rig rig = bones_rig(2);
  const SkinBinding b = make_skin_binding(V, N, W, rig, 0);
  for (SkinMethod m : {SkinMethod::LBS, SkinMethod::DQS, SkinMethod::STBS}) {
    INFO(skin_method_name(m));
    const SkinResult r = skin(m, b, pose);
    REQUIRE((r.N - vertex_normals(r.V, F)).cwiseAbs().maxCoeff() < 1e-12);
  }
}

TEST_CASE("STBS: zero twist and unit stretch is LBS exactly, normals included", "[skin][stbs]") {
  const int h = 4;
  const MatrixXd V = random_points(300, 12), W = random_weights(300, h, 13);
  const Rig rig = bones_rig(h);
  const SkinBinding b = make_skin_binding(V, random_points(300, 14).rowwise().normalized(), W, rig, 0);
  const Pose pose = random_rigid_pose(h, 15);
  const SkinResult l = skin(SkinMethod::LBS, b, pose);
  const SkinResult s = skin(SkinMethod::STBS, b, pose, stbs_handles(rig, std::vector<BoneTwistStretch>(h)));
  REQUIRE(s.V == l.V);
  REQUIRE(s.N == l.N);
}

TEST_CASE("STBS: twist grows from 0 at the first joint to full at the second; stretch likewise", "[skin][stbs]") {
  Rig rig = bones_rig(1);  // bone from (-1,0,0) to (1,0,0)
  MatrixXd V(5, 3);
  V << -1, 1, 0,  // e = 0
      0, 1, 0,    // t = 0.5 -> e = 0.5
      1, 1, 0,    // e = 1
      2, 1, 0,    // beyond the end: e = 1
      0.5, 0, 1;  // t = 0.75 -> e = 0.84375
  const MatrixXd W = MatrixXd::Ones(5, 1);
  const SkinBinding b = make_skin_binding(V, MatrixXd(), W, rig, 0);
  PoseParams p = rest_pose_params(rig);
  p.bone_twist_stretch[0] = {kPi / 2, 1.5};
  const Pose pose = evaluate_pose(rig, p);
  const SkinResult r = skin(SkinMethod::STBS, b, pose, stbs_handles(rig, p.bone_twist_stretch));
  const double e3 = 0.75 * 0.75 * (3 - 1.5);
  const auto expect = [&](double e, Vector3d q) {  // twist e*90 degrees about +x, shift 1.0*e along x
    return Vector3d(q.x() + e * 1.0, std::cos(e * kPi / 2) * q.y() - std::sin(e * kPi / 2) * q.z(),
                    std::sin(e * kPi / 2) * q.y() + std::cos(e * kPi / 2) * q.z());
  };
  REQUIRE((r.V.row(0).transpose() - expect(0, {-1, 1, 0})).norm() < 1e-12);
  REQUIRE((r.V.row(1).transpose() - expect(0.5, {0, 1, 0})).norm() < 1e-12);
  REQUIRE((r.V.row(2).transpose() - expect(1, {1, 1, 0})).norm() < 1e-12);
  REQUIRE((r.V.row(3).transpose() - expect(1, {2, 1, 0})).norm() < 1e-12);
  REQUIRE((r.V.row(4).transpose() - expect(e3, {0.5, 0, 1})).norm() < 1e-12);
  // LBS with the same pose twists and scales everything rigidly with the bone instead.
  const SkinResult l = skin(SkinMethod::LBS, b, pose);
  REQUIRE((l.V.row(0).transpose() - Vector3d(-1, 0, 1)).norm() < 1e-12);
}

TEST_CASE("STBS: a twist at the first joint turns the skin by (1 - e) theta_a + e theta_b (Eq. 6.5), over LBS and DQS",
          "[skin][stbs]") {
  Rig rig = bones_rig(1);  // bone from (-1,0,0) to (1,0,0)
  MatrixXd V(4, 3);
  V << -1, 1, 0,  // e = 0
      0, 1, 0,    // e = 0.5
      1, 0, 1,    // e = 1
      0.5, 0, 1;  // t = 0.75 -> e = 0.84375
  const SkinBinding b = make_skin_binding(V, MatrixXd(), MatrixXd::Ones(4, 1), rig, 0);
  PoseParams p = rest_pose_params(rig);
  const double ta = -kPi / 3, tb = kPi / 2;
  p.bone_twist_stretch[0] = {tb, 1.0, ta};
  const Pose pose = evaluate_pose(rig, p);
  const double es[4] = {0, 0.5, 1, 0.75 * 0.75 * (3 - 1.5)};
  for (SkinMethod m : {SkinMethod::STBS, SkinMethod::STBS_DQS}) {
    const SkinResult r = skin(m, b, pose, stbs_handles(rig, p.bone_twist_stretch));
    for (int i = 0; i < 4; ++i) {
      const double a = (1 - es[i]) * ta + es[i] * tb;  // about +x, the bone's axis; the bone itself stays
      const Vector3d q = V.row(i).transpose();
      const Vector3d expect(q.x(), std::cos(a) * q.y() - std::sin(a) * q.z(), std::sin(a) * q.y() + std::cos(a) * q.z());
      INFO(skin_method_name(m) << " vertex " << i);
      CHECK((r.V.row(i).transpose() - expect).norm() < 1e-12);
    }
  }
  // The twist at the first joint alone makes the bone active; LBS and the bone's frame ignore it.
  p.bone_twist_stretch[0] = {0.0, 1.0, ta};
  CHECK(stbs_handles(rig, p.bone_twist_stretch)[0].active);
  CHECK((skin(SkinMethod::LBS, b, evaluate_pose(rig, p)).V - V).norm() == 0);
}

TEST_CASE("truncation error: zero with every weight, positive with fewer", "[skin][influences]") {
  const int h = 6;
  const MatrixXd V = random_points(200, 16), W = random_weights(200, h, 17);
  const Rig rig = bones_rig(h);
  const Pose pose = random_rigid_pose(h, 18);
  const SkinBinding full = make_skin_binding(V, MatrixXd(), W, rig, 0);
  REQUIRE(truncation_error(SkinMethod::LBS, full, make_skin_binding(V, MatrixXd(), W, rig, h), pose) < 1e-12);
  const double e2 = truncation_error(SkinMethod::LBS, full, make_skin_binding(V, MatrixXd(), W, rig, 2), pose);
  const double e4 = truncation_error(SkinMethod::LBS, full, make_skin_binding(V, MatrixXd(), W, rig, 4), pose);
  REQUIRE(e2 > 1e-3);
  REQUIRE(e4 < e2);
  // Independent check at one vertex: renormalized top-2 weights by hand.
  const MatrixXd W2 = influences_to_dense(top_influences(W, 2), h);
  REQUIRE((lbs(V, W2, pose) - lbs(V, W, pose)).rowwise().norm().maxCoeff() == Approx(e2).epsilon(1e-12));
}

TEST_CASE("bad input: sizes and unknown method are errors", "[skin]") {
  const Rig rig = bones_rig(2);
  REQUIRE_THROWS_AS(make_skin_binding(random_points(3, 1), MatrixXd(), MatrixXd::Ones(3, 3), rig, 0), Error);
  REQUIRE_THROWS_AS(make_skin_binding(random_points(3, 1), MatrixXd(), MatrixXd::Ones(2, 2), rig, 0), Error);
  const SkinBinding b = make_skin_binding(random_points(3, 1), MatrixXd(), MatrixXd::Ones(3, 2) / 2, rig, 0);
  REQUIRE_THROWS_AS(skin(SkinMethod::LBS, b, identity_pose(1)), Error);
  REQUIRE_THROWS_AS(parse_skin_method("nope"), Error);
  REQUIRE(parse_skin_method("DQS") == SkinMethod::DQS);
}
