#include <catch2/catch.hpp>

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
