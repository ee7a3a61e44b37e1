// Twist and stretch an artist can reach (issue 33, Jacobson 2013 ch. 6): the script's twist and stretch
// commands (one undo step each, bones only), the closed form of a stretch (Fig. 6.15: what hangs below a
// bone stretched by s moves (s - 1) bone lengths along it), and keys that carry them: the animation's
// frames at a key and between keys equal the still pose with the same (interpolated) values.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include <unistd.h>

#include "core/mesh/io.h"
#include "core/rig/pose_io.h"
#include "core/scene/key_surfaces.h"
#include "core/scene/script.h"
#include "core/util/error.h"
#include "tests/cli_test_util.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;

namespace {

void run(Document& d, const std::string& text) { run_script(d, parse_script(text, "ts.txt"), "ts.txt"); }

// An ellipsoid along x (-2..2) with a chain of two bones (-2 -> 0 -> 2) and a point handle; weights by
// hand: x < -0.3 the first bone only, x > 0.3 the second only, a linear blend between.
void make_arm(Document& d) {
  TriMesh m = test::icosphere(Eigen::Vector3d::Zero(), 1.0, 2);
  m.V.col(0) *= 2.0;
  m.V.col(1) *= 0.5;
  m.V.col(2) *= 0.5;
  d.set_surface(m, "arm");
  d.add_point(Eigen::Vector3d(0, 0.3, 0));
  d.add_bone_chain({Eigen::Vector3d(-2, 0, 0), Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 0, 0)});
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(m.V.rows(), 3);  // point, bone 0, bone 1
  for (int i = 0; i < m.V.rows(); ++i) {
    const double s = std::clamp((m.V(i, 0) + 0.3) / 0.6, 0.0, 1.0);
    W(i, 1) = 1 - s;
    W(i, 2) = s;
  }
  d.set_weights(W, {});
}

double largest_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  REQUIRE(a.rows() == b.rows());
  return (a - b).cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("twist and stretch: bones by number or name, one undo step each; the wrong handle or value names the line") {
  Document d;
  make_arm(d);
  const int steps = d.undo_depth();
  run(d, "twist 2 90\nstretch 1 1.5\n");
  const std::vector<BoneTwistStretch>& ts = d.pose_params().bone_twist_stretch;
  REQUIRE(ts.size() == 2);
  CHECK(ts[1].twist == Approx(M_PI / 2).epsilon(1e-15));
  CHECK(ts[1].stretch == 1.0);
  CHECK(ts[0].stretch == 1.5);
  CHECK(ts[0].twist == 0.0);
  CHECK(d.undo_depth() == steps + 2);
  d.undo();
  CHECK(d.pose_params().bone_twist_stretch[0].stretch == 1.0);
  CHECK(d.pose_params().bone_twist_stretch[1].twist == Approx(M_PI / 2));

  CHECK_THROWS_WITH(run(d, "twist 0 10\n"), Catch::Contains("ts.txt:1") && Catch::Contains("not a bone"));
  CHECK_THROWS_WITH(run(d, "stretch 1 0\n"), Catch::Contains("ts.txt:1") && Catch::Contains("positive"));
  CHECK_THROWS_WITH(run(d, "stretch 1 -2\n"), Catch::Contains("positive"));
  CHECK_THROWS_WITH(run(d, "twist 7 10\n"), Catch::Contains("ts.txt:1"));
  CHECK_THROWS_WITH(run(d, "twist 1 nan\n"), Catch::Contains("ts.txt:1"));
  CHECK(d.undo_depth() == steps + 1);  // no failed line left a step
}

TEST_CASE("the twist at a bone's first joint (Eq. 6.5): set by twist and stretch, kept by scenes, interpolated by keys") {
  Document d;
  make_arm(d);
  run(d, "twist 2 90 -30\nstretch 1 1.5 10\n");
  const std::vector<BoneTwistStretch>& ts = d.pose_params().bone_twist_stretch;
  CHECK(ts[1].twist_start == Approx(-M_PI / 6).epsilon(1e-15));
  CHECK(ts[0].twist_start == Approx(M_PI / 18).epsilon(1e-15));
  CHECK(ts[0].twist == 0.0);
  run(d, "twist 2 45\n");  // without the third word the start stays
  CHECK(d.pose_params().bone_twist_stretch[1].twist_start == Approx(-M_PI / 6).epsilon(1e-15));

  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("dfm_ts_start_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  d.save_scene((dir / "a.scene.json").string());
  Document back;
  back.load_scene((dir / "a.scene.json").string());
  for (int b = 0; b < 2; ++b) {
    CHECK(back.pose_params().bone_twist_stretch[b].twist_start == d.pose_params().bone_twist_stretch[b].twist_start);
    CHECK(back.pose_params().bone_twist_stretch[b].twist == d.pose_params().bone_twist_stretch[b].twist);
  }
  fs::remove_all(dir);

  // Keyed at 0 (rest) and at 1: halfway, half of each.
  Document k;
  make_arm(k);
  run(k, "set-method stbs\nset-key 0\ntwist 2 90 -30\nset-key 1\n");
  const PoseParams mid = animation_params(k, 0.5);
  CHECK(mid.bone_twist_stretch[1].twist_start == Approx(-M_PI / 12).epsilon(1e-12));
  CHECK(mid.bone_twist_stretch[1].twist == Approx(M_PI / 4).epsilon(1e-12));
}

TEST_CASE("stretch (Fig. 6.15): what hangs below the bone moves (s - 1) bone lengths along it, nothing farther") {
  for (const char* method : {"lbs", "dqs", "stbs"}) {
    INFO(method);
    Document d;
    make_arm(d);
    run(d, std::string("set-method ") + method + "\nstretch 1 1.5\n");
    const TriMesh rest = d.surface();
    const Eigen::MatrixXd moved = posed_surface(d).V - rest.V;
    const Eigen::RowVector3d along(1.0, 0, 0);  // (1.5 - 1) x the first bone's length 2
    double farthest = 0;
    for (int i = 0; i < rest.V.rows(); ++i) {
      farthest = std::max(farthest, moved.row(i).norm());
      if (rest.V(i, 0) > 0.3) CHECK((moved.row(i) - along).norm() < 1e-12);  // the second bone's only
    }
    CHECK(farthest <= 1.0 + 1e-12);
  }
}

TEST_CASE("keys carry twist and stretch: the animation's frame at a key and between keys is the still pose's") {
  const double twist = 120, stretch = 1.3;
  Document d;
  make_arm(d);
  run(d, "set-method stbs\nset-key 0\ntwist 2 120\nstretch 2 1.3\nset-key 1\n");
  const int n = d.inbetweens();
  REQUIRE(n >= 1);
  const double u = 1.0 / (n + 1);  // the first in-between layer
  for (double t : {1.0, u}) {
    INFO("t = " << t);
    d.set_time(t);
    const TriMesh frame = posed_surface(d);
    Document still;  // no keys: the pose itself, skinned
    make_arm(still);
    run(still, "set-method stbs\ntwist 2 " + std::to_string(twist * t) + "\nstretch 2 " + std::to_string(1 + (stretch - 1) * t) + "\n");
    const TriMesh want = posed_surface(still);
    CHECK(largest_difference(frame.V, want.V) < 1e-9);
    CHECK(largest_difference(frame.V, still.surface().V) > 0.1);  // it did twist
  }
}

TEST_CASE("bind stores the STBS endpoint weights: saved and loaded with the scene, undone with the bind, cleared by a rig edit") {
  Document d;
  make_arm(d);
  run(d, "bind\n");
  const Eigen::MatrixXd E = d.endpoint_weights();
  REQUIRE(E.rows() == d.surface().num_vertices());
  REQUIRE(E.cols() == 2);
  CHECK(E.minCoeff() >= 0);
  CHECK(E.maxCoeff() <= 1);
  // Along the first bone (x from -2 to 0) the surface's endpoint weight grows from its start to its end.
  auto mean_at = [&](double x0, double x1) {
    double s = 0;
    int n = 0;
    for (int i = 0; i < E.rows(); ++i)
      if (d.surface().V(i, 0) >= x0 && d.surface().V(i, 0) < x1) s += E(i, 0), ++n;
    REQUIRE(n > 0);
    return s / n;
  };
  CHECK(mean_at(-1.6, -1.2) < mean_at(-1.0, -0.6));
  CHECK(mean_at(-1.0, -0.6) < mean_at(-0.4, 0.0));

  const std::string path = (std::filesystem::temp_directory_path() / ("dfm_ts_" + std::to_string(::getpid()) + ".scene.json")).string();
  d.save_scene(path);
  Document loaded;
  loaded.load_scene(path);
  CHECK(loaded.endpoint_weights() == E);
  std::filesystem::remove(path);
  std::filesystem::remove(path.substr(0, path.size() - 5) + ".bin");

  d.undo();  // the bind
  CHECK(d.endpoint_weights().size() == 0);
  d.redo();
  CHECK(d.endpoint_weights() == E);
  run(d, "add-point 0 0.2 0\n");  // the rig changed: weights and endpoint weights go
  CHECK(d.endpoint_weights().size() == 0);
}

TEST_CASE("a keyed twist: the animation's frame at the key equals deform pose of that key's pose files") {
  namespace fs = std::filesystem;
  Document d;
  make_arm(d);
  run(d, "set-method stbs\nset-key 0\nselect 2\nrotate 30 0 0 1\ntwist 2 150 -40\nstretch 1 1.2\nset-key 1\nset-time 1\n");
  const TriMesh frame = posed_surface(d);  // the animation's frame at the second key (its baked layer)
  const PoseParams& key = d.keys().back().params;

  const fs::path dir = fs::temp_directory_path() / ("dfm_ts_cli_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  write_surface((dir / "arm.obj").string(), d.surface());
  write_dmat((dir / "w.dmat").string(), d.weights());
  TgfData tgf;
  tgf.joints = d.rig().skeleton.joints;
  tgf.edges.resize(2, 2);
  tgf.edges << 0, 1, 1, 2;
  tgf.flags = Eigen::MatrixXi::Zero(2, 3);
  tgf.flags.col(0).setOnes();
  write_tgf((dir / "s.tgf").string(), tgf);
  write_points((dir / "p.txt").string(), Eigen::RowVector3d(0, 0.3, 0));
  write_bone_rotations((dir / "q.dmat").string(), key.bone_rotation);
  Eigen::MatrixXd ts(2, 3);
  for (int b = 0; b < 2; ++b) {
    const BoneTwistStretch t = twist_stretch_of(key, b);
    ts.row(b) << t.twist * 180 / M_PI, t.stretch, t.twist_start * 180 / M_PI;
  }
  write_dmat((dir / "ts.dmat").string(), ts);
  const std::string out = (dir / "out.obj").string();
  const test::RunResult r = test::run_program(DFM_DEFORM_EXE, {"pose", (dir / "arm.obj").string(), "--weights", (dir / "w.dmat").string(),
                                                               "--skeleton", (dir / "s.tgf").string(), "--points", (dir / "p.txt").string(),
                                                               "--pose", (dir / "q.dmat").string(), "--twist-stretch", (dir / "ts.dmat").string(),
                                                               "--method", "stbs", "--cpu", "-o", out},
                                              dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const TriMesh cli = read_surface(out);
  CHECK(largest_difference(frame.V, cli.V) < 1e-5);  // the obj's printed digits
  CHECK(largest_difference(frame.V, d.surface().V) > 0.1);
  fs::remove_all(dir);
}

TEST_CASE("endpoint-filter (Fig. 6.9): STBS twists by the filtered endpoint weight; undoable, saved, refused by name") {
  Document d;
  TriMesh m;
  m.V.resize(4, 3);
  m.V << 1, 0.5, 0, 1, 0, 0.5, 0.5, -0.5, 0, 1.5, 0, -0.5;
  m.F.resize(4, 3);
  m.F << 0, 1, 2, 0, 3, 1, 1, 3, 2, 0, 2, 3;
  d.set_surface(m, "bits");
  d.add_bone_chain({Eigen::Vector3d(-2, 0, 0), Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 0, 0)});
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(4, 2);
  W.col(1).setOnes();  // all on the second bone (0 -> 2): vertex 0 at t = 0.5, e = 0.5 by projection
  d.set_weights(W, {});
  run(d, "set-method stbs\ntwist 1 90\nendpoint-filter 1 0.5 0.1\n");
  const double a = 0.1 * M_PI / 2;  // the filtered endpoint weight times the twist
  const TriMesh posed = posed_surface(d);
  CHECK((posed.V.row(0) - Eigen::RowVector3d(1, 0.5 * std::cos(a), 0.5 * std::sin(a))).norm() < 1e-12);
  d.undo();
  const double b = 0.5 * M_PI / 2;
  CHECK((posed_surface(d).V.row(0) - Eigen::RowVector3d(1, 0.5 * std::cos(b), 0.5 * std::sin(b))).norm() < 1e-12);
  d.redo();

  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("dfm_ef_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  d.save_scene((dir / "f.scene.json").string());
  Document back;
  back.load_scene((dir / "f.scene.json").string());
  REQUIRE(back.endpoint_filters().size() == 2);
  CHECK(back.endpoint_filters()[0].empty());
  CHECK(back.endpoint_filters()[1] == EndpointFilter{{0.5, 0.1}});
  CHECK(posed_surface(back).V == posed_surface(d).V);
  fs::remove_all(dir);

  CHECK_THROWS_WITH(run(d, "endpoint-filter 1 0.5\n"), Catch::Contains("X Y pairs"));
  CHECK_THROWS_WITH(run(d, "endpoint-filter 1 0.6 0.5 0.4 0.7\n"), Catch::Contains("point 2"));
  run(d, "endpoint-filter 1\n");  // off
  CHECK(posed_surface(d).V.row(0).isApprox(Eigen::RowVector3d(1, 0.5 * std::cos(b), 0.5 * std::sin(b)), 1e-12));
}
