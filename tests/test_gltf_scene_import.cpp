// A rigged, animated glTF file as a scene (core/export/gltf_scene_import.h, issue 32), checked against
// what Blender 3.4 itself evaluated: ../shared/data/rigged/elephant.glb (24 bones, Blender's automatic
// weights, an action sampled at every frame) and elephant_frameNNN.obj, Blender's posed meshes in
// elephant.obj's coordinates and vertex order. Vertices are matched by their rest positions. In this
// file frame f is the glTF time f / 24 s (its samples run from 1/24 to 60/24 s).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "core/export/export_document.h"
#include "core/export/gltf_import.h"
#include "core/export/gltf_scene_import.h"
#include "core/mesh/io.h"
#include "core/scene/scene_file.h"
#include "core/scene/script.h"
#include "core/util/error.h"
#include "tests/cli_test_util.h"
#include "tests/rigged_test_util.h"
#include "tests/test_support.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;
using dfm::test::diagonal;
using dfm::test::nearest;

namespace {

}  // namespace

TEST_CASE("glTF import: Blender's elephant posed at frames 1, 15, 30 and 60 as Blender evaluated it", "[gltf][import][data]") {
  DFM_DATA_OR_SKIP(glb, "rigged/elephant.glb");
  DFM_DATA_OR_SKIP(rest_obj, "elephant.obj");
  GltfImportReport rep;
  const SceneData s = import_gltf_scene(glb, &rep);
  INFO(rep.text());
  const TriMesh rest = read_surface(rest_obj);
  const double diag = diagonal(rest.V);
  REQUIRE(s.rig.skeleton.num_bones() == 24);
  for (int b = 0; b < 24; ++b) {
    char name[16];
    std::snprintf(name, sizeof name, "bone_%02d", b);
    CHECK(s.rig.skeleton.bones[b].name == name);
  }
  CHECK(s.rig.points.empty());
  // The rest pose is elephant.obj (to the file's float precision).
  const std::vector<int> m = nearest(rest.V, s.surface.V);
  double rest_err = 0;
  for (Eigen::Index i = 0; i < rest.V.rows(); ++i) rest_err = std::max(rest_err, (rest.V.row(i) - s.surface.V.row(m[i])).norm());
  CHECK(rest_err <= 1e-6 * diag);
  CHECK(s.surface.V.rows() == rest.V.rows());
  // The file's weights: rows a partition of unity, at most the 4 Blender kept.
  CHECK(s.weights.minCoeff() >= 0);
  CHECK((s.weights.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-12);
  CHECK(rep.influences <= 4);
  REQUIRE(s.keys.size() == 60);

  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("dfm_gltf_import_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string scene = (dir / "elephant.scene.json").string();
  write_scene(scene, s);
  Document doc;
  doc.load_scene(scene);
  const GltfDocument g = read_gltf(glb);
  const std::vector<int> fm = nearest(rest.V, g.skinned.V);
  for (int f : {1, 15, 30, 60}) {
    char ref_name[40];
    std::snprintf(ref_name, sizeof ref_name, "rigged/elephant_frame%03d.obj", f);
    DFM_DATA_OR_SKIP(ref_path, ref_name);
    const TriMesh ref = read_surface(ref_path);
    doc.set_time(f / 24.0);
    const TriMesh posed = posed_surface(doc);
    REQUIRE(posed.V.rows() == s.surface.V.rows());
    double worst = 0, mean = 0;
    for (Eigen::Index i = 0; i < ref.V.rows(); ++i) {
      const double e = (ref.V.row(i) - posed.V.row(m[i])).norm();
      worst = std::max(worst, e);
      mean += e / ref.V.rows();
    }
    // The file's own skinning by the specification's formula (gltf_import.h, written from the spec).
    const Eigen::MatrixXd spec = gltf_skinned_positions(g, f / 24.0);
    double spec_worst = 0, blender_spec = 0;
    for (Eigen::Index i = 0; i < ref.V.rows(); ++i) {
      spec_worst = std::max(spec_worst, (spec.row(fm[i]) - posed.V.row(m[i])).norm());
      blender_spec = std::max(blender_spec, (spec.row(fm[i]) - ref.V.row(i)).norm());
    }
    WARN("frame " << f << ": largest distance from Blender's " << worst / diag << ", mean " << mean / diag
                  << " of the diagonal; from the file's own skinning " << spec_worst / diag << " (the file's from Blender's "
                  << blender_spec / diag << ")");
    // Ours is the file's skinning; where the file itself is farther than 1e-5 of the diagonal from
    // Blender's mesh (3 vertices at frame 30 reach 1.4e-5: the file's weights there are not quite what
    // Blender evaluates), no importer of this file can be nearer.
    CHECK(spec_worst <= 1e-6 * diag);
    CHECK(worst <= std::max(1e-5 * diag, blender_spec + 1e-6 * diag));
    CHECK(mean <= 1e-7 * diag);
  }

  // The same through the CLI: deform import, then deform pose SCENE --at T.
  const std::string cli_scene = (dir / "cli.scene.json").string(), out = (dir / "f30.obj").string();
  const test::RunResult a = test::run_program(DFM_DEFORM_EXE, {"import", glb, "-o", cli_scene}, dir);
  INFO(a.out << a.err);
  REQUIRE(a.exit_code == 0);
  CHECK(a.out.find("24 joints as bones") != std::string::npos);
  const test::RunResult b = test::run_program(DFM_DEFORM_EXE, {"pose", cli_scene, "--at", "1.25", "-o", out}, dir);
  INFO(b.out << b.err);
  REQUIRE(b.exit_code == 0);
  doc.set_time(1.25);
  CHECK((read_surface(out).V - posed_surface(doc).V).cwiseAbs().maxCoeff() < 1e-5 * diag);  // the obj's digits
  std::filesystem::remove_all(dir);
}

TEST_CASE("glTF import refuses what is not a rigged glTF, naming the file", "[gltf][import]") {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("dfm_gltf_bad_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string junk = (dir / "junk.glb").string();
  std::ofstream(junk) << "glTF but not really";
  CHECK_THROWS_WITH(import_gltf_scene(junk), Catch::Contains("junk.glb"));
  const std::string missing = (dir / "missing.glb").string();
  CHECK_THROWS_WITH(import_gltf_scene(missing), Catch::Contains("missing.glb"));
  const test::RunResult r = test::run_program(DFM_DEFORM_EXE, {"import", junk, "-o", (dir / "x.scene.json").string()}, dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("junk.glb") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir / "x.scene.json"));
  const test::RunResult u = test::run_program(DFM_DEFORM_EXE, {"pose", (dir / "x.scene.json").string(), "-o", "o.obj"}, dir);
  CHECK(u.exit_code == 2);  // a scene needs --at
  std::filesystem::remove_all(dir);
}

TEST_CASE("open FILE.glb: the script's open imports a rigged glTF as a new, unsaved, bound document", "[gltf][import][data]") {
  DFM_DATA_OR_SKIP(glb, "rigged/elephant.glb");
  register_gltf_scene_importer();
  Document d;
  d.set_surface(test::icosphere(Eigen::Vector3d::Zero(), 1, 1), "before");
  run_script(d, parse_script("open " + glb + "\n", "o.txt"), "o.txt");
  CHECK(d.rig().skeleton.num_bones() == 24);
  CHECK(d.keys().size() == 60);
  CHECK(d.has_weights());
  CHECK(d.path().empty());  // saving asks for a scene name: the .glb is never overwritten
  CHECK_FALSE(d.can_undo());
  CHECK(d.bind_stats().notes.front().find("24 joints as bones") != std::string::npos);
  // A broken file leaves the document as it was.
  const std::filesystem::path bad = std::filesystem::temp_directory_path() / ("dfm_bad_" + std::to_string(::getpid()) + ".glb");
  std::ofstream(bad) << "not a glb";
  CHECK_THROWS_WITH(run_script(d, parse_script("open " + bad.string() + "\n", "o.txt"), "o.txt"), Catch::Contains(bad.filename().string()));
  CHECK(d.rig().skeleton.num_bones() == 24);
  std::filesystem::remove(bad);
}

TEST_CASE("glTF round trip: a bones-only scene exported and imported again plays the same mesh at its keys", "[gltf][import]") {
  // A capsule along x with a chain of three bones, weights that blend along it, and two keys.
  Document d;
  const TriMesh m = test::keyed_capsule(d, "select 1\nrotate 40 0 0 1\nselect 2\nrotate -30 0 1 0\n");
  const Eigen::MatrixXd W = d.weights();
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("dfm_gltf_rt_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string glb = (dir / "capsule.glb").string();
  export_document_gltf(d, glb);
  const SceneData s = import_gltf_scene(glb);
  const double diag = (m.V.colwise().maxCoeff() - m.V.colwise().minCoeff()).norm();
  REQUIRE(s.rig.skeleton.num_bones() == 3);
  for (int b = 0; b < 3; ++b) {
    CHECK(handle_name(s.rig, num_point_handles(s.rig) + b) == handle_name(d.rig(), b));
    CHECK(s.rig.skeleton.bones[b].parent == d.rig().skeleton.bones[b].parent);
    const Eigen::RowVector3d head = s.rig.skeleton.joints.row(s.rig.skeleton.bones[b].a);
    CHECK((head - d.rig().skeleton.joints.row(d.rig().skeleton.bones[b].a)).norm() < 1e-6 * diag);
  }
  REQUIRE(s.surface.V.rows() == m.V.rows());
  const std::vector<int> at = nearest(m.V, s.surface.V);
  double moved = 0, weight = 0;
  for (int i = 0; i < m.V.rows(); ++i) {
    moved = std::max(moved, (m.V.row(i) - s.surface.V.row(at[i])).norm());
    weight = std::max(weight, (W.row(i) - s.weights.row(at[i])).cwiseAbs().maxCoeff());
  }
  CHECK(moved < 1e-6 * diag);  // float positions
  CHECK(weight < 1e-6);        // float weights, every one kept (3 < 4)
  REQUIRE(s.keys.size() == 2);
  const std::string scene = (dir / "back.scene.json").string();
  write_scene(scene, s);
  Document back;
  back.load_scene(scene);
  for (double t : {0.0, 1.0}) {
    d.set_time(t);
    back.set_time(t);
    const TriMesh a = posed_surface(d), b = posed_surface(back);
    double worst = 0;
    for (int i = 0; i < m.V.rows(); ++i) worst = std::max(worst, (a.V.row(i) - b.V.row(at[i])).norm());
    INFO("t = " << t);
    CHECK(worst < 1e-5 * diag);
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("Rebind on the imported elephant: bounded biharmonic weights on its bones, posed at frame 30 beside Blender's",
          "[gltf][import][data]") {
  DFM_DATA_OR_SKIP(glb, "rigged/elephant.glb");
  DFM_DATA_OR_SKIP(ref30, "rigged/elephant_frame030.obj");
  register_gltf_scene_importer();
  Document d;
  run_script(d, parse_script("open " + glb + "\nbind\nset-time 1.25\n", "r.txt"), "r.txt");
  REQUIRE(d.has_weights());
  const Eigen::MatrixXd& W = d.weights();
  CHECK(W.minCoeff() >= 0);
  CHECK(W.maxCoeff() <= 1);
  CHECK((W.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-9);
  const TriMesh ref = read_surface(ref30), posed = posed_surface(d);
  const std::vector<int> m = nearest(read_surface(test::data_file("elephant.obj")).V, d.surface().V);
  const double diag = diagonal(ref.V);
  double worst = 0, mean = 0;
  for (Eigen::Index i = 0; i < ref.V.rows(); ++i) {
    const double e = (ref.V.row(i) - posed.V.row(m[i])).norm();
    worst = std::max(worst, e);
    mean += e / ref.V.rows();
  }
  // Blender weighted by bone heat, the bind by bounded biharmonic weights: near, not equal.
  WARN("rebound elephant at frame 30: largest distance from Blender's " << worst / diag << ", mean " << mean / diag
                                                                        << " of the diagonal");
  CHECK(mean < 0.01 * diag);
  CHECK(worst < 0.05 * diag);
}

namespace {

// Weights for a round trip: per vertex the 4 nearest handles (points and cage vertices by position,
// bones by their segment) by inverse fourth power of the distance, rows summing to 1. Four, so the
// export keeps every one and the posed meshes can be compared exactly.
Eigen::MatrixXd nearest_four_weights(const Eigen::MatrixXd& V, const Rig& rig) {
  const int n = num_handles(rig);
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(V.rows(), n);
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Eigen::Vector3d x = V.row(i).transpose();
    std::vector<std::pair<double, int>> d;
    int cage_vertex = 0;
    for (int h = 0; h < n; ++h) {
      const HandleRef r = handle_ref(rig, h);
      double dist = 0;
      if (r.kind == HandleKind::Point) {
        dist = (x - rig.points[r.index].position).norm();
      } else if (r.kind == HandleKind::Bone) {
        const Eigen::Vector3d a = rig.skeleton.joints.row(rig.skeleton.bones[r.index].a).transpose();
        const Eigen::Vector3d b = rig.skeleton.joints.row(rig.skeleton.bones[r.index].b).transpose();
        const double u = std::clamp((x - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
        dist = (x - (a + u * (b - a))).norm();
      } else {
        dist = (x - rig.cages[r.cage].mesh.V.row(r.index).transpose()).norm();
        ++cage_vertex;
      }
      d.emplace_back(dist, h);
    }
    std::partial_sort(d.begin(), d.begin() + std::min(4, n), d.end());
    for (int k = 0; k < std::min(4, n); ++k) W(i, d[k].second) = 1.0 / (1e-4 + std::pow(d[k].first, 4));
    W.row(i) /= W.row(i).sum();
  }
  return W;
}

// Export -> import: the same handles (kinds, names, positions, bones' joints, cages), the weights to
// float precision and the mesh at every key within 1e-5 of the diagonal.
void check_round_trip(Document& d, const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("dfm_gltf_rt_" + name + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string glb = (dir / (name + ".glb")).string();
  export_document_gltf(d, glb);
  GltfImportReport report;
  const SceneData s = import_gltf_scene(glb, &report);
  INFO(name << ": " << report.text());
  CHECK(report.rig_from_extras);
  const Rig& a = d.rig();
  const Rig& b = s.rig;
  REQUIRE(num_handles(b) == num_handles(a));
  REQUIRE(b.points.size() == a.points.size());
  REQUIRE(b.skeleton.num_bones() == a.skeleton.num_bones());
  REQUIRE(b.cages.size() == a.cages.size());
  for (int h = 0; h < num_handles(a); ++h) CHECK(handle_name(b, h) == handle_name(a, h));
  for (size_t p = 0; p < a.points.size(); ++p) CHECK(b.points[p].position == a.points[p].position);
  CHECK(b.skeleton.joints == a.skeleton.joints);
  for (int k = 0; k < a.skeleton.num_bones(); ++k) {
    CHECK(b.skeleton.bones[k].a == a.skeleton.bones[k].a);
    CHECK(b.skeleton.bones[k].b == a.skeleton.bones[k].b);
    CHECK(b.skeleton.bones[k].parent == a.skeleton.bones[k].parent);
  }
  for (size_t c = 0; c < a.cages.size(); ++c) {
    CHECK(b.cages[c].mesh.V == a.cages[c].mesh.V);
    CHECK(b.cages[c].mesh.F == a.cages[c].mesh.F);
  }
  const Eigen::MatrixXd& V = d.surface().V;
  const double diag = diagonal(V);
  REQUIRE(s.surface.V.rows() == V.rows());
  const std::vector<int> at = nearest(V, s.surface.V);
  double moved = 0, weight = 0;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    moved = std::max(moved, (V.row(i) - s.surface.V.row(at[i])).norm());
    weight = std::max(weight, (d.weights().row(i) - s.weights.row(at[i])).cwiseAbs().maxCoeff());
  }
  CHECK(moved < 1e-6 * diag);
  CHECK(weight < 1e-6);
  REQUIRE(s.keys.size() == d.keys().size());
  register_gltf_scene_importer();
  Document back;
  back.import_scene(glb);
  for (const SceneKey& k : d.keys()) {
    d.set_time(k.time);
    back.set_time(k.time);
    const TriMesh p = posed_surface(d), q = posed_surface(back);
    double worst = 0;
    for (Eigen::Index i = 0; i < V.rows(); ++i) worst = std::max(worst, (p.V.row(i) - q.V.row(at[i])).norm());
    INFO("key at " << k.time);
    CHECK(worst < 1e-5 * diag);
  }
  std::filesystem::remove_all(dir);
}

}  // namespace

TEST_CASE("glTF round trip: the default scene (points, bones, a cage) and the hand come back as they were", "[gltf][import][data]") {
  // The default scene: three points, ten bones and a cage; keyed with a turned bone, a moved point and a
  // moved cage vertex.
  Document teddy;
  teddy.load_scene(std::string(DFM_SOURCE_DIR) + "/assets/default.scene.json");
  REQUIRE(!teddy.rig().points.empty());
  REQUIRE(!teddy.rig().cages.empty());
  teddy.set_weights(nearest_four_weights(teddy.surface().V, teddy.rig()), {});
  const int cage0 = num_point_handles(teddy.rig()) + teddy.rig().skeleton.num_bones();
  run_script(teddy, parse_script("set-key 0\nselect l_ear\ntranslate 0 0.04 0.01\nselect 3\nrotate 35 0 0 1\nselect " +
                                     std::to_string(cage0) + "\ntranslate 0.02 0 0\nset-key 1\n", "k.txt"), "k.txt");
  check_round_trip(teddy, "teddy");

  // The hand (a tet mesh's boundary and hand.tgf's bones), two keys.
  DFM_DATA_OR_SKIP(mesh, "hand.mesh");
  DFM_DATA_OR_SKIP(tgf, "hand.tgf");
  Document hand;
  hand.replace_surface(mesh);
  hand.load_skeleton(tgf);
  hand.set_weights(nearest_four_weights(hand.surface().V, hand.rig()), {});
  run_script(hand, parse_script("set-key 0\nselect 5\nrotate 30 1 0 0\nselect 12\nrotate -25 0 0 1\nset-key 1\n", "k.txt"), "k.txt");
  check_round_trip(hand, "hand");
}
