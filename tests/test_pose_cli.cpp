// `deform pose` end to end: files in, posed surface out, compared with the CPU reference.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <catch2/catch.hpp>

#include "core/mesh/io.h"
#include "core/rig/pose_io.h"
#include "core/rig/pose_params.h"
#include "core/rig/rig_io.h"
#include "core/skin/skin.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;
namespace fs = std::filesystem;

namespace {

int run_deform(const std::string& args) {
  const std::string cmd = std::string(DFM_DEFORM_EXE) + " " + args + " > /dev/null 2>&1";
  const int rc = std::system(cmd.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

// A tube along x from 0 to 2 (rings of 8 vertices, open ends) with two bones 0 -> 1 -> 2 and weights
// blending across the middle joint, written to dir as tube.obj, s.tgf and w.dmat.
struct Tube {
  TriMesh mesh;
  Rig rig;
  Eigen::MatrixXd W;
};

Tube write_tube(const fs::path& dir) {
  Tube t;
  const int rings = 21, around = 8;
  TriMesh& tube = t.mesh;
  tube.V.resize(rings * around, 3);
  tube.F.resize((rings - 1) * around * 2, 3);
  for (int r = 0; r < rings; ++r)
    for (int a = 0; a < around; ++a) {
      const double th = 2.0 * 3.14159265358979 * a / around;
      tube.V.row(r * around + a) << 2.0 * r / (rings - 1), 0.2 * std::cos(th), 0.2 * std::sin(th);
    }
  int f = 0;
  for (int r = 0; r + 1 < rings; ++r)
    for (int a = 0; a < around; ++a) {
      const int i = r * around + a, j = r * around + (a + 1) % around;
      tube.F.row(f++) << i, j, j + around;
      tube.F.row(f++) << i, j + around, i + around;
    }
  write_surface((dir / "tube.obj").string(), tube);
  TgfData tgf;
  tgf.joints.resize(3, 3);
  tgf.joints << 0, 0, 0, 1, 0, 0, 2, 0, 0;
  tgf.edges.resize(2, 2);
  tgf.edges << 0, 1, 1, 2;
  tgf.flags.resize(2, 3);
  tgf.flags << 1, 0, 0, 1, 0, 0;
  write_tgf((dir / "s.tgf").string(), tgf);
  add_tgf_to_rig(t.rig, read_tgf((dir / "s.tgf").string()), "s.tgf");
  REQUIRE(t.rig.skeleton.num_bones() == 2);
  t.W.resize(tube.V.rows(), 2);
  for (int i = 0; i < t.W.rows(); ++i) {
    const double s = std::clamp((tube.V(i, 0) - 0.6) / 0.8, 0.0, 1.0);  // blend across the middle joint
    t.W.row(i) << 1 - s, s;
  }
  write_dmat((dir / "w.dmat").string(), t.W);
  return t;
}

}  // namespace

TEST_CASE("deform pose: a bent two-bone tube saved by extension equals the CPU reference", "[pose][cli]") {
  const fs::path dir = fs::temp_directory_path() / ("dfm_test_pose_cli_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const Tube t = write_tube(dir);
  const TriMesh& tube = t.mesh;
  const Rig& rig = t.rig;
  const Eigen::MatrixXd& W = t.W;
  const std::vector<Eigen::Quaterniond> q = {Eigen::Quaterniond::Identity(),
                                             Eigen::Quaterniond(Eigen::AngleAxisd(1.2, Eigen::Vector3d::UnitZ()))};
  write_bone_rotations((dir / "q.dmat").string(), q);

  PoseParams params = rest_pose_params(rig);
  params.bone_rotation = q;
  const Pose pose = evaluate_pose(rig, params);
  const SkinBinding b = make_skin_binding(tube.V, Eigen::MatrixXd(), W, rig, 4);
  const std::string common = (dir / "tube.obj").string() + " --weights " + (dir / "w.dmat").string() +
                             " --skeleton " + (dir / "s.tgf").string() + " --pose " + (dir / "q.dmat").string();
  for (const char* method : {"lbs", "dqs", "stbs"})
    for (const char* ext : {"obj", "off", "ply", "stl"}) {
      INFO(method << " ." << ext);
      const std::string out = (dir / (std::string("out.") + ext)).string();
      REQUIRE(run_deform("pose " + common + " --cpu --method " + method + " -o " + out) == 0);
      const TriMesh got = read_surface(out);
      const Eigen::MatrixXd ref = skin(parse_skin_method(method), b, pose).V;
      if (std::string(ext) == "stl") {  // STL stores triangle corners, not shared vertices
        REQUIRE(got.num_faces() == tube.num_faces());
        continue;
      }
      REQUIRE(got.F == tube.F);  // same faces, same vertex order
      REQUIRE((got.V - ref).cwiseAbs().maxCoeff() < 1e-6);
      REQUIRE((got.V - tube.V).cwiseAbs().maxCoeff() > 0.1);  // it did move
    }
  // Bad usage -> 2; bad data -> 1, and the previous output survives.
  REQUIRE(run_deform("pose " + common + " --method nope -o " + (dir / "x.obj").string()) == 2);
  REQUIRE(run_deform("pose " + common + " -k 5 -o " + (dir / "x.obj").string()) == 2);
  REQUIRE(run_deform("pose " + common + " -o " + (dir / "x.txt").string()) == 2);
  write_dmat((dir / "bad.dmat").string(), Eigen::MatrixXd::Ones(3, 2));
  REQUIRE(run_deform("pose " + (dir / "tube.obj").string() + " --weights " + (dir / "bad.dmat").string() +
                     " --skeleton " + (dir / "s.tgf").string() + " --cpu -o " + (dir / "out.obj").string()) == 1);
  REQUIRE(read_surface((dir / "out.obj").string()).num_vertices() == tube.num_vertices());
  fs::remove_all(dir);
}

TEST_CASE("deform pose --twist-stretch: a stretch moves what hangs below by the closed form; STBS turns the tip by the twist",
          "[pose][cli]") {
  const fs::path dir = fs::temp_directory_path() / ("dfm_test_pose_ts_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const Tube t = write_tube(dir);
  const std::string common = (dir / "tube.obj").string() + " --weights " + (dir / "w.dmat").string() + " --skeleton " +
                             (dir / "s.tgf").string() + " --cpu";
  Eigen::MatrixXd ts(2, 2);
  ts << 0, 1.5,  // the first bone 1.5 times as long: the second follows by 0.5 along x
      180, 1;    // the second twisted half a turn at its end
  write_dmat((dir / "ts.dmat").string(), ts);
  for (const char* method : {"lbs", "stbs"}) {
    INFO(method);
    const std::string out = (dir / "out.obj").string();
    REQUIRE(run_deform("pose " + common + " --twist-stretch " + (dir / "ts.dmat").string() + " --method " + method +
                       " -o " + out) == 0);
    const TriMesh got = read_surface(out);
    REQUIRE(got.V.rows() == t.mesh.V.rows());
    for (int i = 0; i < got.V.rows(); ++i) {
      const Eigen::RowVector3d p = t.mesh.V.row(i);
      if (p.x() < 1.4) continue;  // the second bone's alone
      // LBS moves it rigidly with the bone (the whole twist); STBS by its endpoint weight, 1 at the tip.
      const bool turned = std::string(method) == "lbs" || p.x() > 2 - 1e-12;
      const Eigen::RowVector3d want(p.x() + 0.5, turned ? -p.y() : p.y(), turned ? -p.z() : p.z());
      if (turned || p.x() > 2 - 1e-12) CHECK((got.V.row(i) - want).norm() < 1e-6);
    }
  }
  // A third column twists the bone at its first joint too (Eq. 6.5): 180 degrees at both ends turns
  // every vertex of the second bone alone, under STBS as under LBS.
  Eigen::MatrixXd ts3(2, 3);
  ts3 << 0, 1.5, 0, 180, 1, 180;
  write_dmat((dir / "ts3.dmat").string(), ts3);
  REQUIRE(run_deform("pose " + common + " --twist-stretch " + (dir / "ts3.dmat").string() + " --method stbs -o " +
                     (dir / "out3.obj").string()) == 0);
  const TriMesh got3 = read_surface((dir / "out3.obj").string());
  int second = 0;
  for (int i = 0; i < got3.V.rows(); ++i) {
    const Eigen::RowVector3d p = t.mesh.V.row(i);
    if (p.x() < 1.4) continue;
    ++second;
    CHECK((got3.V.row(i) - Eigen::RowVector3d(p.x() + 0.5, -p.y(), -p.z())).norm() < 1e-6);
  }
  CHECK(second > 10);
  // A file of the wrong shape, a stretch that is not positive: exit 1 naming the file.
  write_dmat((dir / "short.dmat").string(), Eigen::MatrixXd::Ones(1, 2));
  CHECK(run_deform("pose " + common + " --twist-stretch " + (dir / "short.dmat").string() + " -o " + (dir / "x.obj").string()) == 1);
  ts(1, 1) = 0;
  write_dmat((dir / "zero.dmat").string(), ts);
  CHECK(run_deform("pose " + common + " --twist-stretch " + (dir / "zero.dmat").string() + " -o " + (dir / "x.obj").string()) == 1);
  CHECK(run_deform("pose " + (dir / "tube.obj").string() + " --weights " + (dir / "w.dmat").string() + " --points " +
                   (dir / "p.txt").string() + " --twist-stretch " + (dir / "ts.dmat").string() + " -o " + (dir / "x.obj").string()) == 2);
  fs::remove_all(dir);
}

TEST_CASE("deform bind --endpoints, deform pose --endpoints: the bind's endpoint weights carry to STBS", "[pose][cli][stbs]") {
  const fs::path dir = fs::temp_directory_path() / ("dfm_test_pose_ep_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  // A closed capsule-like ellipsoid along x around the tube's two bones (0 -> 1 -> 2).
  TriMesh body = test::icosphere(Eigen::Vector3d(1, 0, 0), 1.0, 3);
  body.V.col(0) = (body.V.col(0).array() - 1) * 1.2 + 1;
  body.V.col(1) *= 0.3;
  body.V.col(2) *= 0.3;
  write_surface((dir / "body.obj").string(), body);
  write_tube(dir);  // s.tgf
  const std::string s = (dir / "s.tgf").string();
  REQUIRE(run_deform("bind " + (dir / "body.obj").string() + " --skeleton " + s + " -o " + (dir / "w.dmat").string() +
                     " --endpoints " + (dir / "e.dmat").string()) == 0);
  const Eigen::MatrixXd W = read_dmat((dir / "w.dmat").string()), E = read_dmat((dir / "e.dmat").string());
  REQUIRE(E.rows() == body.V.rows());
  REQUIRE(E.cols() == 2);
  CHECK(E.minCoeff() >= 0);
  CHECK(E.maxCoeff() <= 1);
  Eigen::MatrixXd ts(2, 2);
  ts << 0, 1, 90, 1;
  write_dmat((dir / "ts.dmat").string(), ts);
  const std::string out = (dir / "out.obj").string();
  REQUIRE(run_deform("pose " + (dir / "body.obj").string() + " --weights " + (dir / "w.dmat").string() + " --skeleton " + s +
                     " --twist-stretch " + (dir / "ts.dmat").string() + " --endpoints " + (dir / "e.dmat").string() +
                     " --method stbs --cpu -o " + out) == 0);
  Rig rig;
  add_tgf_to_rig(rig, read_tgf(s), "s.tgf");
  PoseParams p = rest_pose_params(rig);
  p.bone_twist_stretch = read_bone_twist_stretch((dir / "ts.dmat").string(), 2);
  const SkinBinding with = make_skin_binding(body.V, Eigen::MatrixXd(), W, rig, 0, E);
  const SkinBinding without = make_skin_binding(body.V, Eigen::MatrixXd(), W, rig, 0);
  const Pose pose = evaluate_pose(rig, p);
  const auto st = stbs_handles(rig, p.bone_twist_stretch);
  const Eigen::MatrixXd got = read_surface(out).V;
  CHECK((got - skin(SkinMethod::STBS, with, pose, st).V).cwiseAbs().maxCoeff() < 1e-6);
  CHECK((got - skin(SkinMethod::STBS, without, pose, st).V).cwiseAbs().maxCoeff() > 1e-3);  // they differ
  // Hostile: the wrong shape, values out of [0, 1].
  write_dmat((dir / "bad.dmat").string(), Eigen::MatrixXd::Constant(body.V.rows(), 2, 1.5));
  CHECK(run_deform("pose " + (dir / "body.obj").string() + " --weights " + (dir / "w.dmat").string() + " --skeleton " + s +
                   " --endpoints " + (dir / "bad.dmat").string() + " --method stbs --cpu -o " + out) == 1);
  write_dmat((dir / "bad.dmat").string(), Eigen::MatrixXd::Zero(3, 2));
  CHECK(run_deform("pose " + (dir / "body.obj").string() + " --weights " + (dir / "w.dmat").string() + " --skeleton " + s +
                   " --endpoints " + (dir / "bad.dmat").string() + " --method stbs --cpu -o " + out) == 1);
  fs::remove_all(dir);
}

TEST_CASE("deform transfer-weights: onto the source itself the weights come back; bad input exits 1 or 2", "[cli][transfer]") {
  const fs::path dir = fs::temp_directory_path() / ("dfm_test_transfer_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const TriMesh s = test::icosphere(Eigen::Vector3d::Zero(), 1.0, 2);
  write_surface((dir / "s.obj").string(), s);
  Eigen::MatrixXd W(s.V.rows(), 2);
  for (int i = 0; i < W.rows(); ++i) W.row(i) << 0.5 + 0.5 * s.V(i, 0), 0.5 - 0.5 * s.V(i, 0);
  write_dmat((dir / "w.dmat").string(), W);
  const std::string common = (dir / "s.obj").string() + " --weights " + (dir / "w.dmat").string() + " " + (dir / "s.obj").string();
  REQUIRE(run_deform("transfer-weights " + common + " -o " + (dir / "t.dmat").string()) == 0);
  CHECK((read_dmat((dir / "t.dmat").string()) - W).cwiseAbs().maxCoeff() < 1e-12);  // the .dmat text keeps 17 digits or so
  CHECK(run_deform("transfer-weights " + common) == 2);  // no -o
  CHECK(run_deform("transfer-weights " + common + " --angle 200 -o " + (dir / "t.dmat").string()) == 2);
  write_dmat((dir / "short.dmat").string(), W.topRows(5));
  CHECK(run_deform("transfer-weights " + (dir / "s.obj").string() + " --weights " + (dir / "short.dmat").string() + " " +
                   (dir / "s.obj").string() + " -o " + (dir / "t.dmat").string()) == 1);
  fs::remove_all(dir);
}
