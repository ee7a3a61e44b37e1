// Keyframes, rotation-aware interpolation and baking (core/anim).
#include <cmath>

#include <catch2/catch.hpp>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "core/anim/bake.h"
#include "core/anim/interpolate.h"
#include "core/anim/keyframes.h"
#include "core/util/error.h"
#include "tests/test_support.h"

using namespace dfm;

namespace {
Pose one(const Eigen::Affine3d& a) {
  Pose p;
  p.transforms.push_back(a);
  return p;
}
Eigen::Affine3d rot_z(double deg) {
  return Eigen::Affine3d(Eigen::AngleAxisd(deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
}
}  // namespace

TEST_CASE("key track keeps keys sorted, replaces equal times, locates intervals", "[anim]") {
  KeyTrack track;
  track.set({2.0, identity_pose(2)});
  track.set({0.0, identity_pose(2)});
  track.set({1.0, identity_pose(2)});
  REQUIRE(track.size() == 3);
  REQUIRE(track.keys()[0].time == 0.0);
  REQUIRE(track.keys()[2].time == 2.0);
  Pose moved = identity_pose(2);
  moved.transforms[1].translation() << 1, 2, 3;
  track.set({1.0, moved});
  REQUIRE(track.size() == 3);
  REQUIRE(track.keys()[1].pose.transforms[1].translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  REQUIRE_THROWS_AS(track.set({3.0, identity_pose(3)}), Error);
  REQUIRE_THROWS_AS(track.set({NAN, identity_pose(2)}), Error);

  auto at = track.locate(1.5);
  REQUIRE(at.interval == 1);
  REQUIRE(at.u == Approx(0.5));
  at = track.locate(-4);
  REQUIRE((at.interval == 0 && at.u == 0.0));
  at = track.locate(9);
  REQUIRE((at.interval == 1 && at.u == 1.0));
  at = track.locate(1.0);  // exactly on a key
  REQUIRE(((at.interval == 1 && at.u == 0.0) || (at.interval == 0 && at.u == 1.0)));
  REQUIRE(track.remove(1.0));
  REQUIRE_FALSE(track.remove(1.0));
  REQUIRE(track.size() == 2);
  REQUIRE_THROWS_AS(KeyTrack().locate(0), Error);
}

TEST_CASE("polar decomposition A = R S", "[anim]") {
  std::srand(7);
  for (int trial = 0; trial < 50; ++trial) {
    Eigen::Matrix3d A = Eigen::Matrix3d::Random();
    if (A.determinant() < 0) A.col(0) *= -1;
    const PolarDecomposition pd = polar_decompose(A);
    REQUIRE((pd.R * pd.R.transpose()).isApprox(Eigen::Matrix3d::Identity(), 1e-12));
    REQUIRE(pd.R.determinant() == Approx(1.0));
    REQUIRE((pd.S - pd.S.transpose()).norm() == 0.0);
    REQUIRE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(pd.S).eigenvalues().minCoeff() > 0);
    REQUIRE((pd.R * pd.S).isApprox(A, 1e-12));
  }
  Eigen::Matrix3d mirror = Eigen::Matrix3d::Identity();
  mirror(0, 0) = -1;
  REQUIRE_THROWS_AS(polar_decompose(mirror), Error);
  REQUIRE_THROWS_AS(polar_decompose(Eigen::Matrix3d::Zero()), Error);
}

TEST_CASE("interpolation slerps rotations and blends stretch and translation linearly", "[anim]") {
  // Identity -> 170 degrees about z: half way is exactly 85 degrees (a matrix blend would shrink).
  Eigen::Affine3d a = Eigen::Affine3d::Identity(), b = rot_z(170);
  a.translation() << 0, 0, 0;
  b.translation() << 4, -2, 6;
  const Eigen::Affine3d h = interpolate_affine(a, b, 0.5);
  REQUIRE(h.linear().isApprox(rot_z(85).linear(), 1e-12));
  REQUIRE(h.translation().isApprox(Eigen::Vector3d(2, -1, 3), 1e-12));
  REQUIRE(interpolate_affine(a, b, 0.25).linear().isApprox(rot_z(42.5).linear(), 1e-12));
  // Endpoints reproduce the keys.
  REQUIRE(interpolate_affine(a, b, 0.0).matrix().isApprox(a.matrix(), 1e-12));
  REQUIRE(interpolate_affine(a, b, 1.0).matrix().isApprox(b.matrix(), 1e-12));
  // Stretch: uniform scale 1 -> 3 gives 2 half way; combined with a rotation R(u) S(u).
  Eigen::Affine3d s3 = rot_z(90);
  s3.linear() *= 3.0;
  const Eigen::Affine3d hs = interpolate_affine(Eigen::Affine3d::Identity(), s3, 0.5);
  REQUIRE(hs.linear().isApprox(2.0 * rot_z(45).linear(), 1e-12));
  // Non-uniform stretch along x blends its eigenvalue linearly.
  Eigen::Affine3d sx = Eigen::Affine3d::Identity();
  sx.linear()(0, 0) = 5.0;
  REQUIRE(interpolate_affine(Eigen::Affine3d::Identity(), sx, 0.75).linear()(0, 0) == Approx(4.0));
  // Reflections are reported, not blended.
  Eigen::Affine3d m = Eigen::Affine3d::Identity();
  m.linear()(1, 1) = -1;
  REQUIRE_THROWS_AS(interpolate_affine(a, m, 0.5), Error);
  REQUIRE_THROWS_AS(interpolate_pose(one(a), identity_pose(2), 0.5), Error);
}

TEST_CASE("sampling a track returns keys exactly and refuses reflections", "[anim]") {
  KeyTrack track;
  Eigen::Affine3d k1 = rot_z(120);
  k1.translation() << 1, 1, 1;
  track.set({0.0, one(Eigen::Affine3d::Identity())});
  track.set({2.0, one(k1)});
  REQUIRE(sample_track(track, 2.0).transforms[0].matrix() == k1.matrix());
  REQUIRE(sample_track(track, 7.0).transforms[0].matrix() == k1.matrix());
  REQUIRE(sample_track(track, 1.0).transforms[0].linear().isApprox(rot_z(60).linear(), 1e-12));
  Eigen::Affine3d mirror = Eigen::Affine3d::Identity();
  mirror.linear()(2, 2) = -1;
  track.set({3.0, one(mirror)});
  REQUIRE_THROWS_WITH(sample_track(track, 2.5), Catch::Contains("determinant"));
  REQUIRE_THROWS_AS(sample_track(track, 3.0), Error);
}

TEST_CASE("baking samples every key and the in-betweens", "[anim]") {
  KeyTrack track;
  Eigen::Affine3d k1 = Eigen::Affine3d::Identity(), k2 = rot_z(90);
  k1.translation() << 3, 0, 0;
  track.set({0.0, one(Eigen::Affine3d::Identity())});
  track.set({1.0, one(k1)});
  track.set({3.0, one(k2)});
  const auto times = bake_times(track, 2);
  const std::vector<double> expect = {0, 1.0 / 3, 2.0 / 3, 1, 5.0 / 3, 7.0 / 3, 3};
  REQUIRE(times.size() == expect.size());
  for (size_t i = 0; i < times.size(); ++i) REQUIRE(times[i] == Approx(expect[i]));
  REQUIRE(bake_times(track, 0) == std::vector<double>{0, 1, 3});
  REQUIRE_THROWS_AS(bake_times(track, -1), Error);

  Eigen::MatrixXd rest(2, 3);
  rest << 1, 0, 0, 0, 2, 0;
  auto skin = [&](const Pose& p) {
    Eigen::MatrixXd out(rest.rows(), 3);
    for (int i = 0; i < rest.rows(); ++i) out.row(i) = (p.transforms[0] * Eigen::Vector3d(rest.row(i).transpose())).transpose();
    return out;
  };
  int calls = 0;
  const BakedLayers L = bake_layers(track, 2, skin, [&](int done, int total) {
    ++calls;
    REQUIRE(total == 7);
    return true;
  });
  REQUIRE(calls == 7);
  REQUIRE(L.positions.size() == 7);
  REQUIRE(L.positions[3].row(0).isApprox(Eigen::RowVector3d(4, 0, 0)));    // key 1: translated
  REQUIRE(L.positions[1].row(1).isApprox(Eigen::RowVector3d(1, 2, 0)));    // 1/3 of the way
  // Between translation (3,0,0) and a 90-degree turn: half-way rotation is 45 degrees, the
  // translation half of (3,0,0).
  const Eigen::Vector3d mid = rot_z(45) * Eigen::Vector3d(1, 0, 0) + Eigen::Vector3d(1.5, 0, 0);
  const BakedLayers L1 = bake_layers(track, 1, skin);
  REQUIRE(L1.times[3] == Approx(2.0));
  REQUIRE(L1.positions[3].row(0).transpose().isApprox(mid, 1e-12));
  REQUIRE_THROWS_WITH(bake_layers(track, 1, skin, [](int d, int) { return d < 2; }), Catch::Contains("cancel"));
  int n = 0;
  auto bad_skin = [&](const Pose&) { return Eigen::MatrixXd::Zero(++n, 3).eval(); };
  REQUIRE_THROWS_AS(bake_layers(track, 0, bad_skin), Error);
}

// Between keys a bone turns about its own first joint and its child stays on its end (issue 38, 3): the
// keys' parameters are interpolated, then forward kinematics places the bones. Interpolating the
// evaluated transforms instead blends the translation part linearly and slides the joint.
TEST_CASE("a bake stopped by its progress callback throws Cancelled; a failure is not one", "[anim]") {
  KeyTrack track;
  track.set({0.0, one(Eigen::Affine3d::Identity())});
  track.set({1.0, one(rot_z(90))});
  const auto skin = [](const Pose& p) { return Eigen::MatrixXd(p.transforms[0].translation().transpose()); };
  REQUIRE_THROWS_AS(bake_layers(track, 3, skin, [](int done, int) { return done < 2; }), Cancelled);
  int n = 0;
  const auto bad_skin = [&](const Pose&) { return Eigen::MatrixXd::Zero(++n, 3).eval(); };
  CHECK(test::thrown_kind([&] { bake_layers(track, 3, bad_skin); }) == "error");
}

TEST_CASE("pose parameters interpolate in each handle's own frame: joints stay joined", "[anim]") {
  Rig rig;
  rig.skeleton.joints.resize(3, 3);
  rig.skeleton.joints << 1, 0, 0,  //
      2, 0, 0,                    //
      3, 0, 0;
  rig.skeleton.bones = {{0, 1, -1, "upper"}, {1, 2, 0, "lower"}};
  rig.points.push_back({Eigen::Vector3d(0, 2, 0), "p"});
  const PoseParams a = rest_pose_params(rig);
  PoseParams b = a;
  b.bone_rotation[0] = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  b.point_rotation[0] = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()));
  b.point_translation[0] = Eigen::Vector3d(0, 0, 1);
  const PoseParams mid = interpolate_pose_params(rig, a, b, 0.5);
  CHECK(mid.bone_rotation[0].angularDistance(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitZ()))) <
        1e-12);
  CHECK((mid.point_translation[0] - Eigen::Vector3d(0, 0, 0.5)).norm() < 1e-15);
  const Pose p = evaluate_pose(rig, mid);
  // Point handle 0: turned 45 degrees about x about itself, moved half way.
  const Eigen::Vector3d q(0, 2, 0), x = q + Eigen::Vector3d(0, 1, 0);
  CHECK((p.transforms[0] * q - Eigen::Vector3d(0, 2, 0.5)).norm() < 1e-12);
  CHECK((p.transforms[0] * x - Eigen::Vector3d(0, 2 + std::sqrt(0.5), 0.5 + std::sqrt(0.5))).norm() < 1e-12);
  // Both bones turned 45 degrees about z through joint (1, 0, 0): the joint stays, the elbow and tip move
  // on the circle.
  const double c = std::sqrt(0.5);
  for (int bone : {1, 2}) {
    const Eigen::Affine3d& T = p.transforms[bone];
    CHECK((T * Eigen::Vector3d(1, 0, 0) - Eigen::Vector3d(1, 0, 0)).norm() < 1e-12);
    CHECK((T * Eigen::Vector3d(2, 0, 0) - Eigen::Vector3d(1 + c, c, 0)).norm() < 1e-12);
    CHECK((T * Eigen::Vector3d(3, 0, 0) - Eigen::Vector3d(1 + 2 * c, 2 * c, 0)).norm() < 1e-12);
  }
  // The evaluated transforms blended instead: R45 j + (j - R90 j) / 2 leaves the joint j = (1, 0, 0)
  // by 1 - cos 45 degrees = 0.29.
  const Pose blended = interpolate_pose(evaluate_pose(rig, a), evaluate_pose(rig, b), 0.5);
  CHECK((blended.transforms[1] * Eigen::Vector3d(1, 0, 0) - Eigen::Vector3d(1, 0, 0)).norm() ==
        Approx(1 - c).epsilon(1e-9));
  // The ends are the keys, and mismatched parameters are refused.
  CHECK(interpolate_pose_params(rig, a, b, 1.0).bone_rotation[0].angularDistance(b.bone_rotation[0]) < 1e-15);
  PoseParams bad = b;
  bad.bone_rotation.pop_back();
  CHECK_THROWS_WITH(interpolate_pose_params(rig, a, bad, 0.5), Catch::Contains("bone rotations"));
}
