// Forward kinematics, pseudo-edge rotations, pose parameters and pose files.
#include <cmath>
#include <filesystem>

#include <unistd.h>

#include <catch2/catch.hpp>

#include "core/mesh/io.h"
#include "core/rig/forward_kinematics.h"
#include "core/rig/pose_io.h"
#include "core/rig/pose_params.h"
#include "core/rig/pseudo_edges.h"
#include "core/rig/rig_io.h"
#include "core/util/error.h"
#include "tests/test_support.h"

using namespace dfm;
using Eigen::Vector3d;

static const double kPi = 3.14159265358979323846;

static Eigen::Quaterniond rot_z(double angle) { return Eigen::Quaterniond(Eigen::AngleAxisd(angle, Vector3d::UnitZ())); }

// Joints 0 -- 1 -- 2 along x at 0, 1, 2; bone 0 = (0,1), bone 1 = (1,2).
static Skeleton chain() {
  Skeleton s;
  s.joints.resize(3, 3);
  s.joints << 0, 0, 0, 1, 0, 0, 2, 0, 0;
  s.bones = {{0, 1}, {1, 2}};
  compute_bone_parents(s);
  return s;
}

static void require_near(const Vector3d& a, const Vector3d& b, double tol = 1e-12) {
  INFO("got " << a.transpose() << " expected " << b.transpose());
  REQUIRE((a - b).norm() < tol);
}

TEST_CASE("FK: rest rotations give identity transforms", "[pose][fk]") {
  auto T = forward_kinematics(chain(), {});
  REQUIRE(T.size() == 2);
  for (auto& t : T) REQUIRE(t.matrix().isIdentity(0));
}

TEST_CASE("FK: a bone rotates about its first joint and carries its children", "[pose][fk]") {
  const Skeleton s = chain();
  auto T = forward_kinematics(s, {rot_z(kPi / 2), Eigen::Quaterniond::Identity()});
  require_near(T[0] * Vector3d(0, 0, 0), Vector3d(0, 0, 0));  // first joint is fixed
  require_near(T[0] * Vector3d(1, 0, 0), Vector3d(0, 1, 0));
  require_near(T[1] * Vector3d(2, 0, 0), Vector3d(0, 2, 0));  // child follows rigidly
  // Child rotation relative to the parent: 90 more degrees about its own first joint (1,0,0).
  T = forward_kinematics(s, {rot_z(kPi / 2), rot_z(kPi / 2)});
  require_near(T[1] * Vector3d(1, 0, 0), Vector3d(0, 1, 0));    // joint 1 where the parent put it
  require_near(T[1] * Vector3d(2, 0, 0), Vector3d(-1, 1, 0));   // (2,0,0) -> (1,1,0) -> (-1,1,0)
  // Only the child rotates: the parent stays.
  T = forward_kinematics(s, {Eigen::Quaterniond::Identity(), rot_z(-kPi / 2)});
  REQUIRE(T[0].matrix().isIdentity(1e-15));
  require_near(T[1] * Vector3d(2, 0, 0), Vector3d(1, -1, 0));
  const Eigen::MatrixXd J = posed_joints(s, T);
  require_near(J.row(2).transpose(), Vector3d(1, -1, 0));
  require_near(J.row(1).transpose(), Vector3d(1, 0, 0));
}

TEST_CASE("FK: translating the root moves the whole chain", "[pose][fk]") {
  const Skeleton s = chain();
  auto T = forward_kinematics(s, {rot_z(kPi / 2), rot_z(kPi / 2)}, {Vector3d(0, 0, 5)});
  require_near(T[0] * Vector3d(1, 0, 0), Vector3d(0, 1, 5));
  require_near(T[1] * Vector3d(2, 0, 0), Vector3d(-1, 1, 5));
}

TEST_CASE("FK: children come after parents whatever the bone order", "[pose][fk]") {
  Skeleton s = chain();
  std::swap(s.bones[0], s.bones[1]);  // child listed first
  compute_bone_parents(s);
  REQUIRE(s.bones[0].parent == 1);
  auto T = forward_kinematics(s, {Eigen::Quaterniond::Identity(), rot_z(kPi / 2)});
  require_near(T[0] * Vector3d(2, 0, 0), Vector3d(0, 2, 0));
}

TEST_CASE("FK: twist and stretch act in the bone's rest frame; children follow", "[pose][fk]") {
  const Skeleton s = chain();
  std::vector<BoneTwistStretch> ts(2);
  ts[0].twist = kPi / 2;
  ts[0].stretch = 2.0;
  auto T = forward_kinematics(s, {}, {}, ts);
  require_near(T[0] * Vector3d(1, 0, 0), Vector3d(2, 0, 0));  // stretched to twice its length
  require_near(T[0] * Vector3d(0.5, 1, 0), Vector3d(1, 0, 1));  // twisted about +x, stretched along it
  require_near(T[1] * Vector3d(2, 0, 0), Vector3d(3, 0, 0));  // child moved to the new end
  require_near(T[1] * Vector3d(2, 1, 0), Vector3d(3, 0, 1));  // and twisted with it
  REQUIRE(twist_stretch_transform(Vector3d(0, 0, 0), Vector3d(1, 0, 0), BoneTwistStretch{}).matrix().isIdentity(0));
}

// Joints 0 -- 1 -- 2 along x, and two more roots starting at joint 0 (down and up): bone 0 = (0,1),
// bone 1 = (1,2) its child, bones 2 = (0,3) and 3 = (0,4) roots sharing bone 0's first joint.
static Skeleton chain_with_roots() {
  Skeleton s;
  s.joints.resize(5, 3);
  s.joints << 0, 0, 0, 1, 0, 0, 2, 0, 0, 0, -1, 0, 0, 1, 0;
  s.bones = {{0, 1}, {1, 2}, {0, 3}, {0, 4}};
  compute_bone_parents(s);
  return s;
}

TEST_CASE("bone attachments: the parent, else the first root at the same joint", "[pose][fk]") {
  const Skeleton s = chain_with_roots();
  CHECK(bone_attachments(s) == std::vector<int>{-1, 0, 0, 0});
  CHECK(bone_attachments(chain()) == std::vector<int>{-1, 0});
}

TEST_CASE("connect_bones: each bone shifts to where its attachment puts its first joint, linear parts kept",
          "[pose][fk]") {
  const Skeleton s = chain_with_roots();
  // Transforms as a solver or a stray translation may leave them: every bone somewhere else.
  std::vector<Eigen::Affine3d> T(4);
  T[0] = Eigen::Translation3d(0.5, 0.25, 0) * rot_z(kPi / 2);                  // root, moved and turned
  T[1] = Eigen::Translation3d(3, 3, 3) * Eigen::Scaling(1.5, 1.0, 1.0);        // detached, stretched
  T[2] = Eigen::Affine3d(Eigen::Translation3d(-1, 0, 0));                      // a root off its joint
  T[3] = Eigen::Affine3d(rot_z(0.3));
  const std::vector<Eigen::Affine3d> before = T;
  connect_bones(s, T);
  CHECK(T[0].matrix() == before[0].matrix());  // places its own joint: untouched
  // Bone 0 maps its rest end (1,0,0) to (0.5, 1.25, 0): bone 1 starts there.
  require_near(T[1] * Vector3d(1, 0, 0), Vector3d(0.5, 1.25, 0));
  // The roots at joint 0 start where bone 0 starts, (0.5, 0.25, 0).
  require_near(T[2] * Vector3d(0, 0, 0), Vector3d(0.5, 0.25, 0));
  require_near(T[3] * Vector3d(0, 0, 0), Vector3d(0.5, 0.25, 0));
  for (int b = 1; b < 4; ++b) CHECK(T[b].linear() == before[b].linear());
  // `only`: bones not flagged keep their transforms exactly.
  std::vector<Eigen::Affine3d> U = before;
  connect_bones(s, U, {0, 1, 0, 0});
  CHECK(U[2].matrix() == before[2].matrix());
  require_near(U[1] * Vector3d(1, 0, 0), Vector3d(0.5, 1.25, 0));
}

TEST_CASE("evaluate_pose: a bone with a parent never leaves its joint; plain FK is untouched bit for bit",
          "[pose][fk]") {
  Rig r;
  r.skeleton = chain_with_roots();
  PoseParams p = rest_pose_params(r);
  p.bone_rotation = {rot_z(0.4), rot_z(-0.7), rot_z(0.2), Eigen::Quaterniond::Identity()};
  // Pure rotations: exactly forward kinematics.
  const auto fk = forward_kinematics(r.skeleton, p.bone_rotation, p.bone_translation, p.bone_twist_stretch);
  Pose pose = evaluate_pose(r, p);
  for (int b = 0; b < 4; ++b) CHECK(pose.transforms[b].matrix() == fk[b].matrix());
  // A child's translation is projected out; a root's moves every bone at its joint with it.
  p.bone_translation[1] = Vector3d(0, 0.5, 0);
  p.bone_translation[0] = Vector3d(0, 0, 2);
  pose = evaluate_pose(r, p);
  const Eigen::Matrix3d R0 = rot_z(0.4).toRotationMatrix();
  const Vector3d elbow = Vector3d(0, 0, 2) + R0 * Vector3d(1, 0, 0);  // bone 0's end, by hand
  require_near(pose.transforms[0] * Vector3d(1, 0, 0), elbow);
  require_near(pose.transforms[1] * Vector3d(1, 0, 0), elbow);
  require_near(pose.transforms[1] * Vector3d(2, 0, 0), elbow + R0 * rot_z(-0.7).toRotationMatrix() * Vector3d(1, 0, 0));
  require_near(pose.transforms[2] * Vector3d(0, 0, 0), Vector3d(0, 0, 2));
  require_near(pose.transforms[3] * Vector3d(0, 0, 0), Vector3d(0, 0, 2));
  // A solved transform of a parent carries its children's starts along; the handle's own parameters
  // (evaluate_handle_parameters) do not.
  p = rest_pose_params(r);
  p.solved[0] = Eigen::Affine3d(Eigen::Translation3d(0, 1, 0));
  pose = evaluate_pose(r, p);
  require_near(pose.transforms[1] * Vector3d(1, 0, 0), Vector3d(1, 1, 0));
  require_near(pose.transforms[2] * Vector3d(0, 0, 0), Vector3d(0, 1, 0));
  CHECK(evaluate_handle_parameters(r, p).transforms[1].matrix().isIdentity(0));
}

TEST_CASE("FK: bad parent index is an error", "[pose][fk]") {
  Skeleton s = chain();
  s.bones[1].parent = 7;
  REQUIRE_THROWS_AS(forward_kinematics(s, {}), Error);
}

TEST_CASE("pseudo-edges: smallest rotation from rest to posed direction, averaged", "[pose][pseudo]") {
  Eigen::MatrixXd rest(3, 3), posed(3, 3);
  rest << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  posed = rest;
  posed.row(1) << 0, 1, 0;   // edge 0-1 turns 90 degrees about z
  posed.row(2) << -1, 0, 0;  // edge 0-2 turns 90 degrees about z too
  std::vector<bool> has;
  auto q = pseudo_edge_rotations(rest, posed, {{0, 1}}, &has);
  REQUIRE(has == std::vector<bool>{true, true, false});
  REQUIRE(q[0].angularDistance(rot_z(kPi / 2)) < 1e-12);
  REQUIRE(q[1].angularDistance(rot_z(kPi / 2)) < 1e-12);
  REQUIRE(q[2].angularDistance(Eigen::Quaterniond::Identity()) < 1e-12);
  // Two edges agreeing: the same rotation.
  q = pseudo_edge_rotations(rest, posed, {{0, 1}, {0, 2}});
  REQUIRE(q[0].angularDistance(rot_z(kPi / 2)) < 1e-12);
  // Edges disagreeing (90 and 0 degrees): the quaternion average is 45 degrees.
  posed.row(2) = rest.row(2);
  q = pseudo_edge_rotations(rest, posed, {{0, 1}, {0, 2}});
  REQUIRE(q[0].angularDistance(rot_z(kPi / 4)) < 1e-12);
  REQUIRE_THROWS_AS(pseudo_edge_rotations(rest, posed, {{0, 5}}), Error);
}

TEST_CASE("average_quaternions aligns hemispheres", "[pose][pseudo]") {
  Eigen::Quaterniond a = rot_z(0.2), b = rot_z(0.4);
  Eigen::Quaterniond nb(-b.w(), -b.x(), -b.y(), -b.z());  // the same rotation as b
  REQUIRE(average_quaternions({a, nb}).angularDistance(rot_z(0.3)) < 1e-12);
}

static Rig mixed_rig() {
  Rig r;
  r.points = {{Vector3d(0, 0, 0), "p0"}, {Vector3d(1, 0, 0), "p1"}, {Vector3d(5, 5, 5), "lonely"}};
  r.pseudo_edges = {{0, 1}};
  r.skeleton = chain();
  Cage c;
  c.mesh.V = Eigen::MatrixXd::Identity(3, 3);
  c.mesh.F = Eigen::MatrixXi(1, 3);
  c.mesh.F << 0, 1, 2;
  r.cages = {c};
  r.regions.resize(1);
  return r;
}

TEST_CASE("evaluate_pose: rest params give the identity for every handle", "[pose]") {
  Rig r = mixed_rig();
  PoseParams p = rest_pose_params(r);
  REQUIRE(p.bone_rotation.size() == 2);
  REQUIRE(p.point_translation.size() == 3);
  REQUIRE(p.cage_translation.size() == 3);
  Pose pose = evaluate_pose(r, p);
  REQUIRE(pose.size() == num_handles(r));
  for (auto& t : pose.transforms) REQUIRE(t.matrix().isIdentity(0));
  // Missing entries mean identity too.
  pose = evaluate_pose(r, PoseParams{});
  REQUIRE(pose.size() == num_handles(r));
  for (auto& t : pose.transforms) REQUIRE(t.matrix().isIdentity(0));
}

TEST_CASE("evaluate_pose: every handle kind in rig order", "[pose]") {
  Rig r = mixed_rig();
  PoseParams p = rest_pose_params(r);
  p.point_translation[1] = Vector3d(-1, 1, 0);  // p1 -> (0,1,0): pseudo-edge turns 90 about z
  p.point_translation[2] = Vector3d(1, 2, 3);
  p.point_rotation[2] = rot_z(kPi);             // no pseudo-edge: the explicit rotation, about the point
  p.point_rotation[0] = rot_z(1.0);             // ignored: point 0 has a pseudo-edge
  p.bone_rotation[0] = rot_z(kPi / 2);
  p.cage_translation[2] = Vector3d(0, 0, 7);
  Eigen::Affine3d region = Eigen::Affine3d::Identity();
  region.scale(2.0);
  p.region_transform[0] = region;
  Pose pose = evaluate_pose(r, p);
  REQUIRE(pose.size() == 3 + 2 + 3 + 1);
  require_near(pose.transforms[0] * Vector3d(0, 0, 0), Vector3d(0, 0, 0));
  require_near(pose.transforms[0] * Vector3d(1, 0, 0), Vector3d(0, 1, 0));
  require_near(pose.transforms[1] * Vector3d(1, 0, 0), Vector3d(0, 1, 0));
  require_near(pose.transforms[1] * Vector3d(2, 0, 0), Vector3d(0, 2, 0));
  require_near(pose.transforms[2] * Vector3d(5, 5, 5), Vector3d(6, 7, 8));
  require_near(pose.transforms[2] * Vector3d(6, 5, 5), Vector3d(5, 7, 8));
  require_near(pose.transforms[3] * Vector3d(1, 0, 0), Vector3d(0, 1, 0));
  require_near(pose.transforms[4] * Vector3d(2, 0, 0), Vector3d(0, 2, 0));
  require_near(pose.transforms[7] * Vector3d(1, 1, 1), Vector3d(1, 1, 8));
  require_near(pose.transforms[5] * Vector3d(1, 1, 1), Vector3d(1, 1, 1));
  require_near(pose.transforms[8] * Vector3d(1, 1, 1), Vector3d(2, 2, 2));
}

TEST_CASE("pose files: bone rotations and point translations round trip; bad files are errors", "[pose][io]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("dfm_test_pose_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::vector<Eigen::Quaterniond> q = {rot_z(0.3), Eigen::Quaterniond(Eigen::AngleAxisd(1.0, Vector3d(1, 2, 3).normalized()))};
  write_bone_rotations((dir / "q.dmat").string(), q);
  auto q2 = read_bone_rotations((dir / "q.dmat").string(), 2);
  for (int i = 0; i < 2; ++i) REQUIRE(q2[i].coeffs().isApprox(q[i].coeffs(), 1e-12));
  REQUIRE_THROWS_AS(read_bone_rotations((dir / "q.dmat").string(), 3), Error);
  write_dmat((dir / "z.dmat").string(), Eigen::MatrixXd::Zero(4, 1));
  REQUIRE_THROWS_AS(read_bone_rotations((dir / "z.dmat").string()), Error);
  write_dmat((dir / "bad.dmat").string(), Eigen::MatrixXd::Ones(5, 1));
  REQUIRE_THROWS_AS(read_bone_rotations((dir / "bad.dmat").string()), Error);
  std::vector<Vector3d> t = {Vector3d(1, 2, 3), Vector3d(-0.5, 0, 1e-3)};
  write_point_translations((dir / "p.txt").string(), t);
  auto t2 = read_point_translations((dir / "p.txt").string(), 2);
  REQUIRE((t2[1] - t[1]).norm() < 1e-12);
  REQUIRE_THROWS_AS(read_point_translations((dir / "p.txt").string(), 1), Error);
  fs::remove_all(dir);
}

TEST_CASE("hand-pose.dmat: 20 relative bone rotations posing hand.tgf", "[pose][data]") {
  DFM_DATA_OR_SKIP(tgf, "hand.tgf");
  DFM_DATA_OR_SKIP(qfile, "hand-pose.dmat");
  Rig rig;
  add_tgf_to_rig(rig, read_tgf(tgf), tgf);
  REQUIRE(rig.skeleton.num_bones() == 20);
  const auto q = read_bone_rotations(qfile, rig.skeleton.num_bones());
  // libigl's first coefficient order is (x, y, z, w): the first quaternion's w is 0.75297...
  REQUIRE(q[0].w() == Approx(0.75297704283434619).epsilon(1e-9));
  PoseParams p = rest_pose_params(rig);
  p.bone_rotation = q;
  const Pose pose = evaluate_pose(rig, p);
  const auto& s = rig.skeleton;
  // FK invariants: rigid transforms; each bone's first joint lands where its parent moved it.
  for (int b = 0; b < s.num_bones(); ++b) {
    const Eigen::Affine3d& T = pose.transforms[b];
    REQUIRE((T.linear().transpose() * T.linear() - Eigen::Matrix3d::Identity()).norm() < 1e-12);
    const Vector3d a = s.joints.row(s.bones[b].a).transpose();
    if (s.bones[b].parent >= 0) {
      require_near(T * a, pose.transforms[s.bones[b].parent] * a, 1e-12);
      // Its rotation relative to the parent is the file's.
      const Eigen::Matrix3d rel = pose.transforms[s.bones[b].parent].linear().transpose() * T.linear();
      REQUIRE((rel - q[b].toRotationMatrix()).norm() < 1e-12);
    } else {
      require_near(T * a, a, 1e-12);  // roots turn about their own first joint
    }
  }
}
