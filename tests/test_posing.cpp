// Posing by dragging in the document (FAST, Jacobson 2013 ch. 7): a drag moves the dragged point to
// where it was dragged, solves the free handles, keeps pinned ones, is one undo step, keys exactly,
// survives a scene file, and the script's `drag` reproduces it exactly.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <unistd.h>

#include <catch2/catch.hpp>

#include "core/scene/document.h"
#include "core/scene/script.h"
#include "core/util/error.h"
#include "tests/test_gltf_fixtures.h"

using namespace dfm;
namespace fs = std::filesystem;

namespace {

// A tube along x with point handles at x = 0, 2, 4 and hat weights between them, bound by hand.
void bound_tube(Document& d) {
  d.set_surface(test::tube(25, 16, 4.0, 0.4), "tube");
  for (double x : {0.0, 2.0, 4.0}) d.add_point(Eigen::Vector3d(x, 0, 0));
  const Eigen::MatrixXd& V = d.surface().V;
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(V.rows(), 3);
  for (int i = 0; i < V.rows(); ++i) {
    const double s = std::clamp(V(i, 0) / 2.0, 0.0, 2.0);
    if (s <= 1) W(i, 0) = 1 - s, W(i, 1) = s;
    else W(i, 1) = 2 - s, W(i, 2) = s - 1;
  }
  d.set_weights(W, BindStats{});
}

}  // namespace

TEST_CASE("document drag: FAST solves the free handle, the pinned one stays, one undo step", "[fast][document]") {
  Document d;
  CHECK_THROWS_WITH(d.drag_handle(0, Eigen::Vector3d(1, 0, 0)), Catch::Contains("bind first"));
  bound_tube(d);
  d.set_handle_state(0, HandleConstraint::Fixed);
  d.set_handle_state(1, HandleConstraint::Free);
  CHECK(d.handle_states() ==
        std::vector<HandleConstraint>{HandleConstraint::Fixed, HandleConstraint::Free, HandleConstraint::Position});
  const int depth = d.undo_depth();
  const Eigen::Vector3d delta(-0.8, 1.6, 0.0);
  d.drag_handle(2, delta);
  CHECK(d.undo_depth() == depth + 1);
  const Pose pose = d.pose();
  CHECK((pose.transforms[2] * Eigen::Vector3d(4, 0, 0) - Eigen::Vector3d(4, 0, 0) - delta).norm() < 1e-9);
  CHECK(pose.transforms[0].matrix() == Eigen::Matrix4d::Identity());
  CHECK((pose.transforms[1].translation()).norm() > 0.05);  // the free middle followed
  CHECK(d.pose_params().solved.size() == 2);
  CHECK(d.last_fast_solve().precomputed);
  // Keys hold the solved transforms; going to the key restores them exactly.
  d.set_key(0.0);
  CHECK(d.key_poses()[0].transforms[1].matrix() == pose.transforms[1].matrix());
  d.undo();  // the key
  d.undo();  // the drag
  CHECK(d.pose_params().solved.empty());
  CHECK(d.pose().transforms[1].matrix() == Eigen::Matrix4d::Identity());
  CHECK(d.handle_states()[1] == HandleConstraint::Free);  // a separate step
  d.redo();
  CHECK(d.pose().transforms[1].matrix() == pose.transforms[1].matrix());
}

TEST_CASE("FAST posing: translate re-solves only with fast on; states and solved survive a scene file",
          "[fast][document]") {
  const fs::path dir = fs::temp_directory_path() / ("dfm_test_posing_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  Document d;
  bound_tube(d);
  d.set_handle_state(1, HandleConstraint::Free);
  d.translate_handle(2, Eigen::Vector3d(0, 1, 0));
  CHECK(d.pose_params().solved.empty());  // fast off: plain posing
  PosingSettings p = d.posing();
  p.fast = true;
  p.iterations = 12;
  d.set_posing(p);  // turning it on solves the current pose
  CHECK(d.pose_params().solved.size() == 3);
  CHECK(d.last_fast_solve().iterations == 12);
  const std::string file = (dir / "posed.scene.json").string();
  d.save_scene(file);
  Document e;
  e.load_scene(file);
  CHECK(e.posing() == d.posing());
  REQUIRE(e.pose_params().solved.size() == 3);
  for (int h = 0; h < 3; ++h) CHECK(e.pose().transforms[h].isApprox(d.pose().transforms[h], 1e-12));
  CHECK_THROWS_WITH(d.set_posing(PosingSettings{true, 0, {}}), Catch::Contains("iterations must be in [1, 1000]"));
  // A bad state word in a scene file names the file and the field; the document keeps what it had.
  std::string text;
  {
    std::ifstream in(file);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const size_t at = text.find("\"free\"");
  REQUIRE(at != std::string::npos);
  text.replace(at, 6, "\"loose\"");
  const std::string bad = (dir / "bad.scene.json").string();
  fs::copy_file(dir / "posed.scene.bin", dir / "bad.scene.bin", fs::copy_options::overwrite_existing);
  {
    std::ofstream out(bad);
    out << text;
  }
  CHECK_THROWS_WITH(e.load_scene(bad), Catch::Contains("bad.scene.json") && Catch::Contains("posing.states[1]") &&
                                           Catch::Contains("unknown handle state 'loose'"));
  CHECK(e.posing() == d.posing());
  fs::remove_all(dir);
}

TEST_CASE("script drag / handle-state / fast reproduce the document commands exactly", "[fast][script]") {
  Document by_hand, by_script;
  bound_tube(by_hand);
  bound_tube(by_script);
  by_hand.set_handle_state(1, HandleConstraint::Free);
  by_hand.drag_handle(2, Eigen::Vector3d(0.3, -1.2, 0.4));
  run_script(by_script, parse_script("handle-state 1 free\ndrag 2 0.3 -1.2 0.4\n", "drag.txt"), "drag.txt");
  for (int h = 0; h < 3; ++h) CHECK(by_script.pose().transforms[h].matrix() == by_hand.pose().transforms[h].matrix());
  CHECK_THROWS_WITH(run_script(by_script, parse_script("handle-state 1 loose\n", "s.txt"), "s.txt"),
                    Catch::Contains("unknown handle state 'loose'"));
  CHECK_THROWS_WITH(run_script(by_script, parse_script("fast maybe\n", "s.txt"), "s.txt"),
                    Catch::Contains("expected on or off"));
  run_script(by_script, parse_script("fast on 5\n", "s.txt"), "s.txt");
  CHECK(by_script.posing().fast);
  CHECK(by_script.posing().iterations == 5);
  Document unbound;
  unbound.add_point(Eigen::Vector3d(0, 0, 0));
  CHECK_THROWS_WITH(run_script(unbound, parse_script("drag 0 1 0 0\n", "s.txt"), "s.txt"), Catch::Contains("bind first"));
}

TEST_CASE("IK chain: the dragged bone's tip lands on the target, the root stays, the chain follows",
          "[fast][script]") {
  Document d;
  d.set_surface(test::tube(31, 16, 4.0, 0.4), "tube");
  d.add_bone_chain({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(4.0 / 3, 0, 0), Eigen::Vector3d(8.0 / 3, 0, 0),
                    Eigen::Vector3d(4, 0, 0)});
  REQUIRE(d.num_handles() == 3);
  const Eigen::MatrixXd& V = d.surface().V;
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(V.rows(), 3);  // smooth blends across the two inner joints
  for (int i = 0; i < V.rows(); ++i) {
    const double x = V(i, 0) * 3 / 4;  // 0..3 along the chain
    const double a = std::clamp(x - 0.5, 0.0, 1.0), b = std::clamp(x - 1.5, 0.0, 1.0);
    W(i, 0) = 1 - a, W(i, 1) = a - b, W(i, 2) = b;
  }
  d.set_weights(W, BindStats{});
  CHECK_THROWS_WITH(run_script(d, parse_script("ik-chain 7\n", "ik.txt"), "ik.txt"), Catch::Contains("no handle 7"));
  run_script(d, parse_script("ik-chain 2\ndrag 2 -0.6 1.5 0\n", "ik.txt"), "ik.txt");
  CHECK(d.handle_states() ==
        std::vector<HandleConstraint>{HandleConstraint::Fixed, HandleConstraint::Free, HandleConstraint::Position});
  const Pose pose = d.pose();
  const Eigen::Vector3d tip(4, 0, 0);
  CHECK((pose.transforms[2] * tip - (tip + Eigen::Vector3d(-0.6, 1.5, 0))).norm() < 1e-9);
  CHECK(pose.transforms[0].matrix() == Eigen::Matrix4d::Identity());
  // The middle bone turned toward the target (its tip rose), instead of the mesh shearing at the end.
  const Eigen::Vector3d mid_tip = pose.transforms[1] * Eigen::Vector3d(8.0 / 3, 0, 0);
  CHECK(mid_tip.y() > 0.2);
}

namespace {

// The largest distance, over the skeleton, between a bone's posed start and the posed end of the bone
// it hangs from (its parent; for a root sharing an earlier root's first joint, that root's posed
// start), from the pose's transforms and the rig's rest joints alone.
double worst_joint_gap(const Rig& rig, const Pose& pose) {
  const Skeleton& sk = rig.skeleton;
  const int np = num_point_handles(rig);
  auto joint = [&](int j) { return Eigen::Vector3d(sk.joints.row(j).transpose()); };
  double gap = 0;
  for (int b = 0; b < sk.num_bones(); ++b) {
    const Eigen::Vector3d start = pose.transforms[np + b] * joint(sk.bones[b].a);
    const int p = sk.bones[b].parent;
    if (p >= 0) gap = std::max(gap, (start - pose.transforms[np + p] * joint(sk.bones[p].b)).norm());
    for (int k = 0; k < b && p < 0; ++k)
      if (sk.bones[k].parent < 0 && sk.bones[k].a == sk.bones[b].a)
        gap = std::max(gap, (start - pose.transforms[np + k] * joint(sk.bones[k].a)).norm());
  }
  return gap;
}

double diagonal(const TriMesh& m) { return (m.V.colwise().maxCoeff() - m.V.colwise().minCoeff()).norm(); }

// The default scene (which ships unbound) with smooth weights made here instead of a bind: inverse
// fourth powers of the distance to each handle (a point, a bone's segment, a cage vertex), rows
// normalized. FAST needs weights, not BBW's.
void load_default_scene_weighted_by_hand(Document& d) {
  d.load_scene(std::string(DFM_ASSETS_DIR) + "/default.scene.json");
  const Rig& rig = d.rig();
  const Eigen::MatrixXd& V = d.surface().V;
  const int n = d.num_handles();
  Eigen::MatrixXd W(V.rows(), n);
  for (int i = 0; i < V.rows(); ++i) {
    const Eigen::Vector3d v = V.row(i).transpose();
    for (int h = 0; h < n; ++h) {
      const HandleRef r = handle_ref(rig, h);
      double dist = (v - d.handle_pivot(h)).norm();
      if (r.kind == HandleKind::Bone) {
        const Bone& b = rig.skeleton.bones[r.index];
        const Eigen::Vector3d a = rig.skeleton.joints.row(b.a).transpose(), e = rig.skeleton.joints.row(b.b).transpose();
        const double t = std::clamp((v - a).dot(e - a) / (e - a).squaredNorm(), 0.0, 1.0);
        dist = (v - (a + t * (e - a))).norm();
      }
      W(i, h) = 1.0 / std::pow(dist * dist + 1e-4, 2);
    }
    W.row(i) /= W.row(i).sum();
  }
  d.set_weights(W, BindStats{});
}

}  // namespace

TEST_CASE("default scene: after a drag on each bone in turn every bone starts where its parent ends, "
          "also after undo and redo", "[fast][document][skeleton]") {
  Document d;
  load_default_scene_weighted_by_hand(d);
  const Rig& rig = d.rig();
  const int np = num_point_handles(rig), nb = rig.skeleton.num_bones();
  REQUIRE(nb == 10);
  const double tol = 1e-9 * diagonal(d.surface());
  const Eigen::Vector3d delta(0, 0.3, 0.2);
  // The case first: l_forearm (handle 6), pinned under a pinned upper arm, turns about its elbow.
  {
    const int h = np + 3;
    REQUIRE(handle_name(rig, h) == "l_forearm");
    const Pose before = d.pose();
    const Eigen::Vector3d elbow = before.transforms[h] * Eigen::Vector3d(rig.skeleton.joints.row(3).transpose());
    const Eigen::Vector3d tip = before.transforms[h] * Eigen::Vector3d(rig.skeleton.joints.row(4).transpose());
    const DragReport r = d.drag_handle(h, delta);
    CHECK(r.kind == DragKind::Rotated);
    CHECK_THAT(r.message, Catch::Contains("l_forearm turned") && Catch::Contains("where l_upper_arm ends"));
    const Pose after = d.pose();
    const Eigen::Vector3d elbow1 = after.transforms[h] * Eigen::Vector3d(rig.skeleton.joints.row(3).transpose());
    const Eigen::Vector3d tip1 = after.transforms[h] * Eigen::Vector3d(rig.skeleton.joints.row(4).transpose());
    CHECK((elbow1 - elbow).norm() < tol);                         // the elbow stayed
    CHECK(std::abs((tip1 - elbow1).norm() - (tip - elbow).norm()) < tol);  // a turn: the length kept
    CHECK(((tip1 - elbow1).normalized() - (tip + delta - elbow).normalized()).norm() < 1e-9);  // toward the drag
    d.undo();
  }
  std::vector<Pose> poses;
  std::vector<DragKind> kinds;
  for (int b = 0; b < nb; ++b) {
    kinds.push_back(d.drag_handle(np + b, delta).kind);
    poses.push_back(d.pose());
    INFO("after dragging " << handle_name(rig, np + b));
    CHECK(worst_joint_gap(rig, poses.back()) <= tol);
  }
  // The spine places its own joint (it moves); every other bone hangs from one and turns.
  CHECK(kinds[0] == DragKind::Moved);
  for (int b = 1; b < nb; ++b) CHECK(kinds[b] == DragKind::Rotated);
  for (int b = nb - 1; b >= 0; --b) {
    d.undo();
    CHECK(worst_joint_gap(rig, d.pose()) <= tol);
  }
  CHECK(d.pose_params().solved.empty());
  for (int b = 0; b < nb; ++b) {
    d.redo();
    CHECK(worst_joint_gap(rig, d.pose()) <= tol);
    for (int h = 0; h < d.num_handles(); ++h) CHECK(d.pose().transforms[h].matrix() == poses[b].transforms[h].matrix());
  }
}

TEST_CASE("default scene: IK on a chain and a free bone over a pinned one keep the skeleton connected",
          "[fast][script][skeleton]") {
  Document d;
  load_default_scene_weighted_by_hand(d);
  const Rig& rig = d.rig();
  const double tol = 1e-9 * diagonal(d.surface());
  const int h = find_handle(rig, "l_forearm");
  const Eigen::Vector3d tip = rig.skeleton.joints.row(4).transpose(), delta(-0.1, 0.25, 0.1);
  std::vector<std::string> printed;
  ScriptHost host;
  host.print = [&](const std::string& s) { printed.push_back(s); };
  run_script(d, parse_script("ik-chain l_forearm\ndrag l_forearm -0.1 0.25 0.1\n", "ik.txt"), "ik.txt", host);
  REQUIRE(printed.size() == 1);
  CHECK_THAT(printed[0], Catch::StartsWith("drag: IK: l_forearm"));
  CHECK(worst_joint_gap(rig, d.pose()) <= tol);
  CHECK((d.pose().transforms[h] * tip - (tip + delta)).norm() < 1e-6 * diagonal(d.surface()));  // the tip on target
  // The upper arm (free) turned; the spine (pinned root) stayed.
  CHECK((d.pose().transforms[find_handle(rig, "l_upper_arm")].matrix() - Eigen::Matrix4d::Identity()).norm() > 1e-3);
  CHECK(d.pose().transforms[find_handle(rig, "spine")].matrix() == Eigen::Matrix4d::Identity());
  // A free upper arm over a pinned forearm: a drag of the belly solves the arm, the forearm follows it.
  Document e;
  load_default_scene_weighted_by_hand(e);
  run_script(e, parse_script("handle-state l_upper_arm free\ndrag belly 0.2 0.1 0.3\n", "free.txt"), "free.txt", host);
  CHECK(e.pose_params().solved.count(find_handle(rig, "l_upper_arm")) == 1);
  CHECK(worst_joint_gap(e.rig(), e.pose()) <= tol);
}
