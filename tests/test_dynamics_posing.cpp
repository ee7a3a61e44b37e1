// Dynamics in the document (Jacobson 2013, 7.7; document.h): a dynamics drag lags behind the static
// drag on its first step and settles onto it; `simulate` keys frames whose free handle lags behind the
// static solve of the same keyed constraints and converges to it while the keys hold still, in one
// undo step; the dynamics settings survive a scene file and old scenes load with dynamics off.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <unistd.h>

#include <catch2/catch.hpp>

#include "core/pose/fast_posing.h"
#include "core/scene/document.h"
#include "core/scene/script.h"
#include "tests/test_gltf_fixtures.h"

using namespace dfm;
namespace fs = std::filesystem;

namespace {

// A tube along x with point handles at x = 0, 2, 4 and hat weights: 0 pinned, 1 free, 2 dragged.
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
  d.set_handle_state(0, HandleConstraint::Fixed);
  d.set_handle_state(1, HandleConstraint::Free);
}

// The surface posed by LBS with the pose's transforms.
Eigen::MatrixXd skinned(const Document& d, const Pose& pose) {
  const Eigen::MatrixXd& V = d.surface().V;
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(V.rows(), 3);
  for (int i = 0; i < V.rows(); ++i)
    for (int j = 0; j < d.weights().cols(); ++j)
      X.row(i) += d.weights()(i, j) * (pose.transforms[j] * Eigen::Vector3d(V.row(i).transpose())).transpose();
  return X;
}

double diagonal(const Document& d) { return (d.surface().V.colwise().maxCoeff() - d.surface().V.colwise().minCoeff()).norm(); }

// The static FAST solve of `params` run to convergence.
Pose static_pose(const Document& d, PoseParams params) {
  FastPosing f;
  f.solve(d.rig(), d.surface().V, d.surface().F, d.weights(), d.handle_states(), 300, params);
  return evaluate_pose(d.rig(), params);
}

const Eigen::Vector3d kDrag(0.0, 1.5, 0.0);
const Eigen::Vector3d kMiddle(2, 0, 0);

}  // namespace

TEST_CASE("dynamics drag: lags on the first step, settles onto the static drag, undo restores", "[dynamics][document]") {
  Document d;
  bound_tube(d);
  const PoseParams before = d.pose_params();
  PosingSettings p = d.posing();
  p.dynamics = true;
  d.set_posing(p);
  CHECK_FALSE(d.dynamics_live());
  const int depth = d.undo_depth();
  d.drag_handle(2, kDrag);
  CHECK(d.undo_depth() == depth + 1);
  CHECK(d.dynamics_live());
  const Pose first = d.pose();
  // The dragged point is where it was dragged (a boundary condition); the free middle lags.
  CHECK((first.transforms[2] * Eigen::Vector3d(4, 0, 0) - Eigen::Vector3d(4, 0, 0) - kDrag).norm() < 1e-9);
  PoseParams target = before;
  target.point_translation[2] += kDrag;
  const Pose still = static_pose(d, target);
  const double moved_first = (first.transforms[1] * kMiddle - kMiddle).norm();
  const double moved_static = (still.transforms[1] * kMiddle - kMiddle).norm();
  CHECK(moved_static > 0.3);
  CHECK(moved_first < 0.5 * moved_static);
  // Settling: the document keeps stepping (what the editor does once per drawn frame).
  double peak = 0;
  int steps = 0;
  while (d.step_dynamics() && steps < 3000) {
    ++steps;
    peak = std::max(peak, (d.pose().transforms[1] * kMiddle - kMiddle).norm());
  }
  CHECK_FALSE(d.dynamics_live());
  CHECK(peak > moved_static);  // it overshot
  const double err = (skinned(d, d.pose()) - skinned(d, still)).rowwise().norm().maxCoeff();
  INFO("settled after " << steps << " steps, peak " << peak << " vs static " << moved_static << ", error " << err);
  CHECK(err < 1e-3 * diagonal(d));
  CHECK(d.undo_depth() == depth + 1);  // the settling added no steps
  d.undo();
  CHECK(d.pose_params().point_translation[2] == before.point_translation[2]);
  CHECK(d.pose_params().solved.empty() == before.solved.empty());
  CHECK_FALSE(d.step_dynamics());  // undo ended the simulation
  // A new drag restarts the simulation from rest (the precompute kept): the same first step.
  d.drag_handle(2, kDrag);
  CHECK((d.pose().transforms[1].matrix() - first.transforms[1].matrix()).norm() < 1e-12);

  // The script's drag and settle do the same.
  Document s;
  bound_tube(s);
  run_script(s, parse_script("dynamics on\ndrag 2 0 1.5 0\nsettle\n", "dyn.txt"), "dyn.txt");
  CHECK_FALSE(s.dynamics_live());
  CHECK((skinned(s, s.pose()) - skinned(s, still)).rowwise().norm().maxCoeff() < 1e-3 * diagonal(s));
}

TEST_CASE("simulate keys the animation through the dynamics, one undo step", "[dynamics][document]") {
  Document d;
  bound_tube(d);
  d.set_key(0.0);
  d.drag_handle(2, kDrag);  // static (dynamics off)
  d.set_key(0.5);
  d.set_key(4.0);  // holds still from 0.5 to 4
  const std::vector<SceneKey> old = d.keys();
  const int depth = d.undo_depth();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(d.simulate(30, nan, nan) == 121);
  CHECK(d.undo_depth() == depth + 1);
  REQUIRE(d.keys().size() == 121);
  CHECK(d.keys().front().time == 0.0);
  CHECK(std::abs(d.keys().back().time - 4.0) < 1e-12);
  // Per frame: the simulated free handle against the static solve of the same keyed constraints.
  double largest = 0;
  for (const SceneKey& k : d.keys()) {
    const Pose sim = evaluate_pose(d.rig(), k.params);
    PoseParams c = k.params;
    c.solved.clear();
    const Pose ref = static_pose(d, c);
    // The keyed point follows its keys exactly (its rotation is solved).
    const Eigen::Vector3d tip(4, 0, 0);
    CHECK((sim.transforms[2] * tip - ref.transforms[2] * tip).norm() < 1e-9);
    largest = std::max(largest, (sim.transforms[1] * kMiddle - ref.transforms[1] * kMiddle).norm());
  }
  const SceneKey& end = d.keys().back();
  PoseParams c = end.params;
  c.solved.clear();
  const double at_end = (evaluate_pose(d.rig(), end.params).transforms[1] * kMiddle - static_pose(d, c).transforms[1] * kMiddle).norm();
  INFO("largest lag " << largest << ", at the end " << at_end);
  CHECK(largest > 0.05);
  CHECK(at_end < 0.05 * largest);
  CHECK(at_end < 1e-2);
  d.undo();
  REQUIRE(d.keys().size() == old.size());
  for (size_t i = 0; i < old.size(); ++i) CHECK(d.keys()[i].time == old[i].time);
  // The script command, with a range: keys in [0, 1] replaced, the key at 4 kept.
  run_script(d, parse_script("simulate 10 0 1\n", "sim.txt"), "sim.txt");
  CHECK(d.keys().size() == 12);
  CHECK(d.keys().back().time == 4.0);
  CHECK_THROWS_WITH(d.simulate(0, nan, nan), Catch::Contains("frames per second"));
  CHECK_THROWS_WITH(d.simulate(30, 1, 1), Catch::Contains("FROM before TO"));
}

TEST_CASE("dynamics settings round-trip through the scene file", "[dynamics][scene]") {
  const fs::path dir = fs::temp_directory_path() / ("dfm_test_dynamics_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  Document d;
  bound_tube(d);
  PosingSettings p = d.posing();
  p.dynamics = true;
  p.dt = 1.0 / 30;
  p.damping = 2.5;
  p.density = 3.0;
  d.set_posing(p);
  const std::string path = (dir / "dyn.scene.json").string();
  d.save_scene(path);
  Document e;
  e.load_scene(path);
  CHECK(e.posing() == d.posing());
  CHECK(e.posing().dynamics);
  CHECK(e.posing().dt == 1.0 / 30);
  p.dt = 0;
  CHECK_THROWS_WITH(d.set_posing(p), Catch::Contains("time step"));
  // A scene without the dynamics fields (saved before them) loads with dynamics off.
  Document old;
  old.load_scene(std::string(DFM_ASSETS_DIR) + "/default.scene.json");
  CHECK_FALSE(old.posing().dynamics);
  CHECK(old.posing().damping == PosingSettings{}.damping);
  fs::remove_all(dir);
}
