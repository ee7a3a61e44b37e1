// The script language: parse errors name the file and line; commands drive the Document the way the
// UI does; save-posed writes the skinned pose, or the animation manifold's slice when keys exist,
// checked against linear blend skinning computed here by hand.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <unistd.h>
#include <fstream>

#include "core/mesh/io.h"
#include "core/scene/bind_document.h"
#include "core/scene/script.h"
#include "core/util/error.h"
#include "tests/test_support.h"

using namespace dfm;
namespace fs = std::filesystem;

namespace {
TriMesh tetra() {
  TriMesh m;
  m.V.resize(4, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  m.F.resize(4, 3);
  m.F << 0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2;
  return m;
}

void expect_parse_error(const std::string& text, int line, const std::string& what) {
  try {
    parse_script(text, "s.txt");
    FAIL("no error for: " << text);
  } catch (const Error& e) {
    INFO(e.what());
    CHECK(std::string(e.what()).find("s.txt:" + std::to_string(line) + ":") == 0);
    CHECK(std::string(e.what()).find(what) != std::string::npos);
  }
}

struct TempDir {
  fs::path dir = fs::temp_directory_path() / ("dfm_script_test_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(dir); }
  ~TempDir() { fs::remove_all(dir); }
  std::string operator/(const std::string& f) const { return (dir / f).string(); }
};

// Two point handles on a tetrahedron, weights fixed by hand: vertex i follows handle 0 with w0(i).
void make_posable(Document& d) {
  d.set_surface(tetra(), "tetra");
  d.add_point({0.1, 0.1, 0.1});
  d.add_point({0.2, 0.1, 0.1});
  Eigen::MatrixXd W(4, 2);
  W << 1, 0, 0.5, 0.5, 0.25, 0.75, 0, 1;
  d.set_weights(W, {});
}
}  // namespace

TEST_CASE("script parsing: comments, blank lines, and errors with file and line") {
  const auto lines = parse_script("# a comment\n\nadd-point 1 2 3   # trailing\r\nselect 0\nquit\n", "s.txt");
  REQUIRE(lines.size() == 3);
  CHECK(lines[0].line == 3);
  CHECK(lines[0].words == std::vector<std::string>{"add-point", "1", "2", "3"});
  CHECK(lines[2].words[0] == "quit");
  expect_parse_error("select 0\nfly 1 2\n", 2, "unknown command 'fly'");
  expect_parse_error("add-point 1 2\n", 1, "takes 3 argument(s), got 2");
  expect_parse_error("\n\ntranslate 1 x 3\n", 3, "'x' is not a finite number");
  expect_parse_error("rotate 30 0 0 nan\n", 1, "not a finite number");
  expect_parse_error("add-bone 0 0 0 1\n", 1, "takes 6..3000");
  expect_parse_error("add-bone 0 0 0 1 1 1 2 2 2 3\n", 1, "in threes");
  expect_parse_error("save-frames out/f 1\n", 1, "must be an integer >= 2");
  expect_parse_error("set-key 1 2\n", 1, "usage: set-key [TIME]");
  CHECK_THROWS_WITH(read_script("/nonexistent/s.txt"), Catch::Contains("/nonexistent/s.txt"));
  expect_parse_error("select 0\nexport-gltf out.obj\n", 2, "writes .glb or .gltf");
  expect_parse_error("export-gltf out.glb 6\n", 1, "must be 4 or 8");
  expect_parse_error("export-gltf out.glb 4 x\n", 1, "takes 1..2");
  CHECK(parse_script("export-gltf a.gltf 8\nexport-gltf b.glb\n", "s.txt").size() == 2);
}

TEST_CASE("export-gltf goes to the host with the influence count (4 by default)") {
  Document d;
  make_posable(d);
  std::vector<std::pair<std::string, int>> calls;
  ScriptHost host;
  host.export_gltf = [&](const std::string& p, int k) { calls.push_back({p, k}); };
  run_script(d, parse_script("export-gltf a.glb\nexport-gltf b.gltf 8\n", "s.txt"), "s.txt", host);
  REQUIRE(calls.size() == 2);
  CHECK(calls[0] == std::make_pair(std::string("a.glb"), 4));
  CHECK(calls[1] == std::make_pair(std::string("b.gltf"), 8));
  CHECK_THROWS_WITH(run_script(d, parse_script("export-gltf a.glb\n", "s.txt"), "s.txt"),
                    Catch::StartsWith("s.txt:1: export-gltf:") && Catch::Contains("needs the editor"));
}

TEST_CASE("script commands edit the document like the UI") {
  Document d;
  d.set_surface(tetra(), "tetra");
  const auto lines = parse_script(
      "add-point 0.1 0.1 0.1\n"
      "add-point 0.2 0.1 0.1\n"
      "pseudo-edge 0 1\n"
      "add-bone 0 0 0.2  0.1 0 0.2  0.2 0 0.2\n"
      "set-method dqs\n"
      "select 2\n"
      "rotate 90 0 0 1\n"
      "set-key 0\n"
      "select 0\n"
      "translate 0 0 1\n"
      "set-time 2\n"
      "set-key\n"
      "delete-key 0\n"
      "undo\n"
      "reset-pose\n"
      "quit\n"
      "add-point 9 9 9\n",
      "s.txt");
  int seen = 0;
  ScriptHost host;
  host.after_command = [&](const ScriptLine&) { ++seen; };
  const ScriptResult r = run_script(d, lines, "s.txt", host);
  CHECK(r.quit);
  CHECK(r.commands_run == 16);
  CHECK(seen == 16);
  CHECK(d.rig().points.size() == 2);  // the line after quit never ran
  CHECK(d.rig().pseudo_edges.size() == 1);
  CHECK(d.rig().skeleton.num_bones() == 2);
  CHECK(d.method() == SkinMethod::DQS);
  REQUIRE(d.keys().size() == 2);  // delete-key was undone
  CHECK(d.keys()[1].time == 2);
  CHECK(d.keys()[1].params.point_translation[0] == Eigen::Vector3d(0, 0, 1));
  CHECK(d.keys()[0].params.point_translation[0].isZero());
  CHECK(d.keys()[0].params.bone_rotation[0].angularDistance(
            Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()))) < 1e-12);
  CHECK(d.pose_params().point_translation[0].isZero());  // reset-pose
  CHECK(d.time() == 2);
}

TEST_CASE("bind-monotone sets the bind setting, one undo step; bind_options carries it") {
  Document d;
  d.set_surface(tetra(), "tetra");
  run_script(d, parse_script("bind-monotone on\n", "m.txt"), "m.txt", ScriptHost{});
  CHECK(d.bind_settings().monotone);
  CHECK(bind_options(d).bbw.monotone);
  run_script(d, parse_script("undo\n", "m.txt"), "m.txt", ScriptHost{});
  CHECK(!d.bind_settings().monotone);
  CHECK(!bind_options(d).bbw.monotone);
  CHECK_THROWS_WITH(run_script(d, parse_script("bind-monotone yes\n", "m.txt"), "m.txt", ScriptHost{}),
                    Catch::Contains("expected on or off"));
}

TEST_CASE("script run errors name the script line and the command") {
  Document d;
  d.set_surface(tetra(), "tetra");
  auto run = [&](const std::string& text) { run_script(d, parse_script(text, "s.txt"), "s.txt"); };
  CHECK_THROWS_WITH(run("set-time 1\ntranslate 1 0 0\n"), Catch::StartsWith("s.txt:2: translate: no handle selected"));
  CHECK_THROWS_WITH(run("select 7\n"), Catch::StartsWith("s.txt:1: select: no handle 7"));
  CHECK_THROWS_WITH(run("save-posed x.obj\n"), Catch::Contains("no weights"));
  CHECK_THROWS_WITH(run("delete-key 3\n"), Catch::StartsWith("s.txt:1: delete-key: no key at time 3"));
  CHECK_THROWS_WITH(run("screenshot a.png\n"), Catch::Contains("screenshots need the editor"));
  CHECK_THROWS_WITH(run("open /nonexistent/m.obj\n"), Catch::Contains("/nonexistent/m.obj"));
  CHECK_THROWS_WITH(run("add-point 0.1 0.1 0.1\nrotate 10 0 0 0\n"), Catch::Contains("axis is zero"));
}

TEST_CASE("save-posed: the skinned pose, then the animation slice between keys") {
  TempDir tmp;
  Document d;
  make_posable(d);
  std::string shot;
  ScriptHost host;
  host.screenshot = [&](const std::string& p) { shot = p; };
  const std::string posed = tmp / "posed.obj", mid = tmp / "mid.obj", sc = tmp / "s.scene.json";
  run_script(d,
             parse_script("select 0\ntranslate 1 0 0\nselect 1\ntranslate 0 2 0\nsave-posed " + posed +
                              "\nscreenshot " + tmp / "a.png" + "\n",
                          "s.txt"),
             "s.txt", host);
  CHECK(shot == tmp / "a.png");
  // LBS with pure translations: v + sum_j w_j t_j.
  const Eigen::MatrixXd& W = d.weights();
  Eigen::MatrixXd expect = tetra().V;
  for (int i = 0; i < 4; ++i) expect.row(i) += Eigen::RowVector3d(W(i, 0), 2 * W(i, 1), 0);
  const TriMesh got = read_surface(posed);
  REQUIRE(got.num_vertices() == 4);
  CHECK((got.V - expect).cwiseAbs().maxCoeff() < 1e-6);

  // Keys at t = 0 (rest) and t = 2 (the pose above), 4 in-betweens: layers at 0, 0.4, ..., 2. The slice
  // at a layer time is that layer, and translations blend linearly: t = 0.4 is a fifth of the way.
  run_script(d,
             parse_script("set-key 2\nreset-pose\nset-key 0\nset-time 0.4\nsave-posed " + mid + "\nsave-scene " + sc +
                              "\nsave-frames " + tmp / "f_" + " 3\n",
                          "s.txt"),
             "s.txt");
  const TriMesh slice = read_surface(mid);
  REQUIRE(slice.num_vertices() == 4);
  const Eigen::MatrixXd quarter = tetra().V + 0.2 * (expect - tetra().V);
  // Slice vertices may come in another order: match each to its nearest expected vertex.
  for (int i = 0; i < 4; ++i) {
    double best = 1e9;
    for (int j = 0; j < 4; ++j) best = std::min(best, (slice.V.row(i) - quarter.row(j)).norm());
    CHECK(best < 1e-6);
  }
  CHECK(fs::exists(tmp / "f_0000.obj"));
  CHECK(fs::exists(tmp / "f_0002.obj"));
  CHECK_FALSE(fs::exists(tmp / "f_0003.obj"));
  const TriMesh last = read_surface(tmp / "f_0002.obj");
  for (int i = 0; i < 4; ++i) {
    double best = 1e9;
    for (int j = 0; j < 4; ++j) best = std::min(best, (last.V.row(i) - expect.row(j)).norm());
    CHECK(best < 1e-6);
  }
  // The saved scene reopens with keys, weights and time.
  Document e;
  run_script(e, parse_script("open " + sc + "\n", "s.txt"), "s.txt");
  CHECK(e.keys().size() == 2);
  CHECK(e.has_weights());
  CHECK(e.time() == 0.4);
}

TEST_CASE("paint-mask sets the mask within the radius, as one brush stroke") {
  Document d;
  d.set_surface(tetra(), "tetra");
  run_script(d, parse_script("paint-mask 0 0 0 0.5 1\npaint-mask 1 0 0 0.1 0.25\n", "s.txt"), "s.txt");
  REQUIRE(d.mask().size() == 4);
  CHECK(d.mask()[0] == 1.0);
  CHECK(d.mask()[1] == 0.25);
  CHECK(d.mask()[2] == 0.0);
  CHECK(d.mask()[3] == 0.0);
  d.undo();
  CHECK(d.mask()[1] == 0.0);
  CHECK(d.mask()[0] == 1.0);
  CHECK_THROWS_WITH(run_script(d, parse_script("paint-mask 5 5 5 0.1 1\n", "s.txt"), "s.txt"),
                    Catch::Contains("no surface vertex within"));
  CHECK_THROWS_WITH(run_script(d, parse_script("paint-mask 0 0 0 0.1 2\n", "s.txt"), "s.txt"),
                    Catch::Contains("in [0, 1]"));
  expect_parse_error("paint-mask 0 0 0 0.1\n", 1, "takes 5");
}

// The brush profile written out here: 1 inside (1 - falloff) r, then 1 - smoothstep to 0 at the rim.
double expected_brush(double d, double r, double falloff) {
  if (d > r) return 0;
  const double inner = (1 - falloff) * r;
  if (d <= inner) return 1;
  const double u = (d - inner) / (r - inner);
  return 1 - (3 * u * u - 2 * u * u * u);
}

TEST_CASE("paint-dab is one dab of the Paint tool: smoothstep falloff, adds or erases a quarter of the strength") {
  // Vertices on a line at distances 0, 0.25, 0.5, 0.75, 1.0, 1.25 from the dab's centre.
  TriMesh line;
  line.V.resize(6, 3);
  for (int i = 0; i < 6; ++i) line.V.row(i) << 0.25 * i, 0, 0;
  line.F.resize(4, 3);
  line.F << 0, 1, 2, 1, 2, 3, 2, 3, 4, 3, 4, 5;
  Document d;
  d.set_surface(line, "line");
  run_script(d, parse_script("paint-dab 0 0 0 1 0.8 0.6\npaint-dab 0 0 0 1 0.8 0.6\npaint-dab 0 0 0 1 0.4 0.6 erase\n",
                             "s.txt"), "s.txt");
  REQUIRE(d.mask().size() == 6);
  for (int i = 0; i < 6; ++i) {
    const double f = expected_brush(0.25 * i, 1.0, 0.6);
    const double expect = std::clamp(2 * 0.25 * 0.8 * f - 0.25 * 0.4 * f, 0.0, 1.0);
    CHECK(d.mask()[i] == Approx(expect).margin(1e-15));
  }
  CHECK(d.mask()[5] == 0.0);                   // outside the radius: untouched
  CHECK(d.mask()[0] == Approx(0.3));           // full strength at the centre: 0.2 + 0.2 - 0.1
  CHECK(d.undo_depth() == 4);                  // the surface, then one undo step per dab
  // paint-mask with a falloff blends toward VALUE by the same profile.
  run_script(d, parse_script("paint-mask 0 0 0 1 1 0.6\n", "s.txt"), "s.txt");
  const double f3 = expected_brush(0.75, 1.0, 0.6), before3 = std::clamp(0.3 * expected_brush(0.75, 1.0, 0.6), 0.0, 1.0);
  CHECK(d.mask()[3] == Approx(before3 + f3 * (1 - before3)).margin(1e-15));
  CHECK(d.mask()[0] == 1.0);
  expect_parse_error("paint-dab 0 0 0 1 0.5\n", 1, "takes 6");
  CHECK_THROWS_WITH(run_script(d, parse_script("paint-dab 0 0 0 1 0.5 0.5 wipe\n", "s.txt"), "s.txt"),
                    Catch::Contains("'erase'"));
  CHECK_THROWS_WITH(run_script(d, parse_script("paint-dab 0 0 0 1 1.5 0.5\n", "s.txt"), "s.txt"),
                    Catch::Contains("strength must be in [0, 1]"));
}

namespace {

const std::string kDefaultScene = std::string(DFM_ASSETS_DIR) + "/default.scene.json";

// A closed bar along x (length 2, radius 0.3): `rings` rings of `around` vertices and two capped
// ends, oriented outward (checked by its signed volume, a closed form here: about pi r^2 L).
TriMesh closed_bar(int rings, int around) {
  TriMesh m;
  m.V.resize(rings * around + 2, 3);
  for (int i = 0; i < rings; ++i)
    for (int k = 0; k < around; ++k) {
      const double a = 2 * M_PI * k / around;
      m.V.row(i * around + k) << 2.0 * i / (rings - 1), 0.3 * std::cos(a), 0.3 * std::sin(a);
    }
  const int c0 = rings * around, c1 = c0 + 1;
  m.V.row(c0) << 0, 0, 0;
  m.V.row(c1) << 2, 0, 0;
  std::vector<Eigen::Vector3i> F;
  for (int i = 0; i + 1 < rings; ++i)
    for (int k = 0; k < around; ++k) {
      const int a = i * around + k, b = i * around + (k + 1) % around, c = a + around, d = b + around;
      F.push_back({a, b, d});
      F.push_back({a, d, c});
    }
  for (int k = 0; k < around; ++k) {
    F.push_back({c0, (k + 1) % around, k});
    F.push_back({c1, (rings - 1) * around + k, (rings - 1) * around + (k + 1) % around});
  }
  m.F.resize(static_cast<int>(F.size()), 3);
  for (int f = 0; f < m.F.rows(); ++f) m.F.row(f) = F[f].transpose();
  double vol = 0;
  for (int f = 0; f < m.F.rows(); ++f)
    vol += Eigen::Vector3d(m.V.row(m.F(f, 0))).dot(Eigen::Vector3d(m.V.row(m.F(f, 1))).cross(Eigen::Vector3d(m.V.row(m.F(f, 2))))) / 6;
  REQUIRE(vol > 0.9 * M_PI * 0.09 * 2 * 0.9);
  return m;
}

ScriptResult run_text(Document& d, const std::string& text, const ScriptHost& host = {}) {
  return run_script(d, parse_script(text, "s.txt"), "s.txt", host);
}

}  // namespace

TEST_CASE("open: a mesh after the default scene starts a new document, which binds once handles are added",
          "[script][open]") {
  TempDir tmp;
  const std::string bar = tmp / "bar.obj";
  write_surface(bar, closed_bar(9, 12));
  Document d;
  run_text(d, "open " + kDefaultScene + "\nselect l_upper_arm\nrotate 30 0 0 1\n");
  REQUIRE(d.num_handles() > 10);
  REQUIRE(d.dirty());
  run_text(d, "open " + bar + "\n");
  CHECK(d.num_handles() == 0);
  CHECK(d.rig().skeleton.num_joints() == 0);
  CHECK(d.keys().empty());
  CHECK(d.surface().num_vertices() == 9 * 12 + 2);
  CHECK(d.path().empty());  // Save asks for a name...
  CHECK(d.title() == bar);  // ...while the title names the file
  CHECK_FALSE(d.can_undo());
  CHECK_FALSE(d.dirty());
  CHECK(d.posing() == PosingSettings{});
  CHECK(d.camera() == Camera{});
  CHECK(d.weights_note() == "not bound yet");
  // The failure was the old rig's handles lying outside the new surface; now the bind works.
  run_text(d, "add-point 0.5 0 0\nadd-point 1.5 0 0\nbind\n");
  REQUIRE(d.has_weights());
  CHECK(d.weights().cols() == 2);
  CHECK((d.weights().rowwise().sum().array() - 1.0).abs().maxCoeff() < 1e-9);
  // A bad file names itself and leaves the document as it was.
  CHECK_THROWS_WITH(run_text(d, "open " + tmp / "missing.obj" + "\n"), Catch::Contains("missing.obj"));
  CHECK(d.has_weights());
  CHECK(d.num_handles() == 2);
}

TEST_CASE("open: arm.obj after the default scene leaves no handle", "[script][open][data]") {
  DFM_DATA_OR_SKIP(arm, "arm.obj");
  Document d;
  run_text(d, "open " + kDefaultScene + "\nopen " + arm + "\n");
  CHECK(d.num_handles() == 0);
  CHECK(d.surface().num_vertices() == read_surface(arm).num_vertices());
  CHECK(d.title() == arm);
}

TEST_CASE("replace-surface keeps the rig, clears the weights and is one undo step", "[script][open]") {
  TempDir tmp;
  write_surface(tmp / "bar.obj", closed_bar(9, 12));
  write_surface(tmp / "bar_fine.obj", closed_bar(17, 20));  // the character remeshed
  Document d;
  run_text(d, "open " + tmp / "bar.obj" + "\nadd-point 0.5 0 0\nadd-point 1.5 0 0\nselect 1\ntranslate 0 0.1 0\nbind\n");
  REQUIRE(d.has_weights());
  const Rig rig = d.rig();
  const PoseParams pose = d.pose_params();
  const int depth = d.undo_depth();
  run_text(d, "replace-surface " + tmp / "bar_fine.obj" + "\n");
  CHECK(d.surface().num_vertices() == 17 * 20 + 2);
  CHECK(d.rig().points.size() == 2);
  CHECK(d.rig().points[1].position == rig.points[1].position);
  CHECK(d.pose_params().point_translation[1] == pose.point_translation[1]);
  CHECK_FALSE(d.has_weights());
  CHECK_THAT(d.weights_note(), Catch::Contains("bind again"));
  CHECK(d.undo_depth() == depth + 1);
  CHECK(d.undo_name() == "replace surface bar_fine.obj");
  d.undo();
  CHECK(d.surface().num_vertices() == 9 * 12 + 2);
  CHECK(d.has_weights());
  d.redo();
  run_text(d, "bind\n");
  CHECK(d.has_weights());
  CHECK(d.weights().rows() == 17 * 20 + 2);
  // On the default scene: the teddy's rig stays whole over the replaced surface.
  Document t;
  t.load_scene(kDefaultScene);
  const int handles = t.num_handles();
  const std::string title = t.title();
  run_text(t, "replace-surface " + std::string(DFM_ASSETS_DIR) + "/default.obj\n");
  CHECK(t.num_handles() == handles);
  CHECK(t.rig().skeleton.num_bones() == 10);
  CHECK(t.rig().cages.size() == 1);
  CHECK_FALSE(t.has_weights());
  CHECK(t.title() == title);
}

TEST_CASE("scripts take handle names wherever they take handle numbers", "[script][names]") {
  Document by_name, by_number;
  by_name.load_scene(kDefaultScene);
  by_number.load_scene(kDefaultScene);
  run_text(by_name, "select l_forearm r_ear\n");
  CHECK(by_name.selection().handles == std::vector<int>{6, 1});
  CHECK(handle_name(by_name.rig(), 6) == "l_forearm");
  std::vector<std::string> printed;
  ScriptHost host;
  host.print = [&](const std::string& s) { printed.push_back(s); };
  run_text(by_name, "handle-state l_ear free\nselect l_forearm\ntranslate 0 0.3 0.2\n", host);
  run_text(by_number, "handle-state 0 free\nselect 6\ntranslate 0 0.3 0.2\n", host);
  REQUIRE(printed.size() == 2);
  CHECK(printed[0] == printed[1]);
  CHECK_THAT(printed[0], Catch::StartsWith("translate: l_forearm turned"));
  CHECK(by_name.handle_states() == by_number.handle_states());
  for (int h = 0; h < by_name.num_handles(); ++h)
    CHECK(by_name.pose().transforms[h].matrix() == by_number.pose().transforms[h].matrix());
  // An unknown name is named, with the close ones and their numbers.
  CHECK_THROWS_WITH(run_text(by_name, "select l_forarm\n"),
                    Catch::Contains("s.txt:1: select: no handle named 'l_forarm'") && Catch::Contains("l_forearm (6)"));
  CHECK_THROWS_WITH(run_text(by_name, "ik-chain r_shinn\n"), Catch::Contains("r_shin (12)"));
  CHECK_THROWS_WITH(run_text(by_name, "select 99\n"), Catch::Contains("no handle 99"));
  expect_parse_error("select 1.5\n", 1, "not a handle number or name");
  expect_parse_error("drag l_forearm 0 up 0\n", 1, "'up' is not a finite number");
  // Unnamed handles are "point 0", "bone 1", ...: a name with a space, so they go by number.
  Document plain;
  plain.set_surface(tetra(), "tetra");
  run_text(plain, "add-point 0.1 0.1 0.1\nadd-bone 0 0 0.2  0.1 0 0.2  0.2 0 0.2\nselect 2\n");
  CHECK(plain.selection().handles == std::vector<int>{2});
  CHECK(handle_name(plain.rig(), 2) == "bone 1");
  CHECK_THROWS_WITH(run_text(plain, "select bone\n"), Catch::Contains("bone 0 (1)") && Catch::Contains("bone 1 (2)"));
  // The weight tools' locked handles, drag and pseudo-edge take names too.
  Document a, b;
  make_posable(a);
  make_posable(b);
  for (Document* x : {&a, &b}) x->rename_handle(0, "left"), x->rename_handle(1, "right");
  run_text(a, "weights-smooth 1 0.5 uniform right\ndrag left 0 0.1 0\npseudo-edge left right\n", host);
  run_text(b, "weights-smooth 1 0.5 uniform 1\ndrag 0 0 0.1 0\npseudo-edge 0 1\n", host);
  CHECK(a.weights() == b.weights());
  CHECK(a.pose().transforms[0].matrix() == b.pose().transforms[0].matrix());
  CHECK(a.rig().pseudo_edges == b.rig().pseudo_edges);
  CHECK_THROWS_WITH(run_text(a, "weights-normalize rihgt\n"), Catch::Contains("right (1)"));
}

TEST_CASE("delete-handles: by number or name, one undo step, as the Delete key on a selection") {
  Document d;
  d.set_surface(tetra(), "tetra");
  run_script(d, parse_script("add-point 0.1 0.1 0.1\nadd-point 0.2 0.1 0.1\nadd-point 0.1 0.2 0.1\npseudo-edge 0 1\n", "s.txt"), "s.txt");
  REQUIRE(d.num_handles() == 3);
  run_script(d, parse_script("delete-handles 0 2\n", "s.txt"), "s.txt");
  CHECK(d.num_handles() == 1);
  CHECK(d.rig().pseudo_edges.empty());  // point 0 took its pseudo-edge along
  CHECK(d.rig().points[0].position.isApprox(Eigen::Vector3d(0.2, 0.1, 0.1)));
  d.undo();
  CHECK(d.num_handles() == 3);
  CHECK(d.rig().pseudo_edges.size() == 1);
  CHECK_THROWS_WITH(run_script(d, parse_script("delete-handles 7\n", "s.txt"), "s.txt"), Catch::Contains("s.txt:1"));
  CHECK(d.num_handles() == 3);
  // rename-handle: the rest of the line is the name; the UI's words (command_words) are the same line.
  run_script(d, parse_script("rename-handle 1 left ear\n", "s.txt"), "s.txt");
  CHECK(d.rig().points[1].name == "left ear");
  run_command(d, command_words("rename-handle", {1, std::string("tip")}));
  CHECK(d.rig().points[1].name == "tip");
  run_command(d, command_words("delete-handles", std::vector<int>{1}));
  CHECK(d.num_handles() == 2);
}

TEST_CASE("add-bone-from: a chain hanging from an existing joint, as the Bones tool started on a joint makes") {
  Document d;
  d.set_surface(tetra(), "tetra");
  run_script(d, parse_script("add-bone 0.1 0.1 0.1 0.1 0.2 0.1\nadd-bone-from 1 0.2 0.25 0.1 0.3 0.3 0.1\n", "s.txt"), "s.txt");
  const Skeleton& sk = d.rig().skeleton;
  REQUIRE(sk.num_bones() == 3);
  CHECK(sk.bones[1].a == 1);  // from the existing joint, no zero-length bone to a copy of it
  CHECK(sk.num_joints() == 4);
  for (const Bone& b : sk.bones) CHECK((sk.joints.row(b.b) - sk.joints.row(b.a)).norm() > 0.05);
  CHECK_THROWS_WITH(run_script(d, parse_script("add-bone-from 9 0 0 0\n", "s.txt"), "s.txt"), Catch::Contains("s.txt:1"));
  CHECK_THROWS_WITH(run_script(d, parse_script("add-bone-from 1 0 0 0 1\n", "s.txt"), "s.txt"), Catch::Contains("threes"));
  CHECK(sk.num_bones() == 3);
}
