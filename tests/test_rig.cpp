#include <catch2/catch.hpp>

#include "core/rig/handle_deletion.h"
#include "core/rig/rig.h"
#include "core/util/error.h"

using namespace dfm;

static Rig sample_rig() {
  Rig r;
  r.points.resize(2);
  r.skeleton.joints = Eigen::MatrixXd::Zero(4, 3);
  r.skeleton.bones = {{0, 1}, {1, 2}, {1, 3}};
  compute_bone_parents(r.skeleton);
  Cage c;
  c.mesh.V = Eigen::MatrixXd::Zero(3, 3);
  c.mesh.F = Eigen::MatrixXi(1, 3);
  c.mesh.F << 0, 1, 2;
  r.cages = {c, c};
  r.regions.resize(1);
  return r;
}

TEST_CASE("handle order: points, bones, cage vertices, regions; round trip", "[rig]") {
  Rig r = sample_rig();
  REQUIRE(num_handles(r) == 2 + 3 + 6 + 1);
  REQUIRE(handle_ref(r, 1).kind == HandleKind::Point);
  REQUIRE(handle_ref(r, 2).kind == HandleKind::Bone);
  REQUIRE(handle_ref(r, 4).index == 2);
  HandleRef cv = handle_ref(r, 9);
  REQUIRE(cv.kind == HandleKind::CageVertex);
  REQUIRE(cv.cage == 1);
  REQUIRE(cv.index == 1);
  REQUIRE(handle_ref(r, 11).kind == HandleKind::Region);
  for (int h = 0; h < num_handles(r); ++h) REQUIRE(handle_index(r, handle_ref(r, h)) == h);
  REQUIRE_THROWS_AS(handle_ref(r, 12), Error);
}

TEST_CASE("bone parents follow shared joints; parents come first", "[rig]") {
  Rig r = sample_rig();
  REQUIRE(r.skeleton.bones[0].parent == -1);
  REQUIRE(r.skeleton.bones[1].parent == 0);
  REQUIRE(r.skeleton.bones[2].parent == 0);
  auto order = bones_topological_order(r.skeleton);
  REQUIRE(order.front() == 0);
  Skeleton cyc;
  cyc.joints = Eigen::MatrixXd::Zero(2, 3);
  cyc.bones = {{0, 1}, {1, 0}};
  REQUIRE_THROWS_AS(compute_bone_parents(cyc), Error);
}

namespace {
// Three points (a b c) with pseudo-edges, a 5-joint skeleton of 4 named bones, two 3-vertex cages,
// two regions; joint j sits at (j, 0, 0).
Rig deletion_rig() {
  Rig r;
  r.points = {{Eigen::Vector3d(0, 0, 0), "a"}, {Eigen::Vector3d(1, 0, 0), "b"}, {Eigen::Vector3d(2, 0, 0), "c"}};
  r.pseudo_edges = {{0, 1}, {1, 2}, {0, 2}};
  r.skeleton.joints = Eigen::MatrixXd::Zero(5, 3);
  for (int j = 0; j < 5; ++j) r.skeleton.joints(j, 0) = j;
  r.skeleton.bones = {{0, 1}, {1, 2}, {2, 3}, {1, 4}};
  for (int i = 0; i < 4; ++i) r.skeleton.bones[i].name = "bone" + std::to_string(i);
  compute_bone_parents(r.skeleton);
  Cage c;
  c.mesh.V = Eigen::MatrixXd::Zero(3, 3);
  c.mesh.F = Eigen::MatrixXi(1, 3);
  c.mesh.F << 0, 1, 2;
  c.name = "cage0";
  r.cages = {c, c};
  r.cages[1].name = "cage1";
  r.regions = {{{0}, "r0"}, {{1}, "r1"}};
  return r;
}
}  // namespace

TEST_CASE("deleting handles: points take their pseudo-edges, bones their unused joints, a cage vertex its cage", "[rig]") {
  const Rig before = deletion_rig();
  REQUIRE(num_handles(before) == 3 + 4 + 6 + 2);
  // Point b (1), bone2 (3 + 2), a vertex of cage0 (7 + 1), region r0 (13).
  const HandleDeletion d = plan_handle_deletion(before, {1, 5, 8, 13});
  Rig r = before;
  delete_handles(r, d);

  REQUIRE(r.points.size() == 2);
  CHECK(r.points[0].name == "a");
  CHECK(r.points[1].name == "c");
  CHECK(r.pseudo_edges == std::vector<std::pair<int, int>>{{0, 1}});  // a-c, renumbered
  REQUIRE(r.skeleton.num_bones() == 3);
  CHECK(r.skeleton.bones[0].name == "bone0");
  CHECK(r.skeleton.bones[1].name == "bone1");
  CHECK(r.skeleton.bones[2].name == "bone3");
  // Joint 3 (only bone2's end) is gone; joint 4 becomes 3.
  REQUIRE(r.skeleton.num_joints() == 4);
  for (int j = 0; j < 3; ++j) CHECK(r.skeleton.joints(j, 0) == j);
  CHECK(r.skeleton.joints(3, 0) == 4);
  CHECK((r.skeleton.bones[2].a == 1 && r.skeleton.bones[2].b == 3));
  CHECK(r.skeleton.bones[0].parent == -1);
  CHECK(r.skeleton.bones[1].parent == 0);
  CHECK(r.skeleton.bones[2].parent == 0);
  REQUIRE(r.cages.size() == 1);
  CHECK(r.cages[0].name == "cage1");
  REQUIRE(r.regions.size() == 1);
  CHECK(r.regions[0].name == "r1");

  // The renumbering: 15 handles to 2 + 3 + 3 + 1 = 9, each kept one keeping its name.
  const std::vector<int> expect = {0, -1, 1, 2, 3, -1, 4, -1, -1, -1, 5, 6, 7, -1, 8};
  CHECK(d.new_handle == expect);
  REQUIRE(num_handles(r) == 9);
  for (int h = 0; h < num_handles(before); ++h)
    if (d.new_handle[h] >= 0 && handle_ref(before, h).kind != HandleKind::CageVertex)
      CHECK(handle_name(r, d.new_handle[h]) == handle_name(before, h));
}

TEST_CASE("deleting handles from pose parameters keeps the others' entries and renumbers solved ones", "[rig]") {
  const Rig before = deletion_rig();
  PoseParams p;
  for (int i = 0; i < 3; ++i) p.point_translation.push_back(Eigen::Vector3d(i, 0, 0));
  for (int i = 0; i < 3; ++i) p.point_rotation.push_back(Eigen::Quaterniond(Eigen::AngleAxisd(0.1 * i, Eigen::Vector3d::UnitZ())));
  for (int i = 0; i < 4; ++i) {
    p.bone_rotation.push_back(Eigen::Quaterniond(Eigen::AngleAxisd(0.2 * i, Eigen::Vector3d::UnitX())));
    p.bone_translation.push_back(Eigen::Vector3d(0, i, 0));
    p.bone_twist_stretch.push_back({0.3 * i, 1.0 + i});
  }
  for (int i = 0; i < 6; ++i) p.cage_translation.push_back(Eigen::Vector3d(0, 0, i));
  for (int i = 0; i < 2; ++i) p.region_transform.push_back(Eigen::Affine3d(Eigen::Translation3d(i, i, i)));
  p.solved[1] = Eigen::Affine3d(Eigen::Translation3d(1, 0, 0));    // point b: deleted
  p.solved[4] = Eigen::Affine3d(Eigen::Translation3d(4, 0, 0));    // bone1: becomes 3
  p.solved[14] = Eigen::Affine3d(Eigen::Translation3d(14, 0, 0));  // region r1: becomes 8

  const HandleDeletion d = plan_handle_deletion(before, {1, 5, 8, 13});
  delete_handles(p, d);
  REQUIRE(p.point_translation.size() == 2);
  CHECK(p.point_translation[1].x() == 2);
  REQUIRE(p.point_rotation.size() == 2);
  CHECK(p.point_rotation[1].isApprox(Eigen::Quaterniond(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ()))));
  REQUIRE(p.bone_rotation.size() == 3);
  CHECK(p.bone_rotation[2].isApprox(Eigen::Quaterniond(Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitX()))));
  REQUIRE(p.bone_translation.size() == 3);
  CHECK(p.bone_translation[2].y() == 3);
  REQUIRE(p.bone_twist_stretch.size() == 3);
  CHECK(p.bone_twist_stretch[2].stretch == 4.0);
  REQUIRE(p.cage_translation.size() == 3);  // cage0's three vertices gone
  for (int i = 0; i < 3; ++i) CHECK(p.cage_translation[i].z() == 3 + i);
  REQUIRE(p.region_transform.size() == 1);
  CHECK(p.region_transform[0].translation().x() == 1);
  REQUIRE(p.solved.size() == 2);
  CHECK(p.solved.at(3).translation().x() == 4);
  CHECK(p.solved.at(8).translation().x() == 14);

  // Short (unsized) parameters lose nothing they do not have.
  PoseParams empty;
  delete_handles(empty, d);
  CHECK(empty.point_translation.empty());
  CHECK(empty.cage_translation.empty());
}

TEST_CASE("a deletion names a handle out of range; an empty one changes nothing", "[rig]") {
  const Rig before = deletion_rig();
  CHECK_THROWS_WITH(plan_handle_deletion(before, {15}), Catch::Contains("no handle 15"));
  CHECK_THROWS_AS(plan_handle_deletion(before, {-1}), Error);
  const HandleDeletion none = plan_handle_deletion(before, {});
  CHECK(none.empty());
  Rig r = before;
  delete_handles(r, none);
  CHECK(num_handles(r) == num_handles(before));
  CHECK(r.skeleton.num_joints() == 5);
}
