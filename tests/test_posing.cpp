// Posing by dragging in the document (FAST, Jacobson 2013 ch. 7): a drag moves the dragged point to
// where it was dragged, solves the free handles, keeps pinned ones, is one undo step, keys exactly,
// survives a scene file, and the script's `drag` reproduces it exactly.
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
  CHECK_THROWS_WITH(run_script(d, parse_script("ik-chain 7\n", "ik.txt"), "ik.txt"), Catch::Contains("is not a bone"));
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
