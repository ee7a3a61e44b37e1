// Rigged, animated FBX and Collada files as scenes, and BVH motion onto a rig or alone, through Assimp
// (core/export/assimp_scene_import.h, bvh_motion.h; issue 32), checked against what Blender 3.4 itself
// evaluated: ../shared/data/rigged/elephant.{fbx,dae,bvh} and elephant_frameNNN.obj (Blender's posed
// meshes in elephant.obj's coordinates). Vertices are matched by their rest positions.
// Time of Blender's frame f: (f - 1) / 24 s in its FBX (the file's first key is at 0), f / 24 s in its
// Collada (as in its glb), (f - 1) * Frame Time in its BVH.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include <unistd.h>

#include "core/export/assimp_scene_import.h"
#include "core/export/bvh_motion.h"
#include "core/export/gltf_scene_import.h"
#include "core/mesh/io.h"
#include "core/rig/forward_kinematics.h"
#include "core/rig/pose_params.h"
#include "core/scene/scene_file.h"
#include "core/scene/script.h"
#include "core/util/error.h"
#include "tests/cli_test_util.h"
#include "tests/rigged_test_util.h"
#include "tests/test_support.h"

using namespace dfm;
using dfm::test::diagonal;
using dfm::test::nearest;

namespace {

struct Distance {
  double worst = 0, mean = 0;
};
Distance distance(const Eigen::MatrixXd& ref, const Eigen::MatrixXd& V, const std::vector<int>& m) {
  Distance d;
  for (Eigen::Index i = 0; i < ref.rows(); ++i) {
    const double e = (ref.row(i) - V.row(m[i])).norm();
    d.worst = std::max(d.worst, e);
    d.mean += e / ref.rows();
  }
  return d;
}

std::string frame_file(int f) {
  char name[40];
  std::snprintf(name, sizeof name, "rigged/elephant_frame%03d.obj", f);
  return test::data_file(name);
}

std::filesystem::path temp_dir(const std::string& tag) {
  const std::filesystem::path d = std::filesystem::temp_directory_path() / ("dfm_assimp_" + tag + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

// Per frame, the bones whose keys the file lacks there although they move (with the bones below them).
using Unkeyed = std::map<int, std::vector<int>>;

// Imports `file` and checks it against Blender's frames; `time(f)` is frame f's time in that file.
// Vertices that an `unkeyed` bone moves are measured apart: the file interpolates its keys there.
void check_against_blender(const std::string& file, double (*time)(int), const Unkeyed& unkeyed = {}) {
  DFM_DATA_OR_SKIP(rest_obj, "elephant.obj");
  register_assimp_scene_importers();
  Document doc;
  const std::string report = doc.import_scene(file);
  INFO(report);
  const TriMesh rest = read_surface(rest_obj);
  const double diag = diagonal(rest.V);
  REQUIRE(doc.rig().skeleton.num_bones() == 24);
  for (int b = 0; b < 24; ++b) {
    char name[16];
    std::snprintf(name, sizeof name, "bone_%02d", b);
    CHECK(doc.rig().skeleton.bones[b].name == name);
  }
  // The rest pose is elephant.obj (to the file's float precision), welded to its vertex count.
  CHECK(doc.surface().V.rows() == rest.V.rows());
  const std::vector<int> m = nearest(rest.V, doc.surface().V);
  CHECK(distance(rest.V, doc.surface().V, m).worst <= 1e-6 * diag);
  const Eigen::MatrixXd& W = doc.weights();
  CHECK(W.minCoeff() >= 0);
  CHECK((W.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-12);
  REQUIRE(doc.keys().size() >= 3);
  for (int f : {1, 15, 30, 60}) {
    const std::string ref_path = frame_file(f);
    if (ref_path.empty()) return;
    const TriMesh ref = read_surface(ref_path);
    doc.set_time(time(f));
    const TriMesh posed = posed_surface(doc);
    const Distance d = distance(ref.V, posed.V, m);
    WARN(file << " frame " << f << " (t = " << time(f) << " s): largest distance from Blender's " << d.worst / diag << ", mean "
              << d.mean / diag << " of the diagonal");
    const auto u = unkeyed.find(f);
    if (u == unkeyed.end()) {
      CHECK(d.worst <= 1e-5 * diag);
      continue;
    }
    double keyed = 0, moved = 0;
    for (Eigen::Index i = 0; i < ref.V.rows(); ++i) {
      double w = 0;
      for (int b : u->second) w += W(m[i], b);
      const double e = (ref.V.row(i) - posed.V.row(m[i])).norm();
      (w > 0 ? moved : keyed) = std::max(w > 0 ? moved : keyed, e);
    }
    WARN("  vertices no unkeyed bone moves: largest " << keyed / diag << "; the others: largest " << moved / diag);
    CHECK(keyed <= 1e-5 * diag);
    CHECK(moved <= 1e-3 * diag);  // the file's interpolation between the keys Blender kept
  }
}

double fbx_time(int f) { return (f - 1) / 24.0; }
double dae_time(int f) { return f / 24.0; }

}  // namespace

TEST_CASE("FBX import: Blender's elephant posed at frames 1, 15, 30 and 60 as Blender evaluated it", "[assimp][import][data]") {
  DFM_DATA_OR_SKIP(fbx, "rigged/elephant.fbx");
  RigImportReport rep;
  const SceneData s = import_assimp_scene(fbx, &rep);
  INFO(rep.text());
  CHECK(rep.bones_to_end == 5);  // the five leaf bones end at Blender's *_end nodes, no bones of them
  CHECK(rep.influences <= 4);
  CHECK(s.keys.size() == 60);
  CHECK(s.keys.front().time == Approx(0));
  CHECK(s.keys.back().time == Approx(59 / 24.0));
  // Blender's FBX export simplifies its baked keys (bake_anim_simplify_factor 1.0 by default), each
  // Euler angle's curve on its own: it drops a key that the neighbours' straight line nearly gives, and
  // the file says LINEAR (KeyAttrFlags 0x6104). Read from the file's curves: at frame 15 bone_11's,
  // bone_16's and bone_21's X angle have no key (a line from frame 1 to 30 or 31), at frame 30 bone_07's
  // X and Y, bone_11's X and Y and bone_20's X (their turning points: frames 29 and 31 are kept). There
  // the file itself is not Blender's Bezier curve; those bones and the ones below them are measured
  // apart. Every other bone is keyed at those frames or still.
  check_against_blender(fbx, fbx_time, Unkeyed{{15, {11, 12, 13, 16, 17, 18, 21, 22, 23}}, {30, {7, 8, 9, 11, 12, 13, 20, 21, 22, 23}}});
}

TEST_CASE("Collada import: Blender's elephant posed at frames 1, 15, 30 and 60 as Blender evaluated it", "[assimp][import][data]") {
  DFM_DATA_OR_SKIP(dae, "rigged/elephant.dae");
  RigImportReport rep;
  const SceneData s = import_assimp_scene(dae, &rep);
  INFO(rep.text());
  CHECK(rep.influences <= 4);
  CHECK(s.keys.size() == 60);
  CHECK(s.keys.front().time == Approx(1 / 24.0));
  check_against_blender(dae, dae_time);
}

TEST_CASE("BVH motion onto the imported glb's rig reproduces Blender's frame 30", "[assimp][bvh][data]") {
  DFM_DATA_OR_SKIP(glb, "rigged/elephant.glb");
  DFM_DATA_OR_SKIP(bvh, "rigged/elephant.bvh");
  DFM_DATA_OR_SKIP(ref30, "rigged/elephant_frame030.obj");
  SceneData s = import_gltf_scene(glb);
  BvhReport rep;
  apply_bvh_motion(s, bvh, &rep);
  INFO(rep.text());
  CHECK(rep.matched.size() == 24);
  CHECK(rep.scene_only.empty());
  CHECK(rep.bvh_only == std::vector<std::string>{"__0"});  // Blender's root above its three root bones
  CHECK(rep.residual < 1e-6);
  REQUIRE(s.keys.size() == 60);
  const std::filesystem::path dir = temp_dir("bvh");
  const std::string scene = (dir / "bvh.scene.json").string();
  write_scene(scene, s);
  Document doc;
  doc.load_scene(scene);
  doc.set_time(s.keys[29].time);  // BVH frame 29 (from 0) is Blender's frame 30
  const TriMesh ref = read_surface(ref30);
  const TriMesh rest = read_surface(test::data_file("elephant.obj"));
  const double diag = diagonal(rest.V);
  const Distance d = distance(ref.V, posed_surface(doc).V, nearest(rest.V, s.surface.V));
  WARN("BVH on the glb's rig, frame 30: largest distance from Blender's " << d.worst / diag << ", mean " << d.mean / diag
                                                                        << " of the diagonal");
  CHECK(d.worst <= 1e-4 * diag);

  // The CLI (deform import MOTION.bvh --onto SCENE -o OUT) and the script (load-motion) give the same keys.
  const std::string glb_scene = (dir / "glb.scene.json").string(), out = (dir / "out.scene.json").string();
  write_scene(glb_scene, import_gltf_scene(glb));
  const test::RunResult a = test::run_program(DFM_DEFORM_EXE, {"import", bvh, "--onto", glb_scene, "-o", out}, dir);
  INFO(a.out << a.err);
  REQUIRE(a.exit_code == 0);
  CHECK(a.out.find("BVH joints without a bone: __0") != std::string::npos);
  Document cli;
  cli.load_scene(out);
  cli.set_time(s.keys[29].time);
  CHECK((posed_surface(cli).V - posed_surface(doc).V).cwiseAbs().maxCoeff() < 1e-9 * diag);
  register_assimp_scene_importers();
  Document scripted;
  scripted.load_scene(glb_scene);
  run_script(scripted, parse_script("load-motion " + bvh + "\nset-time " + std::to_string(s.keys[29].time) + "\n", "m.txt"), "m.txt");
  REQUIRE(scripted.keys().size() == 60);
  CHECK((posed_surface(scripted).V - posed_surface(doc).V).cwiseAbs().maxCoeff() < 1e-6 * diag);
  scripted.undo();  // one undo step: the glb's own keys again
  CHECK(scripted.keys().size() == 60);
  CHECK(scripted.keys().front().time == Approx(1 / 24.0));
  std::filesystem::remove_all(dir);
}

TEST_CASE("A BVH opened alone: its skeleton and motion as bones and keys, posed as the glb's rig", "[assimp][bvh][data]") {
  DFM_DATA_OR_SKIP(glb, "rigged/elephant.glb");
  DFM_DATA_OR_SKIP(bvh, "rigged/elephant.bvh");
  register_assimp_scene_importers();
  Document d;
  const std::string report = d.import_scene(bvh);
  INFO(report);
  CHECK(report.find("no mesh") != std::string::npos);
  REQUIRE(d.rig().skeleton.num_bones() == 25);  // Blender's __0 above bone_00, bone_14 and bone_19
  CHECK(d.surface().num_vertices() == 0);
  CHECK_FALSE(d.has_weights());
  REQUIRE(d.keys().size() == 60);
  // Independent of the BVH: the glb's own rig at frame 30 (t = 30/24 there). The BVH is Blender's Z up:
  // obj (x, y, z) = Blender (x, z, -y).
  const SceneData g = import_gltf_scene(glb);
  const Skeleton& gs = g.rig.skeleton;
  REQUIRE(g.keys.size() == 60);
  CHECK(g.keys[29].time == Approx(30 / 24.0));
  const Eigen::MatrixXd gj = posed_joints(gs, evaluate_pose(g.rig, g.keys[29].params).transforms);
  const Skeleton& bs = d.rig().skeleton;
  const Eigen::MatrixXd bj = posed_joints(bs, evaluate_pose(d.rig(), d.keys()[29].params).transforms);
  const double diag = diagonal(gs.joints);
  double worst = 0;
  int compared = 0;
  for (int b = 0; b < bs.num_bones(); ++b)
    for (int k = 0; k < gs.num_bones(); ++k)
      if (gs.bones[k].name == bs.bones[b].name) {
        const Eigen::RowVector3d p = bj.row(bs.bones[b].a);
        worst = std::max(worst, (Eigen::RowVector3d(p.x(), p.z(), -p.y()) - gj.row(gs.bones[k].a)).norm());
        ++compared;
      }
  WARN("BVH alone at frame 30: bone heads " << worst / diag << " of the rig's diagonal from the glb rig's");
  CHECK(compared == 24);
  CHECK(worst <= 1e-4 * diag);
  // A scene file holds it.
  const std::filesystem::path dir = temp_dir("bvh_alone");
  const std::string scene = (dir / "skeleton.scene.json").string();
  d.save_scene(scene);
  Document back;
  back.load_scene(scene);
  CHECK(back.rig().skeleton.num_bones() == 25);
  CHECK(back.keys().size() == 60);
  std::filesystem::remove_all(dir);
}

TEST_CASE("FBX, Collada and BVH import refuse broken files, naming them", "[assimp][import]") {
  const std::filesystem::path dir = temp_dir("bad");
  register_assimp_scene_importers();
  const std::string junk = (dir / "junk.fbx").string();
  std::ofstream(junk) << "Kaydara FBX Binary but not really; just some words";
  CHECK_THROWS_WITH(import_assimp_scene(junk), Catch::Contains("junk.fbx"));
  const std::string missing = (dir / "missing.dae").string();
  CHECK_THROWS_WITH(import_assimp_scene(missing), Catch::Contains("missing.dae"));
  const std::string obj_as_dae = (dir / "mesh.dae").string();
  std::ofstream(obj_as_dae) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  CHECK_THROWS_WITH(import_assimp_scene(obj_as_dae), Catch::Contains("mesh.dae"));
  const std::string truncated = (dir / "truncated.dae").string();
  if (const std::string dae = test::data_file("rigged/elephant.dae"); !dae.empty()) {
    std::ifstream in(dae, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(truncated, std::ios::binary) << text.substr(0, text.size() / 2);
    CHECK_THROWS_WITH(import_assimp_scene(truncated), Catch::Contains("truncated.dae"));
  }
  const test::RunResult r = test::run_program(DFM_DEFORM_EXE, {"import", junk, "-o", (dir / "x.scene.json").string()}, dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("junk.fbx") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir / "x.scene.json"));
  // BVH: junk motion names the file, onto a rig, alone and through the CLI.
  const std::string bad_bvh = (dir / "bad.bvh").string();
  std::ofstream(bad_bvh) << "HIERARCHY\nROOT hips\n{\n OFFSET 0 0\n";
  Document d;
  d.add_bone_chain({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0)});
  CHECK_THROWS_WITH(d.load_motion(bad_bvh), Catch::Contains("bad.bvh"));
  CHECK_THROWS_WITH(d.import_scene(bad_bvh), Catch::Contains("bad.bvh"));
  const test::RunResult u = test::run_program(DFM_DEFORM_EXE, {"import", bad_bvh, "-o", (dir / "y.scene.json").string()}, dir);
  CHECK(u.exit_code == 1);
  CHECK(u.err.find("bad.bvh") != std::string::npos);
  const test::RunResult o = test::run_program(DFM_DEFORM_EXE, {"import", junk, "--onto", (dir / "y.scene.json").string(), "-o", (dir / "z.scene.json").string()}, dir);
  CHECK(o.exit_code == 2);  // --onto takes motion
  std::filesystem::remove_all(dir);
}

TEST_CASE("deform import FILE.fbx writes the scene and prints what it imported", "[assimp][import][data]") {
  DFM_DATA_OR_SKIP(fbx, "rigged/elephant.fbx");
  const std::filesystem::path dir = temp_dir("cli");
  const std::string scene = (dir / "fbx.scene.json").string(), out = (dir / "f30.obj").string();
  const test::RunResult a = test::run_program(DFM_DEFORM_EXE, {"import", fbx, "-o", scene}, dir);
  INFO(a.out << a.err);
  REQUIRE(a.exit_code == 0);
  CHECK(a.out.find("24 joints as bones") != std::string::npos);
  const test::RunResult b = test::run_program(DFM_DEFORM_EXE, {"pose", scene, "--at", std::to_string(29 / 24.0), "-o", out}, dir);
  INFO(b.out << b.err);
  REQUIRE(b.exit_code == 0);
  if (const std::string ref = frame_file(30); !ref.empty()) {
    const TriMesh r = read_surface(ref), posed = read_surface(out);
    const TriMesh rest = read_surface(test::data_file("elephant.obj"));
    Document doc;
    doc.load_scene(scene);
    CHECK(distance(r.V, posed.V, nearest(rest.V, doc.surface().V)).worst < 1e-3 * diagonal(rest.V));  // unkeyed bones (above)
    doc.set_time(29 / 24.0);
    CHECK((posed.V - posed_surface(doc).V).cwiseAbs().maxCoeff() < 1e-5 * diagonal(rest.V));  // the obj's digits
  }
  std::filesystem::remove_all(dir);
}
