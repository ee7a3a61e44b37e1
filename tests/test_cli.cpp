// `deform` end to end: the real executable run as a child process. Help texts, `info` on the shared
// data against the counts in ../shared/data/README.md, a bind -> pose -> manifold -> export flow on
// the small knight, and hostile flags / files for every subcommand (exit 1 or 2, never a signal,
// never 0, a message naming the flag or file), plus atomic saves under a simulated full disk.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include "core/mesh/io.h"
#include "core/rig/pose_io.h"
#include "core/rig/pose_params.h"
#include "core/rig/rig_io.h"
#include "core/skin/skin.h"
#include "tests/cli_test_util.h"
#include "tests/test_support.h"

using dfm::test::run_program;
using dfm::test::RunResult;
namespace fs = std::filesystem;

namespace {

const std::string kExe = DEFORM_EXE;

// A scratch folder per test case, removed afterwards.
struct Scratch {
  fs::path dir;
  explicit Scratch(const std::string& name) {
    dir = fs::temp_directory_path() / ("dfm_test_cli_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir / "io");
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  std::string operator/(const std::string& f) const { return (dir / f).string(); }
};

RunResult deform(const Scratch& s, const std::vector<std::string>& args, const dfm::test::RunOptions& o = {}) {
  return run_program(kExe, args, s.dir / "io", o);
}

std::string describe(const RunResult& r) {
  std::string d = r.command + "\n  -> ";
  d += r.signaled ? "killed by signal " + std::to_string(r.signal) : "exit " + std::to_string(r.exit_code);
  return d + "\n  stdout: " + r.out.substr(0, 600) + "\n  stderr: " + r.err.substr(0, 600);
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
}

// "key: 123" from deform's stdout, -1 if absent.
long field(const std::string& text, const std::string& key) {
  std::smatch m;
  if (std::regex_search(text, m, std::regex("\\b" + key + ": (-?[0-9]+)"))) return std::stol(m[1]);
  return -1;
}

double signed_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  double v = 0;
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)).transpose(), b = V.row(F(f, 1)).transpose(), c = V.row(F(f, 2)).transpose();
    v += a.dot(b.cross(c)) / 6.0;
  }
  return v;
}

// Three point handles inside the knight (checked by winding number offline; bind rejects outside ones).
const char* kPoints = "0.45 0.2 0.5\n0.5 0.5 0.5\n0.5 0.8 0.5\n";
const char* kPointTgf = "1 0.45 0.2 0.5\n2 0.5 0.5 0.5\n3 0.5 0.8 0.5\n#\n";
const char* kBoneTgf = "1 0.45 0.2 0.5\n2 0.5 0.5 0.5\n3 0.5 0.8 0.5\n#\n1 2\n2 3\n";  // 2 bones, 0 points

}  // namespace

TEST_CASE("deform --help lists the subcommands and each subcommand's --help exits 0", "[cli]") {
  Scratch s("help");
  const RunResult h = deform(s, {"--help"});
  INFO(describe(h));
  REQUIRE(!h.signaled);
  CHECK(h.exit_code == 0);
  const std::vector<std::string> cmds = {"bind", "pose", "manifold", "export", "info", "version"};
  for (const auto& c : cmds) {
    INFO("subcommand " << c);
    CHECK(std::regex_search(h.out, std::regex("\\n  " + c + " +\\S")));
    const RunResult r = deform(s, {c, "--help"});
    INFO(describe(r));
    CHECK(!r.signaled);
    CHECK(r.exit_code == 0);
    CHECK(r.out.find("usage: deform " + c) != std::string::npos);
  }
  const RunResult none = deform(s, {});
  CHECK(none.exit_code == 2);  // no command: the help, as a usage error
  CHECK(none.out.find("commands:") != std::string::npos);
  const RunResult v = deform(s, {"version"});
  CHECK(v.exit_code == 0);
  CHECK(v.out.find("deform ") == 0);
}

TEST_CASE("deform info on every shared data file prints the README's counts", "[cli][data]") {
  Scratch s("info");
  struct Expect {
    const char* file;
    std::map<std::string, long> fields;
    int closed;  // 1 closed, 0 open, -1 not a surface
  };
  const std::vector<Expect> expect = {
      {"hand.mesh", {{"vertices", 7234}, {"tetrahedra", 29998}}, 1},
      {"hand.tgf", {{"bones", 20}}, -1},
      {"hand-pose.dmat", {}, -1},
      {"arm.obj", {{"vertices", 8311}}, 1},
      {"arm.tgf", {{"bones", 4}}, -1},
      {"elephant.obj", {{"vertices", 6034}}, 1},
      {"elephant.tgf", {{"bones", 24}}, -1},
      {"armadillo.obj", {{"vertices", 43243}, {"triangles", 86482}}, 1},
      {"decimated-knight.off", {{"vertices", 502}}, 1},
      {"octopus-low.mesh", {}, -1},
      {"bunny.off", {}, 1},
      {"cow.off", {}, 1},
      {"cheburashka.off", {}, 1},
      {"3holes.off", {}, 1},
      {"camelhead.off", {}, 0},
      {"beetle.off", {}, 0},
  };
  for (const Expect& e : expect) {
    SECTION(e.file) {
      DFM_DATA_OR_SKIP(path, e.file);
      const RunResult r = deform(s, {"info", path});
      INFO(describe(r));
      REQUIRE(!r.signaled);
      CHECK(r.exit_code == 0);
      CHECK(r.out.find(path) == 0);
      for (const auto& [key, n] : e.fields) {
        INFO(key);
        CHECK(field(r.out, key) == n);
      }
      if (e.closed >= 0) CHECK(r.out.find(e.closed ? "closed: yes" : "closed: no") != std::string::npos);
      if (std::string(e.file) == "hand-pose.dmat") CHECK(r.out.find("size: 80 rows x 1 column") != std::string::npos);
      if (std::string(e.file) == "octopus-low.mesh") CHECK(field(r.out, "tetrahedra") > 0);
    }
  }
}

TEST_CASE("deform bind -> pose -> manifold -> export on the knight", "[cli][flow]") {
  DFM_DATA_OR_SKIP(knight, "decimated-knight.off");
  Scratch s("flow");
  const dfm::TriMesh K = dfm::read_surface(knight);
  REQUIRE(K.V.rows() == 502);
  write_text(s / "p.txt", kPoints);
  write_text(s / "p.tgf", kPointTgf);

  // bind: 502 x 3 weights in [0, 1], rows summing to 1.
  const RunResult b = deform(s, {"bind", knight, "--points", s / "p.txt", "-o", s / "W.dmat"});
  INFO(describe(b));
  REQUIRE(!b.signaled);
  REQUIRE(b.exit_code == 0);
  const Eigen::MatrixXd W = dfm::read_dmat(s / "W.dmat");
  REQUIRE(W.rows() == 502);
  REQUIRE(W.cols() == 3);
  CHECK(W.minCoeff() >= 0.0);
  CHECK(W.maxCoeff() <= 1.0);
  CHECK((W.rowwise().sum().array() - 1.0).abs().maxCoeff() <= 1e-9);
  // Each handle dominates somewhere (the weights are not all one column).
  for (int j = 0; j < 3; ++j) CHECK(W.col(j).maxCoeff() > 0.9);

  // pose: identity reproduces the rest mesh; a common translation translates it (weights sum to 1).
  write_text(s / "zero.txt", "0 0 0\n0 0 0\n0 0 0\n");
  write_text(s / "shift.txt", "0.1 0.2 0.3\n0.1 0.2 0.3\n0.1 0.2 0.3\n");
  write_text(s / "bend.txt", "0 0 0\n0 0.05 0\n0.1 0.15 0\n");
  const std::vector<std::string> pose = {"pose", knight, "--weights", s / "W.dmat", "--skeleton", s / "p.tgf"};
  auto run_pose = [&](const std::string& pp, const std::string& out, bool cpu) {
    std::vector<std::string> a = pose;
    a.insert(a.end(), {"--points-pose", s / pp, "-o", s / out});
    if (cpu) a.push_back("--cpu");
    const RunResult r = deform(s, a);
    INFO(describe(r));
    REQUIRE(!r.signaled);
    REQUIRE(r.exit_code == 0);
    const dfm::TriMesh m = dfm::read_surface(s / out);
    REQUIRE(m.V.rows() == 502);
    CHECK(m.F == K.F);
    return m;
  };
  const dfm::TriMesh id = run_pose("zero.txt", "id.obj", true);
  CHECK((id.V - K.V).cwiseAbs().maxCoeff() <= 1e-9);
  const dfm::TriMesh tr = run_pose("shift.txt", "shift.obj", true);
  const Eigen::RowVector3d t(0.1, 0.2, 0.3);
  CHECK((tr.V.rowwise() - t - K.V).cwiseAbs().maxCoeff() <= 1e-9);
  const dfm::TriMesh bend = run_pose("bend.txt", "bend.obj", true);
  CHECK((bend.V - K.V).cwiseAbs().maxCoeff() > 0.05);  // the top handle moved 0.18: the head moves
  // Without --cpu: the GPU when a display exists (float precision), else the CPU again.
  const dfm::TriMesh tr_gpu = run_pose("shift.txt", "shift_gpu.obj", false);
  CHECK((tr_gpu.V - tr.V).cwiseAbs().maxCoeff() <= 1e-5);

  // manifold: keyframes rest (t=0), shifted (t=1), bent (t=2); the slice at t=0.5 is the knight
  // moved by half the shift, so it is closed with the knight's volume.
  const RunResult m = deform(s, {"manifold", "--keyframes", s / "id.obj", s / "shift.obj", s / "bend.obj", "--at",
                                 "0.5", "-o", s / "slice.obj", "--stats", "--save-manifold", s / "m.tet4"});
  INFO(describe(m));
  REQUIRE(!m.signaled);
  REQUIRE(m.exit_code == 0);
  CHECK(field(m.out, "tets") == 2 * 3 * K.F.rows());  // each triangle x time slab = 3 tetrahedra
  CHECK(field(m.out, "layers") == 3);
  CHECK(m.out.find("closed: yes") != std::string::npos);
  const double vol = signed_volume(K.V, K.F);
  std::smatch vm;
  REQUIRE(std::regex_search(m.out, vm, std::regex("\\nvolume: ([-0-9.eE+]+)")));
  CHECK(std::stod(vm[1]) == Approx(vol).epsilon(1e-5));
  const dfm::TriMesh slice = dfm::read_surface(s / "slice.obj");
  REQUIRE(slice.V.rows() > 0);
  const Eigen::RowVector3d lo = K.V.colwise().minCoeff() + 0.5 * t, hi = K.V.colwise().maxCoeff() + 0.5 * t;
  CHECK((slice.V.colwise().minCoeff() - lo).cwiseAbs().maxCoeff() <= 1e-9);
  CHECK((slice.V.colwise().maxCoeff() - hi).cwiseAbs().maxCoeff() <= 1e-9);
  CHECK(std::abs(signed_volume(slice.V, slice.F) - vol) <= 1e-6 * std::abs(vol));
  // The saved manifold reloads and slices the same.
  const RunResult m2 = deform(s, {"manifold", "--manifold", s / "m.tet4", "--at", "0.5", "--stats"});
  INFO(describe(m2));
  CHECK(m2.exit_code == 0);
  CHECK(field(m2.out, "slice triangles") == field(m.out, "slice triangles"));

  // export: points rig at rest, and a bone rig with two keys baked into morph targets.
  const RunResult e = deform(s, {"export", knight, "--weights", s / "W.dmat", "--skeleton", s / "p.tgf", "-o",
                                 s / "knight.glb"});
  INFO(describe(e));
  REQUIRE(!e.signaled);
  REQUIRE(e.exit_code == 0);
  REQUIRE(fs::exists(s / "knight.glb"));
  CHECK(fs::file_size(s / "knight.glb") > 1000);
  std::ifstream glb(s / "knight.glb", std::ios::binary);
  char magic[4] = {};
  glb.read(magic, 4);
  CHECK(std::string(magic, 4) == "glTF");
  write_text(s / "bones.tgf", kBoneTgf);
  dfm::write_dmat(s / "W2.dmat", Eigen::MatrixXd::Constant(502, 2, 0.5));
  write_text(s / "q.dmat", "4 2\n0\n0\n0.2\n0\n0\n0\n1\n1\n");  // bone 1 about z, bone 2 identity
  const RunResult e2 = deform(s, {"export", knight, "--weights", s / "W2.dmat", "--skeleton", s / "bones.tgf",
                                  "--pose", s / "q.dmat", "--morph-frames", "3", "--verify", "-o", s / "bones.gltf"});
  INFO(describe(e2));
  REQUIRE(!e2.signaled);
  CHECK(e2.exit_code == 0);
  CHECK(e2.out.find("3 morph targets") != std::string::npos);
  CHECK(fs::exists(s / "bones.gltf"));
}

// `deform pose` skins with every weight by default, on the GPU too: the BBW hand (7.3 nonzero weights
// a row on average, 16 at most) in hand-pose.dmat equals skinning with all of the bind's weights within
// 1e-6 of the bbox diagonal for every method; -k 4 (the old default) moves vertices by far more.
TEST_CASE("deform pose: default flags skin with all weights, on the GPU as on the CPU (BBW hand)", "[cli][gl]") {
  DFM_DATA_OR_SKIP(meshfile, "hand.mesh");
  DFM_DATA_OR_SKIP(tgf, "hand.tgf");
  DFM_DATA_OR_SKIP(qfile, "hand-pose.dmat");
  Scratch s("hand_pose");
  const RunResult b = deform(s, {"bind", meshfile, "--skeleton", tgf, "-o", s / "W.dmat"});
  INFO(describe(b));
  REQUIRE(b.exit_code == 0);
  const dfm::TetMesh tets = dfm::read_tet_mesh(meshfile);
  const Eigen::MatrixXd W = dfm::read_dmat(s / "W.dmat");
  dfm::Rig rig;
  dfm::add_tgf_to_rig(rig, dfm::read_tgf(tgf), tgf);
  dfm::PoseParams params = dfm::rest_pose_params(rig);
  params.bone_rotation = dfm::read_bone_rotations(qfile, rig.skeleton.num_bones());
  const dfm::Pose pose = dfm::evaluate_pose(rig, params);
  const dfm::SkinBinding all = dfm::make_skin_binding(tets.V, Eigen::MatrixXd(), W, rig, 0);
  REQUIRE(dfm::sparse_influences(all.influences).max_row > 8);  // rows no fixed k = 8 would hold
  const double diag = (tets.V.colwise().maxCoeff() - tets.V.colwise().minCoeff()).norm();
  const bool display = std::getenv("DISPLAY") != nullptr;
  auto pose_error = [&](const std::string& method, const std::vector<std::string>& extra) {
    std::vector<std::string> a = {"pose", meshfile, "--weights", s / "W.dmat", "--skeleton", tgf, "--pose", qfile,
                                  "--method", method, "-o", s / "posed.obj"};
    a.insert(a.end(), extra.begin(), extra.end());
    const RunResult r = deform(s, a);
    INFO(describe(r));
    REQUIRE(r.exit_code == 0);
    if (display) CHECK(r.out.find("on the GPU") != std::string::npos);
    if (extra.empty()) CHECK(r.out.find("all weights") != std::string::npos);
    const dfm::TriMesh got = dfm::read_surface(s / "posed.obj");
    REQUIRE(got.V.rows() == tets.V.rows());
    const Eigen::MatrixXd ref = dfm::skin(dfm::parse_skin_method(method), all, pose).V;
    return (got.V - ref).rowwise().norm().maxCoeff() / diag;
  };
  for (const char* m : {"lbs", "dqs", "stbs"}) {
    const double e = pose_error(m, {});
    WARN("deform pose --method " << m << " (default flags): max |posed - all-weights " << m << "| = " << e
                                 << " of the bbox diagonal");
    CHECK(e <= 1e-6);
  }
  const double e4 = pose_error("lbs", {"-k", "4"});
  WARN("deform pose -k 4: " << e4 << " of the bbox diagonal from all weights");
  CHECK(e4 > 1e-3);
}

TEST_CASE("deform rejects hostile flags and files with exit 1 or 2 and a message naming them", "[cli][hostile]") {
  DFM_DATA_OR_SKIP(knight, "decimated-knight.off");
  Scratch s("hostile");
  // Valid inputs, so that each case below is wrong in exactly one way.
  write_text(s / "p.txt", kPoints);
  write_text(s / "p.tgf", kPointTgf);
  write_text(s / "bones.tgf", kBoneTgf);
  const RunResult b = deform(s, {"bind", knight, "--points", s / "p.txt", "-o", s / "W.dmat"});
  INFO(describe(b));
  REQUIRE(b.exit_code == 0);
  dfm::write_dmat(s / "W2.dmat", Eigen::MatrixXd::Constant(502, 2, 0.5));     // bone weights
  dfm::write_dmat(s / "Wrows.dmat", Eigen::MatrixXd::Constant(501, 3, 1.0 / 3));  // one row short
  dfm::write_dmat(s / "Wcols.dmat", Eigen::MatrixXd::Constant(502, 4, 0.25));     // one column too many
  write_text(s / "Wnan.dmat", "1 2\n0.5\nnan\n");
  write_text(s / "Wtrunc.dmat", "3 502\n0.1\n0.2\n");
  write_text(s / "q2.dmat", "4 2\n0\n0\n0\n0\n0\n0\n1\n1\n");           // 2 identity rotations, valid
  write_text(s / "q3.dmat", "4 3\n0\n0\n0\n0\n0\n0\n0\n0\n0\n1\n1\n1\n");  // 3 rotations for 2 bones
  write_text(s / "q1.dmat", "1 4\n0\n0\n0\n1\n");                          // 1 rotation for 2 bones
  write_text(s / "qnan.dmat", "4 2\n0\n0\n0\n0\n0\n0\nnan\n1\n");
  write_text(s / "qzero.dmat", "4 2\n0\n0\n0\n0\n0\n0\n0\n1\n");
  write_text(s / "q7.dmat", "1 7\n0\n0\n0\n1\n0\n0\n0\n");  // not a multiple of 4
  write_text(s / "zero.txt", "0 0 0\n0 0 0\n0 0 0\n");
  write_text(s / "pp2.txt", "0 0 0\n0 0 0\n");
  write_text(s / "ppnan.txt", "0 0 0\nnan 0 0\n0 0 0\n");
  write_text(s / "ppinf.txt", "0 0 0\n0 inf 0\n0 0 0\n");
  write_text(s / "pnan.txt", "0.45 0.2 0.5\nnan 0.5 0.5\n");
  write_text(s / "pout.txt", "5 5 5\n");  // outside the knight
  write_text(s / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");  // connectivity differs from the knight
  write_text(s / "nanv.off", "OFF\n3 1 0\nnan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  write_text(s / "infv.obj", "v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n");
  write_text(s / "huge.off", "OFF\n999999999 999999999 0\n");
  write_text(s / "oob.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  write_text(s / "neg.off", "OFF\n-3 1 0\n");
  write_text(s / "garbage.json", "{ this is not json");
  write_text(s / "junk.tet4", "not a manifold\n");
  for (const char* e : {"obj", "off", "ply", "stl", "mesh", "node", "tgf", "dmat", "txt", "json", "tet4"})
    write_text(s / (std::string("empty.") + e), "");
  for (const char* d : {"adir", "adir.obj", "adir.dmat", "adir.glb", "adir.off", "adir.tgf", "adir.txt"})
    fs::create_directories(s.dir / d);
  const std::string W2 = s / "W2.dmat";
  const std::string W = s / "W.dmat", P = s / "p.txt", PT = s / "p.tgf", BT = s / "bones.tgf";
  const std::string nofolder = (s.dir / "no_such_folder").string();

  struct Case {
    std::vector<std::string> args;
    std::string needle;  // must appear in stderr: the flag or the file's name
  };
  const std::vector<Case> cases = {
      // top level
      {{"frobnicate"}, "frobnicate"},
      {{"version", "--bogus"}, "version"},
      // info
      {{"info"}, "info"},
      {{"info", "--bogus"}, "--bogus"},
      {{"info", s / "nosuch.off"}, "nosuch.off"},
      {{"info", s / "adir"}, "adir"},
      {{"info", s / "adir.obj"}, "adir.obj"},
      {{"info", s / "adir.tgf"}, "adir.tgf"},
      {{"info", s / "empty.obj"}, "empty.obj"},
      {{"info", s / "empty.off"}, "empty.off"},
      {{"info", s / "empty.ply"}, "empty.ply"},
      {{"info", s / "empty.stl"}, "empty.stl"},
      {{"info", s / "empty.mesh"}, "empty.mesh"},
      {{"info", s / "empty.node"}, "empty.node"},
      {{"info", s / "empty.tgf"}, "empty.tgf"},
      {{"info", s / "empty.dmat"}, "empty.dmat"},
      {{"info", s / "empty.json"}, "empty.json"},
      {{"info", s / "nanv.off"}, "nanv.off"},
      {{"info", s / "infv.obj"}, "infv.obj"},
      {{"info", s / "huge.off"}, "huge.off"},
      {{"info", s / "oob.off"}, "oob.off"},
      {{"info", s / "neg.off"}, "neg.off"},
      {{"info", s / "Wnan.dmat"}, "Wnan.dmat"},
      {{"info", s / "Wtrunc.dmat"}, "Wtrunc.dmat"},
      {{"info", s / "pnan.txt"}, "pnan.txt"},
      {{"info", knight, s / "nosuch.obj"}, "nosuch.obj"},  // a bad file after a good one still fails
      // bind
      {{"bind"}, "input"},
      {{"bind", knight, "--points", P}, "-o"},
      {{"bind", knight, "--points", P, "-o"}, "-o"},
      {{"bind", knight, "--points", P, "-o", s / "o.dmat", "--bogus"}, "--bogus"},
      {{"bind", knight, "--points", P, "-o", s / "o.dmat", "--threads", "abc"}, "--threads"},
      {{"bind", knight, "--points", P, "-o", s / "o.dmat", "--threads", "0"}, "--threads"},
      {{"bind", knight, "--points", P, "-o", s / "o.dmat", "--threads", "-3"}, "--threads"},
      {{"bind", knight, "--points", P, "-o", s / "o.dmat", "--threads", "nan"}, "--threads"},
      {{"bind", knight, "--points", P, "-o", s / "o.dmat", "--threads", "99999999999"}, "--threads"},
      {{"bind", knight, "--points", P, "-o", s / "o.dmat", "--threads"}, "--threads"},
      {{"bind", knight, "--points", P, "-o", s / "o.dmat", "--tetgen", "pq1.4a-1"}, "pq1.4a-1"},
      {{"bind", knight, "--points", P, "-o", s / "o.dmat", "--segmentation", "magic"}, "--segmentation"},
      {{"bind", knight, "--points", P, "-o", s / "o.dmat", "--segmentation"}, "--segmentation"},
      {{"bind", knight, "-o", s / "o.dmat"}, "handles"},
      {{"bind", knight, knight, "--points", P, "-o", s / "o.dmat"}, "more than one"},
      {{"bind", s / "nosuch.off", "--points", P, "-o", s / "o.dmat"}, "nosuch.off"},
      {{"bind", s / "adir.off", "--points", P, "-o", s / "o.dmat"}, "adir.off"},
      {{"bind", s / "empty.off", "--points", P, "-o", s / "o.dmat"}, "empty.off"},
      {{"bind", s / "empty.mesh", "--points", P, "-o", s / "o.dmat"}, "empty.mesh"},
      {{"bind", s / "nanv.off", "--points", P, "-o", s / "o.dmat"}, "nanv.off"},
      {{"bind", knight, "--points", s / "nosuch.txt", "-o", s / "o.dmat"}, "nosuch.txt"},
      {{"bind", knight, "--points", s / "adir.txt", "-o", s / "o.dmat"}, "adir.txt"},
      {{"bind", knight, "--points", s / "pnan.txt", "-o", s / "o.dmat"}, "pnan.txt"},
      {{"bind", knight, "--points", s / "pout.txt", "-o", s / "o.dmat"}, "point 1"},
      {{"bind", knight, "--skeleton", s / "nosuch.tgf", "-o", s / "o.dmat"}, "nosuch.tgf"},
      {{"bind", knight, "--skeleton", s / "empty.tgf", "-o", s / "o.dmat"}, "empty.tgf"},
      {{"bind", knight, "--cage", s / "nosuch.obj", "-o", s / "o.dmat"}, "nosuch.obj"},
      {{"bind", knight, "--cage", "-o", s / "o.dmat"}, "--cage"},
      {{"bind", knight, "--points", P, "-o", nofolder + "/o.dmat"}, "no_such_folder"},
      {{"bind", knight, "--points", P, "-o", s / "adir.dmat"}, "adir.dmat"},
      {{"bind", knight, "--points", P, "-o", s / "o.dmat", "--tets", nofolder + "/t.mesh"}, "no_such_folder"},
      // pose
      {{"pose"}, "INPUT"},
      {{"pose", knight, "--weights", W, "--skeleton", PT}, "-o"},
      {{"pose", knight, "--skeleton", PT, "-o", s / "o.obj"}, "--weights"},
      {{"pose", knight, "--weights", "--skeleton", PT, "-o", s / "o.obj"}, "--weights"},
      {{"pose", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.obj", "--bogus"}, "--bogus"},
      {{"pose", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.obj", "-k", "0"}, "-k"},
      {{"pose", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.obj", "-k", "99999"}, "-k"},
      {{"pose", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.obj", "-k", "-4"}, "-k"},
      {{"pose", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.obj", "-k", "four"}, "-k"},
      {{"pose", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.obj", "-k", "nan"}, "-k"},
      {{"pose", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.obj", "-k", "4.5"}, "-k"},
      {{"pose", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.obj", "-k"}, "-k"},
      {{"pose", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.obj", "--method", "bogus"}, "bogus"},
      {{"pose", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.xyz"}, "o.xyz"},
      {{"pose", knight, "--weights", W, "-o", s / "o.obj"}, "--skeleton"},
      {{"pose", knight, "--weights", W2, "--pose", s / "q2.dmat", "-o", s / "o.obj"}, "--skeleton"},
      {{"pose", s / "nosuch.off", "--weights", W, "--skeleton", PT, "-o", s / "o.obj"}, "nosuch.off"},
      {{"pose", s / "adir.obj", "--weights", W, "--skeleton", PT, "-o", s / "o.obj"}, "adir.obj"},
      {{"pose", s / "empty.obj", "--weights", W, "--skeleton", PT, "-o", s / "o.obj"}, "empty.obj"},
      {{"pose", knight, "--weights", s / "nosuch.dmat", "--skeleton", PT, "-o", s / "o.obj"}, "nosuch.dmat"},
      {{"pose", knight, "--weights", s / "empty.dmat", "--skeleton", PT, "-o", s / "o.obj"}, "empty.dmat"},
      {{"pose", knight, "--weights", s / "adir.dmat", "--skeleton", PT, "-o", s / "o.obj"}, "adir.dmat"},
      {{"pose", knight, "--weights", s / "Wrows.dmat", "--skeleton", PT, "-o", s / "o.obj"}, "Wrows.dmat"},
      {{"pose", knight, "--weights", s / "Wcols.dmat", "--skeleton", PT, "-o", s / "o.obj"}, "Wcols.dmat"},
      {{"pose", knight, "--weights", s / "Wtrunc.dmat", "--skeleton", PT, "-o", s / "o.obj"}, "Wtrunc.dmat"},
      {{"pose", knight, "--weights", W, "--skeleton", s / "nosuch.tgf", "-o", s / "o.obj"}, "nosuch.tgf"},
      {{"pose", knight, "--weights", W, "--skeleton", s / "adir.tgf", "-o", s / "o.obj"}, "adir.tgf"},
      {{"pose", knight, "--weights", W2, "--skeleton", BT, "--pose", s / "q3.dmat", "-o", s / "o.obj"}, "q3.dmat"},
      {{"pose", knight, "--weights", W2, "--skeleton", BT, "--pose", s / "q1.dmat", "-o", s / "o.obj"}, "q1.dmat"},
      {{"pose", knight, "--weights", W2, "--skeleton", BT, "--pose", s / "q7.dmat", "-o", s / "o.obj"}, "q7.dmat"},
      {{"pose", knight, "--weights", W2, "--skeleton", BT, "--pose", s / "qnan.dmat", "-o", s / "o.obj"}, "qnan.dmat"},
      {{"pose", knight, "--weights", W2, "--skeleton", BT, "--pose", s / "qzero.dmat", "-o", s / "o.obj"}, "qzero.dmat"},
      {{"pose", knight, "--weights", W2, "--skeleton", BT, "--pose", s / "empty.dmat", "-o", s / "o.obj"}, "empty.dmat"},
      {{"pose", knight, "--weights", W, "--skeleton", PT, "--points-pose", s / "pp2.txt", "-o", s / "o.obj"}, "pp2.txt"},
      {{"pose", knight, "--weights", W, "--skeleton", PT, "--points-pose", s / "ppnan.txt", "-o", s / "o.obj"}, "ppnan.txt"},
      {{"pose", knight, "--weights", W, "--skeleton", PT, "--points-pose", s / "ppinf.txt", "-o", s / "o.obj"}, "ppinf.txt"},
      {{"pose", knight, "--weights", W, "--skeleton", PT, "--points-pose", s / "nosuch.txt", "-o", s / "o.obj"}, "nosuch.txt"},
      {{"pose", knight, "--weights", W, "--skeleton", PT, "--cpu", "-o", nofolder + "/o.obj"}, "no_such_folder"},
      {{"pose", knight, "--weights", W, "--skeleton", PT, "--cpu", "-o", s / "adir.obj"}, "adir.obj"},
      // manifold
      {{"manifold"}, "--keyframes"},
      {{"manifold", "--bogus"}, "--bogus"},
      {{"manifold", "--keyframes"}, "--keyframes"},
      {{"manifold", "--keyframes", knight, "--at", "0.5", "--stats"}, "--keyframes"},
      {{"manifold", "--keyframes", knight, knight}, "nothing to do"},
      {{"manifold", "--keyframes", knight, knight, "--at"}, "--at"},
      {{"manifold", "--keyframes", knight, knight, "--at", "abc", "--stats"}, "--at"},
      {{"manifold", "--keyframes", knight, knight, "--at", "nan", "--stats"}, "--at"},
      {{"manifold", "--keyframes", knight, knight, "--at", "inf", "--stats"}, "--at"},
      {{"manifold", "--keyframes", knight, knight, "--at", "-inf", "--stats"}, "--at"},
      {{"manifold", "--keyframes", knight, knight, "--at", "1e999", "--stats"}, "--at"},
      {{"manifold", "--keyframes", knight, knight, "--at", "0.5"}, "-o"},
      {{"manifold", "--keyframes", knight, knight, "--axis", "w", "--at", "0.5", "--stats"}, "w"},
      {{"manifold", "--keyframes", knight, knight, "--times", "0", "--at", "0.5", "--stats"}, "--times"},
      {{"manifold", "--keyframes", knight, knight, "--times", "1", "1", "--at", "0.5", "--stats"}, "--times"},
      {{"manifold", "--keyframes", knight, knight, "--times", "0", "nan", "--at", "0.5", "--stats"}, "--times"},
      {{"manifold", "--keyframes", knight, knight, "--times", "0", "inf", "--at", "0.5", "--stats"}, "--times"},
      {{"manifold", "--keyframes", knight, knight, "--frames", "-1", "--sequence", s / "seq"}, "--frames"},
      {{"manifold", "--keyframes", knight, knight, "--frames", "0", "--sequence", s / "seq"}, "--frames"},
      {{"manifold", "--keyframes", knight, knight, "--frames", "abc", "--sequence", s / "seq"}, "--frames"},
      {{"manifold", "--keyframes", knight, knight, "--frames", "99999999999", "--sequence", s / "seq"}, "--frames"},
      {{"manifold", "--keyframes", knight, knight, "--frames", "3"}, "--frames"},
      {{"manifold", "--keyframes", knight, knight, "--sequence", s / "seq"}, "--frames"},
      {{"manifold", "--keyframes", knight, s / "tri.obj", "--at", "0.5", "--stats"}, "tri.obj"},
      {{"manifold", "--keyframes", knight, s / "nosuch.obj", "--at", "0.5", "--stats"}, "nosuch.obj"},
      {{"manifold", "--keyframes", knight, s / "adir.obj", "--at", "0.5", "--stats"}, "adir.obj"},
      {{"manifold", "--keyframes", knight, s / "empty.obj", "--at", "0.5", "--stats"}, "empty.obj"},
      {{"manifold", "--keyframes", knight, s / "nanv.off", "--at", "0.5", "--stats"}, "nanv.off"},
      {{"manifold", "--manifold", s / "nosuch.tet4", "--at", "0.5", "--stats"}, "nosuch.tet4"},
      {{"manifold", "--manifold", s / "empty.tet4", "--at", "0.5", "--stats"}, "empty.tet4"},
      {{"manifold", "--manifold", s / "junk.tet4", "--at", "0.5", "--stats"}, "junk.tet4"},
      {{"manifold", "--manifold", s / "adir", "--at", "0.5", "--stats"}, "adir"},
      {{"manifold", "--manifold", s / "junk.tet4", "--keyframes", knight, knight, "--at", "0", "--stats"}, "--keyframes"},
      {{"manifold", "--keyframes", knight, knight, "--at", "0.5", "-o", nofolder + "/s.obj"}, "no_such_folder"},
      {{"manifold", "--keyframes", knight, knight, "--at", "0.5", "-o", s / "adir.obj"}, "adir.obj"},
      {{"manifold", "--keyframes", knight, knight, "--save-manifold", nofolder + "/m.tet4"}, "no_such_folder"},
      {{"manifold", "--keyframes", knight, knight, "--frames", "2", "--sequence", nofolder + "/seq"}, "no_such_folder"},
      // export
      {{"export"}, "INPUT"},
      {{"export", knight, "--weights", W, "--skeleton", PT}, "-o"},
      {{"export", knight, "--weights", W, "--skeleton", PT, "-o"}, "-o"},
      {{"export", knight, "--skeleton", PT, "-o", s / "o.glb"}, "--weights"},
      {{"export", knight, "--weights", W, "-o", s / "o.glb"}, "--skeleton"},
      {{"export", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.glb", "--bogus"}, "--bogus"},
      {{"export", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.fbx"}, "-o"},
      {{"export", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.glb", "-k", "0"}, "-k"},
      {{"export", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.glb", "-k", "99999"}, "-k"},
      {{"export", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.glb", "-k", "nan"}, "-k"},
      {{"export", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.glb", "--morph-frames", "-1"}, "--morph-frames"},
      {{"export", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.glb", "--morph-frames", "1"}, "--morph-frames"},
      {{"export", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.glb", "--morph-frames", "x"}, "--morph-frames"},
      {{"export", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.glb", "--morph-frames", "4"}, "--morph-frames"},
      {{"export", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.glb", "--key-seconds", "nan"}, "--key-seconds"},
      {{"export", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.glb", "--key-seconds", "inf"}, "--key-seconds"},
      {{"export", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.glb", "--key-seconds", "-1"}, "--key-seconds"},
      {{"export", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.glb", "--key-seconds", "0"}, "--key-seconds"},
      {{"export", knight, "--weights", W, "--skeleton", PT, "-o", s / "o.glb", "--key-seconds"}, "--key-seconds"},
      {{"export", s / "nosuch.off", "--weights", W, "--skeleton", PT, "-o", s / "o.glb"}, "nosuch.off"},
      {{"export", s / "adir.off", "--weights", W, "--skeleton", PT, "-o", s / "o.glb"}, "adir.off"},
      {{"export", s / "empty.off", "--weights", W, "--skeleton", PT, "-o", s / "o.glb"}, "empty.off"},
      {{"export", knight, "--weights", s / "Wrows.dmat", "--skeleton", PT, "-o", s / "o.glb"}, "Wrows.dmat"},
      {{"export", knight, "--weights", s / "Wcols.dmat", "--skeleton", PT, "-o", s / "o.glb"}, "Wcols.dmat"},
      {{"export", knight, "--weights", s / "empty.dmat", "--skeleton", PT, "-o", s / "o.glb"}, "empty.dmat"},
      {{"export", knight, "--weights", s / "nosuch.dmat", "--skeleton", PT, "-o", s / "o.glb"}, "nosuch.dmat"},
      {{"export", knight, "--weights", W, "--skeleton", s / "empty.tgf", "-o", s / "o.glb"}, "empty.tgf"},
      {{"export", knight, "-o", s / "o.glb", "--weights", W2, "--skeleton", BT, "--pose", s / "q3.dmat"}, "q3.dmat"},
      {{"export", knight, "--weights", W2, "--skeleton", BT, "--pose", s / "q3.dmat", "-o", s / "o.glb"}, "q3.dmat"},
      {{"export", knight, "-o", s / "o.glb", "--weights", W2, "--skeleton", BT, "--pose", s / "qnan.dmat"}, "qnan.dmat"},
      {{"export", knight, "-o", s / "o.glb", "--weights", W2, "--skeleton", BT, "--pose", s / "q2.dmat", s / "q3.dmat"}, "q3.dmat"},
      {{"export", knight, "-o", s / "o.glb", "--weights", W2, "--skeleton", BT, "--pose", s / "q2.dmat", s / "nosuch.dmat"}, "nosuch.dmat"},
      {{"export", knight, "-o", s / "o.glb", "--weights", W2, "--skeleton", BT, "--pose", "--verify"}, "--pose"},
      {{"export", knight, "-o", s / "o.glb", "--weights", W2, "--skeleton", BT, "--points", s / "pp2.txt", "--pose", s / "q2.dmat"}, "pp2.txt"},
      {{"export", s / "garbage.json", "-o", s / "o.glb"}, "garbage.json"},
      {{"export", s / "empty.json", "-o", s / "o.glb"}, "empty.json"},
      {{"export", s / "nosuch.json", "-o", s / "o.glb"}, "nosuch.json"},
      {{"export", s / "garbage.json", "--weights", W, "-o", s / "o.glb"}, "scene"},
      {{"export", knight, "--weights", W, "--skeleton", PT, "-o", nofolder + "/o.glb"}, "no_such_folder"},
      {{"export", knight, "--weights", W, "--skeleton", PT, "-o", s / "adir.glb"}, "adir.glb"},
  };
  std::map<std::string, int> count;
  int failed = 0;
  for (const Case& c : cases) {
    const RunResult r = deform(s, c.args);
    const std::string sub = c.args.empty() ? "(none)" : c.args[0];
    ++count[sub == "frobnicate" || sub == "version" ? "top-level/version" : sub];
    // The needle must be in the first line: the usage text that follows names every flag.
    const std::string first = r.err.substr(0, r.err.find('\n'));
    const bool ok = !r.signaled && (r.exit_code == 1 || r.exit_code == 2) && first.find(c.needle) != std::string::npos;
    if (!ok) {
      ++failed;
      FAIL_CHECK("hostile invocation not rejected cleanly (exit 1-2, stderr's first line naming '" << c.needle << "'):\n" << describe(r));
    }
  }
  // No temporary files (".NAME.tmpNNN") were left behind by the rejected saves.
  for (const auto& e : fs::directory_iterator(s.dir)) {
    const std::string n = e.path().filename().string();
    INFO(n);
    CHECK(n.find(".tmp") == std::string::npos);
  }
  // Once-known problems, now fixed: an empty points file is named; a flag is never taken as a value.
  const std::vector<Case> known = {
      // An empty --points file is read as zero points: the error says "no handles" without naming it.
      {{"bind", knight, "--points", s / "empty.txt", "-o", s / "o.dmat"}, "empty.txt"},
      // ArgReader::value takes a single-dash flag as a value: "--points -o W" reads points from "-o".
      {{"bind", knight, "--points", "-o", s / "o.dmat"}, "--points"},
  };
  for (const Case& c : known) {
    const RunResult r = deform(s, c.args);
    CHECK(!r.signaled);
    CHECK(r.exit_code != 0);
    const std::string first = r.err.substr(0, r.err.find('\n'));
    INFO(describe(r));
    CHECK(first.find(c.needle) != std::string::npos);
  }
  std::ostringstream summary;
  summary << "hostile invocations: " << cases.size() << " (";
  for (const auto& [k, n] : count) summary << k << " " << n << ", ";
  summary << "rejected cleanly: " << cases.size() - failed << ")";
  std::cout << "test_cli: " << summary.str() << "\n";
  INFO(summary.str());
  CHECK(failed == 0);
}

TEST_CASE("deform: a failed save (full disk) leaves the previous output intact", "[cli][atomic]") {
  DFM_DATA_OR_SKIP(knight, "decimated-knight.off");
  Scratch s("atomic");
  write_text(s / "p.txt", kPoints);
  write_text(s / "p.tgf", kPointTgf);
  REQUIRE(deform(s, {"bind", knight, "--points", s / "p.txt", "-o", s / "W.dmat"}).exit_code == 0);
  REQUIRE(deform(s, {"pose", knight, "--weights", s / "W.dmat", "--skeleton", s / "p.tgf", "--cpu", "-o",
                     s / "a.obj"}).exit_code == 0);
  const std::string previous = "previous contents that must survive\n";
  dfm::test::RunOptions full_disk;
  full_disk.max_file_bytes = 4096;  // every output below is larger: the write fails with EFBIG
  struct Save {
    std::vector<std::string> args;
    std::string target;
    std::string needle;  // what the error must name; empty: the target
  };
  const std::vector<Save> saves = {
      // bind's first write is TetGen's scratch input, which fails first.
      {{"bind", knight, "--points", s / "p.txt", "-o", s / "keep.dmat"}, "keep.dmat", "cannot write"},
      {{"pose", knight, "--weights", s / "W.dmat", "--skeleton", s / "p.tgf", "--cpu", "-o", s / "keep.obj"}, "keep.obj"},
      {{"pose", knight, "--weights", s / "W.dmat", "--skeleton", s / "p.tgf", "--cpu", "-o", s / "keep.ply"}, "keep.ply"},
      {{"manifold", "--keyframes", s / "a.obj", knight, "--at", "0.5", "-o", s / "keep.obj"}, "keep.obj"},
      {{"manifold", "--keyframes", s / "a.obj", knight, "--save-manifold", s / "keep.tet4"}, "keep.tet4"},
      {{"export", knight, "--weights", s / "W.dmat", "--skeleton", s / "p.tgf", "-o", s / "keep.glb"}, "keep.glb"},
  };
  auto listing = [&] {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(s.dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  };
  for (const Save& sv : saves) {
    write_text(s / sv.target, previous);
    const std::vector<std::string> before = listing();
    const RunResult r = deform(s, sv.args, full_disk);
    INFO(describe(r));
    CHECK(!r.signaled);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find(sv.needle.empty() ? sv.target : sv.needle) != std::string::npos);
    CHECK(dfm::test::slurp(s.dir / sv.target) == previous);
    CHECK(listing() == before);  // no temporary file left beside the target
  }
  // A run that fails before saving (weights of the wrong size) leaves the output intact too.
  dfm::write_dmat(s / "short.dmat", Eigen::MatrixXd::Constant(10, 3, 1.0 / 3));
  write_text(s / "keep.obj", previous);
  const RunResult bad = deform(s, {"pose", knight, "--weights", s / "short.dmat", "--skeleton", s / "p.tgf", "--cpu",
                                   "-o", s / "keep.obj"});
  CHECK(bad.exit_code == 1);
  CHECK(dfm::test::slurp(s.dir / "keep.obj") == previous);
  // Without the limit the same save replaces the file.
  const RunResult ok = deform(s, saves[1].args);
  INFO(describe(ok));
  CHECK(ok.exit_code == 0);
  CHECK(dfm::read_surface(s / "keep.obj").V.rows() == 502);
}
