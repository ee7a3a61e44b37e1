// Document: every edit is one undo step that restores the exact previous state; gestures merge;
// rig edits after a bind clear the weights (and undo brings them back); dirty tracks the saved state.
#include <catch2/catch.hpp>

#include <filesystem>

#include "core/mesh/mesh_info.h"
#include "core/scene/document.h"
#include "core/util/error.h"

using namespace dfm;

namespace {
TriMesh tetra_surface() {
  TriMesh m;
  m.V.resize(4, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  m.F.resize(4, 3);
  m.F << 0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2;
  return m;
}

Eigen::MatrixXd uniform_weights(const Document& d) {
  return Eigen::MatrixXd::Constant(d.surface().num_vertices(), d.num_handles(), 1.0 / d.num_handles());
}
}  // namespace

TEST_CASE("tet boundary surface is the outward hull of one tet") {
  TetMesh t;
  t.V = tetra_surface().V;
  t.T.resize(1, 4);
  t.T << 0, 1, 2, 3;
  Eigen::VectorXi to_tet;
  TriMesh s = tet_boundary_surface(t, &to_tet);
  REQUIRE(s.num_faces() == 4);
  REQUIRE(s.num_vertices() == 4);
  // Divergence theorem: signed volume of an outward surface = tet volume 1/6.
  double vol = 0;
  for (int f = 0; f < s.num_faces(); ++f) {
    Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
    vol += a.dot(b.cross(c)) / 6.0;
  }
  CHECK(vol == Approx(1.0 / 6.0));
  for (int i = 0; i < 4; ++i) CHECK(s.V.row(i) == t.V.row(to_tet[i]));
}

TEST_CASE("edits undo and redo exactly, and the dirty flag follows the saved state") {
  Document d;
  CHECK_FALSE(d.dirty());
  d.set_surface(tetra_surface(), "tetra");
  CHECK(d.dirty());
  const int p = d.add_point({0.2, 0.2, 0.2}, "belly");
  CHECK(p == 0);
  CHECK(d.selection().handles == std::vector<int>{0});
  d.add_bone_chain({{0.1, 0.1, 0.1}, {0.2, 0.1, 0.1}, {0.3, 0.1, 0.1}});
  REQUIRE(d.rig().skeleton.num_bones() == 2);
  CHECK(d.rig().skeleton.bones[1].parent == 0);
  CHECK(d.num_handles() == 3);
  CHECK(d.pose_params().bone_rotation.size() == 2);
  CHECK(d.pose_params().point_translation.size() == 1);
  CHECK(d.undo_depth() == 3);

  const std::string where = (std::filesystem::temp_directory_path() / "dfm_doc_dirty.scene.json").string();
  d.save_scene(where);
  CHECK_FALSE(d.dirty());
  d.move_point(0, {0.25, 0.2, 0.2});
  CHECK(d.dirty());
  d.undo();
  CHECK_FALSE(d.dirty());
  CHECK(d.rig().points[0].position == Eigen::Vector3d(0.2, 0.2, 0.2));
  d.redo();
  CHECK(d.dirty());
  CHECK(d.rig().points[0].position == Eigen::Vector3d(0.25, 0.2, 0.2));

  // Undo everything back to the empty document.
  while (d.can_undo()) d.undo();
  CHECK(d.surface().num_vertices() == 0);
  CHECK(d.num_handles() == 0);
  CHECK(d.pose_params().bone_rotation.empty());
  while (d.can_redo()) d.redo();
  CHECK(d.num_handles() == 3);
  CHECK(d.rig().points[0].position == Eigen::Vector3d(0.25, 0.2, 0.2));
  std::filesystem::remove(where);
  std::filesystem::remove(where.substr(0, where.size() - 5) + ".bin");
}

TEST_CASE("a drag inside a gesture is one undo step; two gestures are two") {
  Document d;
  d.set_surface(tetra_surface(), "tetra");
  d.add_point({0.2, 0.2, 0.2});
  const int before = d.undo_depth();
  d.begin_gesture();
  for (int i = 1; i <= 10; ++i) d.move_point(0, {0.2 + 0.01 * i, 0.2, 0.2});
  d.end_gesture();
  CHECK(d.undo_depth() == before + 1);
  d.begin_gesture();
  d.move_point(0, {0.5, 0.2, 0.2});
  d.move_point(0, {0.6, 0.2, 0.2});
  d.end_gesture();
  CHECK(d.undo_depth() == before + 2);
  d.undo();
  CHECK(d.rig().points[0].position.x() == Approx(0.3));
  d.undo();
  CHECK(d.rig().points[0].position.x() == Approx(0.2));
  // Different targets inside one gesture do not merge.
  d.add_point({0.1, 0.1, 0.1});
  const int n = d.undo_depth();
  d.begin_gesture();
  d.move_point(0, {0.3, 0.2, 0.2});
  d.move_point(1, {0.15, 0.1, 0.1});
  d.end_gesture();
  CHECK(d.undo_depth() == n + 2);
  // Outside a gesture nothing merges.
  d.move_point(0, {0.31, 0.2, 0.2});
  d.move_point(0, {0.32, 0.2, 0.2});
  CHECK(d.undo_depth() == n + 4);
}

TEST_CASE("rig edits after a bind clear the weights; undo restores them") {
  Document d;
  d.set_surface(tetra_surface(), "tetra");
  d.add_point({0.2, 0.2, 0.2});
  d.add_point({0.1, 0.1, 0.3});
  CHECK_FALSE(d.has_weights());
  CHECK(d.weights_note() == "not bound yet");
  const Eigen::MatrixXd W = uniform_weights(d);
  std::uint64_t sw = d.surface_weights_revision();
  d.set_weights(W, BindStats{1.5, 10, 20, {"ok"}});
  CHECK(d.has_weights());
  CHECK(d.weights_note().empty());
  CHECK(d.surface_weights_revision() != sw);
  sw = d.surface_weights_revision();
  // Posing and renaming keep the weights (and their revision).
  d.translate_handle(0, {0.1, 0, 0});
  d.rename_handle(1, "nose");
  d.add_pseudo_edge(0, 1);
  CHECK(d.has_weights());
  CHECK(d.surface_weights_revision() == sw);
  // The same weights again: a new revision all the same (a re-bind into the same storage).
  d.set_weights(W, BindStats{1.5, 10, 20, {"ok"}});
  CHECK(d.surface_weights_revision() != sw);
  d.undo();
  d.move_point(1, {0.1, 0.1, 0.25});
  CHECK_FALSE(d.has_weights());
  CHECK(d.weights_note().find("weights cleared") != std::string::npos);
  sw = d.surface_weights_revision();
  d.undo();
  CHECK(d.surface_weights_revision() != sw);
  REQUIRE(d.has_weights());
  CHECK(d.weights() == W);
  CHECK(d.bind_stats() == BindStats{1.5, 10, 20, {"ok"}});
  CHECK(d.weights_note().empty());
  CHECK_THROWS_AS(d.set_weights(Eigen::MatrixXd::Zero(3, 2), {}), Error);
}

TEST_CASE("a bind keeps the weights it replaced for the difference view; undo and rig edits follow") {
  Document d;
  d.set_surface(tetra_surface(), "tetra");
  d.add_point({0.2, 0.2, 0.2});
  d.add_point({0.1, 0.1, 0.3});
  const Eigen::MatrixXd A = uniform_weights(d);
  d.set_weights(A, BindStats{});
  CHECK(d.replaced_weights().size() == 0);  // nothing bound before
  Eigen::MatrixXd B = A;
  B.col(0).setConstant(0.8);
  B.col(1).setConstant(0.2);
  d.set_weights(B, BindStats{});  // a Rebind
  CHECK(d.weights() == B);
  CHECK(d.replaced_weights() == A);
  d.undo();
  CHECK(d.weights() == A);
  CHECK(d.replaced_weights().size() == 0);
  d.redo();
  CHECK(d.replaced_weights() == A);
  // A rig edit clears both (they no longer match the handles); its undo brings both back.
  d.move_point(1, {0.1, 0.1, 0.25});
  CHECK(d.replaced_weights().size() == 0);
  d.undo();
  CHECK(d.replaced_weights() == A);
}

TEST_CASE("deleting handles keeps pose params, keys and pseudo-edges consistent") {
  Document d;
  d.set_surface(tetra_surface(), "tetra");
  d.add_point({0.1, 0.1, 0.1}, "a");
  d.add_point({0.2, 0.1, 0.1}, "b");
  d.add_point({0.1, 0.2, 0.1}, "c");
  d.add_pseudo_edge(0, 2);
  d.add_pseudo_edge(1, 2);
  d.add_bone_chain({{0.1, 0.1, 0.2}, {0.2, 0.1, 0.2}, {0.2, 0.2, 0.2}});
  d.translate_handle(2, {0, 0, 1});          // point c
  d.rotate_handle(4, Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ())));  // bone 1
  d.set_key(0.0);
  d.delete_handles({1, 3});  // point b and bone 0
  REQUIRE(d.rig().points.size() == 2);
  CHECK(d.rig().points[1].name == "c");
  REQUIRE(d.rig().pseudo_edges.size() == 1);
  CHECK(d.rig().pseudo_edges[0] == std::make_pair(0, 1));
  REQUIRE(d.rig().skeleton.num_bones() == 1);
  CHECK(d.rig().skeleton.num_joints() == 2);  // the joint only bone 0 used is gone
  CHECK(d.rig().skeleton.bones[0].parent == -1);
  CHECK(d.pose_params().point_translation[1] == Eigen::Vector3d(0, 0, 1));
  CHECK(d.pose_params().bone_rotation[0].angularDistance(Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()))) <
        1e-12);
  REQUIRE(d.keys().size() == 1);
  CHECK(d.keys()[0].params.point_translation.size() == 2);
  CHECK(d.keys()[0].params.bone_rotation.size() == 1);
  CHECK(d.pose().size() == d.num_handles());
  d.undo();
  CHECK(d.rig().points.size() == 3);
  CHECK(d.rig().skeleton.num_bones() == 2);
}

TEST_CASE("cages and regions: pose entries and handle order") {
  Document d;
  d.set_surface(tetra_surface(), "tetra");
  d.add_point({0.1, 0.1, 0.1});
  Cage c;
  c.mesh = tetra_surface();
  c.mesh.V *= 0.1;
  c.name = "face";
  d.add_cage(c);
  CHECK(d.num_handles() == 5);
  CHECK(d.pose_params().cage_translation.size() == 4);
  d.translate_handle(3, {1, 2, 3});  // cage vertex 2
  CHECK(d.pose_params().cage_translation[2] == Eigen::Vector3d(1, 2, 3));
  CHECK_THROWS_AS(d.rotate_handle(3, Eigen::Quaterniond::Identity()), Error);
  const int r = d.add_region("cheek");
  d.begin_gesture();
  d.paint_region(r, {0, 1}, false);
  d.paint_region(r, {2}, false);
  d.paint_region(r, {0}, true);
  d.end_gesture();
  CHECK(d.rig().regions[0].vertices == std::vector<int>{1, 2});
  const Eigen::Vector3d c0 = d.handle_pivot(5);
  CHECK(c0.isApprox(Eigen::Vector3d(0.5, 0.5, 0)));
  // Rotating a region turns about its centroid: the centroid stays put.
  d.rotate_handle(5, Eigen::Quaterniond(Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitX())));
  CHECK((d.pose_params().region_transform[0] * c0).isApprox(c0));
  d.undo();
  d.undo();  // the whole stroke is one step
  CHECK(d.rig().regions[0].vertices.empty());
}

TEST_CASE("bone rotation is in world space: a child turned after its parent ends where expected") {
  Document d;
  d.set_surface(tetra_surface(), "tetra");
  d.add_bone_chain({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}});
  const Eigen::Quaterniond q90(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  d.rotate_handle(0, q90);
  d.rotate_handle(1, q90);  // world z again: the child now points along -x
  const Pose p = d.pose();
  const Eigen::Vector3d tip = p.transforms[1] * Eigen::Vector3d(2, 0, 0);
  CHECK(tip.isApprox(Eigen::Vector3d(-1, 1, 0), 1e-12));
  // A world translation of a child under a rotated parent turns it about its joint (0,1,0), its tip
  // (-1,1,0) toward (-1,1,1): the unit bone then points along (-1,0,1)/sqrt 2, the joint unmoved.
  const DragReport r = d.translate_handle(1, {0, 0, 1});
  CHECK(r.kind == DragKind::Rotated);
  const Eigen::Vector3d tip2 = d.pose().transforms[1] * Eigen::Vector3d(2, 0, 0);
  CHECK(tip2.isApprox(Eigen::Vector3d(0, 1, 0) + Eigen::Vector3d(-1, 0, 1) / std::sqrt(2.0), 1e-12));
  CHECK((d.pose().transforms[1] * Eigen::Vector3d(1, 0, 0) - d.pose().transforms[0] * Eigen::Vector3d(1, 0, 0)).norm() < 1e-12);
  // The root translates, and the chain with it.
  CHECK(d.translate_handle(0, {0, 0, 1}).kind == DragKind::Moved);
  const Eigen::Vector3d tip3 = d.pose().transforms[1] * Eigen::Vector3d(2, 0, 0);
  CHECK((tip3 - tip2 - Eigen::Vector3d(0, 0, 1)).norm() < 1e-12);
}

TEST_CASE("keys: set replaces at the same time, stay sorted, move refuses collisions") {
  Document d;
  d.set_surface(tetra_surface(), "tetra");
  d.add_point({0.1, 0.1, 0.1});
  d.set_key(1.0);
  d.translate_handle(0, {1, 0, 0});
  d.set_key(0.0);
  d.set_key(0.5);
  REQUIRE(d.key_times() == std::vector<double>{0.0, 0.5, 1.0});
  d.translate_handle(0, {1, 0, 0});
  d.set_key(0.5);
  CHECK(d.keys().size() == 3);
  CHECK(d.keys()[1].params.point_translation[0].x() == 2);
  CHECK_THROWS_AS(d.move_key(0, 1.0), Error);
  d.move_key(0, 2.0);
  CHECK(d.key_times() == std::vector<double>{0.5, 1.0, 2.0});
  d.go_to_key(1);
  CHECK(d.pose_params().point_translation[0].x() == 0);
  d.delete_key(0);
  CHECK(d.key_times() == std::vector<double>{1.0, 2.0});
  CHECK(d.key_poses().size() == 2);
  d.reset_pose();
  CHECK(d.pose_params().point_translation[0].isZero());
  // Time, camera, selection are view state: not undoable, not dirty.
  const int depth = d.undo_depth();
  d.set_time(0.7);
  d.set_selection({{0}, -1});
  CHECK(d.undo_depth() == depth);
  CHECK(d.time() == 0.7);
  CHECK_THROWS_AS(d.set_selection({{5}, -1}), Error);
  CHECK_THROWS_AS(d.set_time(std::nan("")), Error);
}

TEST_CASE("bad edits throw and leave the document unchanged") {
  Document d;
  d.set_surface(tetra_surface(), "tetra");
  d.add_point({0.1, 0.1, 0.1});
  const int depth = d.undo_depth();
  const auto rev = d.revision();
  CHECK_THROWS_AS(d.move_point(3, {0, 0, 0}), Error);
  CHECK_THROWS_AS(d.add_point({std::nan(""), 0, 0}), Error);
  CHECK_THROWS_AS(d.add_bone_chain({{0, 0, 0}}), Error);
  CHECK_THROWS_AS(d.add_pseudo_edge(0, 0), Error);
  CHECK_THROWS_AS(d.paint_mask({7}, {1.0}), Error);
  CHECK_THROWS_AS(d.delete_handles({4}), Error);
  CHECK_THROWS_AS(d.open_mesh("/nonexistent/x.obj"), Error);
  CHECK_THROWS_AS(d.load_skeleton("/nonexistent/x.tgf"), Error);
  CHECK_THROWS_AS(d.delete_key(0), Error);
  CHECK_THROWS_AS(parse_skin_method("xyz"), Error);
  CHECK(d.undo_depth() == depth);
  CHECK(d.revision() == rev);
  CHECK(d.num_handles() == 1);
}

TEST_CASE("mask painting clamps to [0,1] and a stroke is one step") {
  Document d;
  d.set_surface(tetra_surface(), "tetra");
  d.begin_gesture();
  d.paint_mask({0, 1}, {0.5, 2.0});
  d.paint_mask({2}, {-1.0});
  d.end_gesture();
  REQUIRE(d.mask().size() == 4);
  CHECK(d.mask()[0] == 0.5);
  CHECK(d.mask()[1] == 1.0);
  CHECK(d.mask()[2] == 0.0);
  d.undo();
  CHECK(d.mask().size() == 0);
  d.set_method(SkinMethod::DQS);
  CHECK(d.method() == SkinMethod::DQS);
  d.undo();
  CHECK(d.method() == SkinMethod::LBS);
}
