// Scene files: save -> load gives equal data, save -> load -> save gives byte-identical files, and
// hostile files (bad JSON, wrong version, missing/short/corrupt sidecar, out-of-range indices, NaN)
// are refused with an error naming the file and the problem.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <functional>
#include <unistd.h>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/scene/document.h"
#include "core/scene/scene_file.h"
#include "core/util/error.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
void spit(const std::string& p, const std::string& s) {
  std::ofstream out(p, std::ios::binary);
  out << s;
}

// Independent FNV-1a (64-bit) for re-signing tampered sidecars.
std::string fnv_hex(const std::string& b) {
  unsigned long long h = 0xcbf29ce484222325ull;
  for (unsigned char c : b) h = (h ^ c) * 0x100000001b3ull;
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", h);
  return buf;
}

struct TempDir {
  fs::path dir;
  TempDir() {
    dir = fs::temp_directory_path() / ("dfm_scene_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
  }
  ~TempDir() { fs::remove_all(dir); }
  std::string operator/(const std::string& f) const { return (dir / f).string(); }
};

// A document using every feature of the format.
void fill(Document& d) {
  d.set_surface(test::octahedron(), "octa.obj");
  d.add_point({0.1, 0.2, 0.3}, "ear");
  d.add_point({-0.1, 0.0, 0.1}, "belly");
  d.add_pseudo_edge(0, 1);
  d.add_bone_chain({{0, -0.5, 0}, {0, 0, 0}, {0, 0.5, 0.1}});
  Cage c;
  c.mesh = test::octahedron();
  c.mesh.V *= 0.2;
  c.mesh.F.conservativeResize(4, 3);  // open: half the faces
  c.edges.resize(1, 2);
  c.edges << 0, 5;
  c.name = "cage";
  d.add_cage(c);
  const int r = d.add_region("cheek");
  d.paint_region(r, {1, 4}, false);
  d.paint_mask({0, 2, 5}, {0.25, 1.0, 0.1});
  d.translate_handle(0, {0.1, 1e-17, -3.5});
  d.rotate_handle(2, Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized())));
  d.rotate_handle(d.num_handles() - 1, Eigen::Quaterniond(Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitY())));
  d.set_key(0.0);
  d.translate_handle(4, {1.0 / 3.0, 0, 0});
  d.set_key(0.75);
  TriMesh key = test::octahedron();  // a mesh key (format version 2)
  key.V *= 0.5;
  d.key_mesh(key, "octa-key.obj", 1.5);
  d.set_method(SkinMethod::DQS);
  d.set_inbetweens(7);
  BindSettings bs;
  bs.volume.tetgen_switches = "pq1.2Y";
  bs.volume.robust = VolumeOptions::Robust::Always;
  bs.max_influences = 4;
  bs.monotone = true;
  d.set_bind_settings(bs);
  Eigen::MatrixXd W = Eigen::MatrixXd::Random(d.surface().num_vertices(), d.num_handles()).cwiseAbs();
  d.set_weights(W, BindStats{2.5, 100, 300, {"robust volume", "ok"}});
  Camera cam;
  cam.position = {1, 2, 3.25};
  cam.fov_deg = 33.3;
  cam.ortho = true;
  d.set_camera(cam);
  d.set_time(0.4);
  d.set_selection({{1, 3}, 2});
}

// Shape and contents (Eigen's == asserts on shape mismatches in debug builds).
template <class A, class B>
bool same(const A& a, const B& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && a == b;
}

void require_equal(const SceneData& a, const SceneData& b) {
  CHECK(same(a.surface.V, b.surface.V));
  CHECK(same(a.surface.F, b.surface.F));
  CHECK(a.surface.N.size() == b.surface.N.size());
  CHECK(a.surface_path == b.surface_path);
  CHECK(same(a.tets.V, b.tets.V));
  CHECK(same(a.tets.T, b.tets.T));
  CHECK(same(a.surface_to_tet, b.surface_to_tet));
  REQUIRE(a.rig.points.size() == b.rig.points.size());
  for (size_t i = 0; i < a.rig.points.size(); ++i) {
    CHECK(a.rig.points[i].position == b.rig.points[i].position);
    CHECK(a.rig.points[i].name == b.rig.points[i].name);
  }
  CHECK(same(a.rig.skeleton.joints, b.rig.skeleton.joints));
  REQUIRE(a.rig.skeleton.bones.size() == b.rig.skeleton.bones.size());
  for (size_t i = 0; i < a.rig.skeleton.bones.size(); ++i) {
    CHECK(a.rig.skeleton.bones[i].a == b.rig.skeleton.bones[i].a);
    CHECK(a.rig.skeleton.bones[i].b == b.rig.skeleton.bones[i].b);
    CHECK(a.rig.skeleton.bones[i].parent == b.rig.skeleton.bones[i].parent);
    CHECK(a.rig.skeleton.bones[i].name == b.rig.skeleton.bones[i].name);
  }
  REQUIRE(a.rig.cages.size() == b.rig.cages.size());
  for (size_t i = 0; i < a.rig.cages.size(); ++i) {
    CHECK(same(a.rig.cages[i].mesh.V, b.rig.cages[i].mesh.V));
    CHECK(same(a.rig.cages[i].mesh.F, b.rig.cages[i].mesh.F));
    CHECK(same(a.rig.cages[i].edges, b.rig.cages[i].edges));
    CHECK(a.rig.cages[i].name == b.rig.cages[i].name);
  }
  REQUIRE(a.rig.regions.size() == b.rig.regions.size());
  for (size_t i = 0; i < a.rig.regions.size(); ++i) CHECK(a.rig.regions[i].vertices == b.rig.regions[i].vertices);
  CHECK(a.rig.pseudo_edges == b.rig.pseudo_edges);
  auto same_params = [](const PoseParams& p, const PoseParams& q) {
    REQUIRE(p.bone_rotation.size() == q.bone_rotation.size());
    for (size_t i = 0; i < p.bone_rotation.size(); ++i) CHECK(p.bone_rotation[i].coeffs() == q.bone_rotation[i].coeffs());
    CHECK(p.bone_translation == q.bone_translation);
    CHECK(p.point_translation == q.point_translation);
    REQUIRE(p.point_rotation.size() == q.point_rotation.size());
    for (size_t i = 0; i < p.point_rotation.size(); ++i) CHECK(p.point_rotation[i].coeffs() == q.point_rotation[i].coeffs());
    CHECK(p.cage_translation == q.cage_translation);
    REQUIRE(p.region_transform.size() == q.region_transform.size());
    for (size_t i = 0; i < p.region_transform.size(); ++i)
      CHECK(p.region_transform[i].matrix() == q.region_transform[i].matrix());
    REQUIRE(p.bone_twist_stretch.size() == q.bone_twist_stretch.size());
  };
  same_params(a.pose, b.pose);
  REQUIRE(a.keys.size() == b.keys.size());
  for (size_t i = 0; i < a.keys.size(); ++i) {
    CHECK(a.keys[i].time == b.keys[i].time);
    same_params(a.keys[i].params, b.keys[i].params);
    CHECK(a.keys[i].is_mesh() == b.keys[i].is_mesh());
    CHECK(same(a.keys[i].mesh.V, b.keys[i].mesh.V));
    CHECK(same(a.keys[i].mesh.F, b.keys[i].mesh.F));
    CHECK(a.keys[i].mesh_path == b.keys[i].mesh_path);
  }
  CHECK(a.method == b.method);
  CHECK(a.inbetweens == b.inbetweens);
  CHECK(a.bind_settings == b.bind_settings);
  CHECK(same(a.weights, b.weights));
  CHECK(a.bind_stats == b.bind_stats);
  CHECK(same(a.mask, b.mask));
  CHECK(a.camera == b.camera);
  CHECK(a.time == b.time);
  CHECK(a.selection == b.selection);
}

}  // namespace

TEST_CASE("scene files round-trip exactly and re-save byte-identically") {
  TempDir tmp;
  Document d;
  fill(d);
  const std::string a = tmp / "a.scene.json", b = tmp / "b.scene.json";
  d.save_scene(a);
  CHECK(fs::exists(tmp / "a.scene.bin"));
  Document e;
  e.load_scene(a);
  require_equal(d.data(), e.data());
  CHECK_FALSE(e.dirty());
  CHECK(e.has_weights());
  e.save_scene(b);
  // Same bytes apart from the sidecar's name inside the JSON.
  std::string ja = slurp(a), jb = slurp(b);
  const auto pos = jb.find("b.scene.bin");
  REQUIRE(pos != std::string::npos);
  jb.replace(pos, 11, "a.scene.bin");
  CHECK(ja == jb);
  CHECK(slurp(tmp / "a.scene.bin") == slurp(tmp / "b.scene.bin"));
  // Re-saving under the same name is byte-identical outright.
  const std::string before_json = slurp(a), before_bin = slurp(tmp / "a.scene.bin");
  e.save_scene(a);
  CHECK(slurp(a) == before_json);
  CHECK(slurp(tmp / "a.scene.bin") == before_bin);
  // The JSON is versioned and readable.
  const json j = json::parse(before_json);
  CHECK(j["format"] == "deform-scene");
  CHECK(j["version"] == kSceneFormatVersion);
  CHECK(j["method"] == "dqs");
}

TEST_CASE("an empty document round-trips") {
  TempDir tmp;
  Document d;
  d.save_scene(tmp / "empty.scene.json");
  Document e;
  e.load_scene(tmp / "empty.scene.json");
  require_equal(d.data(), e.data());
}

TEST_CASE("autosave writes beside the scene and leaves the document's path and dirty flag alone") {
  TempDir tmp;
  CHECK(autosave_path("x/y.scene.json") == "x/y.autosave.scene.json");
  CHECK(autosave_path("x/y.json") == "x/y.json.autosave.json");
  CHECK(scene_sidecar_path("x/y.scene.json") == "x/y.scene.bin");
  Document d;
  fill(d);
  const std::string p = tmp / "s.scene.json";
  d.save_scene(p);
  d.add_point({0, 0, 0});
  REQUIRE(d.dirty());
  const std::string written = d.autosave();
  CHECK(written == tmp / "s.autosave.scene.json");
  CHECK(d.dirty());
  CHECK(d.path() == p);
  Document e;
  e.load_scene(written);
  CHECK(e.rig().points.size() == d.rig().points.size());
}

TEST_CASE("hostile scene files give errors naming the file and the problem") {
  TempDir tmp;
  Document d;
  fill(d);
  const std::string good = tmp / "good.scene.json";
  d.save_scene(good);
  const std::string good_json = slurp(good), good_bin = slurp(tmp / "good.scene.bin");

  // Writes a variant (JSON text, sidecar bytes, re-signed or not) and expects an error mentioning `what`.
  int n = 0;
  auto expect_error = [&](const std::string& text, const std::string& bin, const std::string& what,
                          bool resign = false) {
    const std::string name = "bad" + std::to_string(n++);
    const std::string jp = tmp / (name + ".scene.json"), bp = tmp / (name + ".scene.bin");
    std::string t = text;
    if (!t.empty() && t[0] == '{') {
      json j = json::parse(t, nullptr, false);
      if (!j.is_discarded() && j.contains("sidecar") && j["sidecar"].is_object()) {
        if (j["sidecar"]["file"] == "good.scene.bin") j["sidecar"]["file"] = name + ".scene.bin";
        if (resign) {
          j["sidecar"]["bytes"] = bin.size();
          j["sidecar"]["fnv1a64"] = fnv_hex(bin);
        }
        t = j.dump(1);
      }
    }
    spit(jp, t);
    spit(bp, bin);
    Document e;
    e.set_surface(test::octahedron(), "keep");
    try {
      e.load_scene(jp);
      FAIL("no error for: " << what);
    } catch (const Error& err) {
      const std::string msg = err.what();
      INFO(msg);
      CHECK((msg.find(jp) != std::string::npos || msg.find(bp) != std::string::npos));
      CHECK(msg.find(what) != std::string::npos);
    }
    CHECK(e.surface_path() == "keep");  // a failed load changes nothing
  };
  auto edit = [&](const std::function<void(json&)>& f) {
    json j = json::parse(good_json);
    f(j);
    return j.dump(1);
  };

  expect_error("", good_bin, "not valid JSON");
  expect_error("{\"format\": \"deform-scene\", ", good_bin, "not valid JSON");
  expect_error("[1, 2, 3]", good_bin, "not a scene file");
  expect_error(edit([](json& j) { j["format"] = "something-else"; }), good_bin, "not a scene file");
  expect_error(edit([](json& j) { j["version"] = 99; }), good_bin, "newer than this program");
  expect_error(edit([](json& j) { j["version"] = "one"; }), good_bin, "'version' is not an integer");
  expect_error(edit([](json& j) { j.erase("rig"); }), good_bin, "missing field 'scene.rig'");
  expect_error(good_json, good_bin.substr(0, good_bin.size() / 2), "truncated");
  std::string flipped = good_bin;
  flipped[flipped.size() / 3] ^= 0x5a;
  expect_error(good_json, flipped, "checksum mismatch");
  expect_error(edit([](json& j) { j["sidecar"]["file"] = "../good.scene.bin"; }), good_bin, "plain file name");
  expect_error(edit([](json& j) { j["sidecar"]["file"] = "missing.bin"; }), good_bin, "cannot open its sidecar");
  expect_error(edit([](json& j) { j["surface"]["V"]["rows"] = 1000000; }), good_bin, "runs past the end");
  expect_error(edit([](json& j) { j["surface"]["V"]["offset"] = 3; }), good_bin, "misaligned");
  expect_error(edit([](json& j) { j["surface"]["F"]["type"] = "f64"; }), good_bin, "expected i32");
  expect_error(edit([](json& j) { j["rig"]["skeleton"]["bones"][0]["b"] = 99; }), good_bin, "out of range");
  expect_error(edit([](json& j) { j["rig"]["skeleton"]["bones"][0]["b"] = j["rig"]["skeleton"]["bones"][0]["a"]; }),
               good_bin, "joins a joint to itself");
  expect_error(edit([](json& j) { j["rig"]["pseudo_edges"][0][1] = 7; }), good_bin, "out of range");
  expect_error(edit([](json& j) { j["rig"]["points"][0]["position"] = {1, 2}; }), good_bin, "expected 3");
  expect_error(edit([](json& j) { j["pose"]["bone_rotation"][0] = {0, 0, 0, 0}; }), good_bin, "zero quaternion");
  expect_error(edit([](json& j) { j["pose"]["point_translation"].erase(0); }), good_bin, "pose.point_translation");
  expect_error(edit([](json& j) { std::swap(j["keys"][0]["time"], j["keys"][1]["time"]); }), good_bin,
               "not after the previous key");
  expect_error(edit([](json& j) { j["method"] = "xyz"; }), good_bin, "unknown skinning method");
  expect_error(edit([](json& j) { j["selection"]["handles"] = {500}; }), good_bin, "selection.handles");
  expect_error(edit([](json& j) { j["weights"]["cols"] = 2; j["weights"]["rows"] = 3; }), good_bin, "'weights' is 3 x 2");
  expect_error(edit([](json& j) { j["camera"]["fov_deg"] = "wide"; }), good_bin, "camera.fov_deg");

  // Tampered sidecar contents, re-signed so only the semantic checks can catch them.
  const json gj = json::parse(good_json);
  {
    std::string b = good_bin;
    const long long off = gj["surface"]["F"]["offset"];
    const int bad = 1000;
    std::memcpy(&b[off], &bad, 4);
    expect_error(good_json, b, "'surface.F' has an index out of range", true);
  }
  {
    std::string b = good_bin;
    const long long off = gj["surface"]["V"]["offset"];
    const double nan = std::nan("");
    std::memcpy(&b[off + 8], &nan, 8);
    expect_error(good_json, b, "NaN", true);
  }
  {
    std::string b = good_bin;
    const long long off = gj["mask"]["offset"];
    const double big = 7;
    std::memcpy(&b[off], &big, 8);
    expect_error(good_json, b, "'mask' values must lie in [0, 1]", true);
  }
  {
    std::string b = good_bin;
    const long long off = gj["rig"]["regions"][0]["vertices"]["offset"];
    const int neg = -1;
    std::memcpy(&b[off], &neg, 4);
    expect_error(good_json, b, "rig.regions[0].vertices", true);
  }
  // Mesh keys (version 2).
  expect_error(edit([](json& j) { j["version"] = 1; }), good_bin, "'keys[2].mesh' needs scene format version 2");
  expect_error(edit([](json& j) { j["keys"][2]["mesh"].erase("source"); }), good_bin, "keys[2].mesh.source");
  expect_error(edit([](json& j) { j["keys"][2]["mesh"]["F"]["cols"] = 2; }), good_bin, "keys[2].mesh.F");
  {
    std::string b = good_bin;
    const long long off = gj["keys"][2]["mesh"]["F"]["offset"];
    const int bad = 6;  // the octahedron has 6 vertices
    std::memcpy(&b[off], &bad, 4);
    expect_error(good_json, b, "'keys[2].mesh.F' has an index out of range", true);
  }
  CHECK(n >= 29);
}

TEST_CASE("a mesh key round-trips; version 1 files (pose keys only) still load") {
  TempDir tmp;
  Document d;
  fill(d);
  REQUIRE(d.keys().size() == 3);
  REQUIRE(d.keys()[2].is_mesh());
  const std::string a = tmp / "m.scene.json";
  d.save_scene(a);
  const json j = json::parse(slurp(a));
  CHECK(j["version"] == 2);
  CHECK(j["keys"][2]["mesh"]["source"] == "octa-key.obj");
  CHECK_FALSE(j["keys"][0].contains("mesh"));
  Document e;
  e.load_scene(a);
  require_equal(d.data(), e.data());
  CHECK(e.keys()[2].mesh.V == d.keys()[2].mesh.V);

  // A version 1 file: the same scene without the mesh key, as the previous program wrote it.
  d.delete_key(2);
  const std::string old_path = tmp / "old.scene.json";
  d.save_scene(old_path);
  json o = json::parse(slurp(old_path));
  o["version"] = 1;
  spit(old_path, o.dump(1));
  Document f;
  f.load_scene(old_path);
  require_equal(d.data(), f.data());
  CHECK_FALSE(f.has_mesh_keys());

  // Scenes from before monotone weights (no bind_settings.monotone) bind without them.
  REQUIRE(d.bind_settings().monotone);
  o["bind_settings"].erase("monotone");
  spit(old_path, o.dump(1));
  Document g;
  g.load_scene(old_path);
  CHECK_FALSE(g.bind_settings().monotone);
  o["bind_settings"]["monotone"] = "yes";
  spit(old_path, o.dump(1));
  Document h;
  CHECK_THROWS_WITH(h.load_scene(old_path), Catch::Contains("bind_settings.monotone"));
}

TEST_CASE("bind settings compare and save the robust volume's segmentation and cut") {
  // Every field takes part in ==: change one at a time from the defaults.
  const BindSettings base;
  const std::vector<std::function<void(BindSettings&)>> changes = {
      [](BindSettings& b) { b.volume.tetgen_switches = "pq1.2Y"; },
      [](BindSettings& b) { b.volume.robust = VolumeOptions::Robust::Never; },
      [](BindSettings& b) { b.volume.segmentation = VolumeOptions::Segmentation::Threshold; },
      [](BindSettings& b) { b.volume.cut.gamma = 3.0; },
      [](BindSettings& b) { b.volume.cut.sigma = 0.25; },
      [](BindSettings& b) { b.volume.cut.surface_factor = 0.5; },
      [](BindSettings& b) { b.max_influences = 4; },
      [](BindSettings& b) { b.monotone = true; }};
  for (size_t i = 0; i < changes.size(); ++i) {
    BindSettings b;
    changes[i](b);
    CAPTURE(i);
    CHECK_FALSE(b == base);
    CHECK(b == b);
  }

  TempDir tmp;
  const std::string path = tmp / "seg.scene.json";
  Document d;
  d.set_surface(test::octahedron(), "octa.obj");
  d.add_point({0.1, 0.2, 0.3}, "ear");
  BindSettings bs;
  bs.volume.segmentation = VolumeOptions::Segmentation::Threshold;
  bs.volume.cut.gamma = 3.5;
  bs.volume.cut.sigma = 0.125;
  bs.volume.cut.surface_factor = 0.75;
  d.set_bind_settings(bs);
  d.save_scene(path);
  const auto loaded_volume = [&] {
    Document e;
    e.load_scene(path);
    return e.bind_settings().volume;
  };
  const auto check_volume = [](const VolumeOptions& v, VolumeOptions::Segmentation seg, double gamma, double sigma,
                               double factor) {
    CHECK(v.segmentation == seg);
    CHECK(v.cut.gamma == gamma);
    CHECK(v.cut.sigma == sigma);
    CHECK(v.cut.surface_factor == factor);
  };
  check_volume(loaded_volume(), VolumeOptions::Segmentation::Threshold, 3.5, 0.125, 0.75);

  // Scenes from before these were saved load with the defaults (Cut; gamma 2, sigma 0.4, factor 0).
  json o = json::parse(slurp(path));
  o["bind_settings"].erase("segmentation");
  o["bind_settings"].erase("cut");
  spit(path, o.dump(1));
  check_volume(loaded_volume(), VolumeOptions::Segmentation::Cut, 2.0, 0.4, 0.0);

  // Bad values are refused, naming the field.
  const auto load_error = [&](const json& bad) {
    spit(path, bad.dump(1));
    try {
      Document g;
      g.load_scene(path);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("loaded");
  };
  json bad = o;
  bad["bind_settings"]["segmentation"] = "otsu";
  CHECK_THAT(load_error(bad), Catch::Contains("bind_settings.segmentation"));
  bad = o;
  bad["bind_settings"]["cut"] = {{"gamma", 1.0}, {"sigma", 0.0}, {"surface_factor", 0.0}};
  CHECK_THAT(load_error(bad), Catch::Contains("bind_settings.cut"));
  bad["bind_settings"]["cut"].erase("surface_factor");
  CHECK_THAT(load_error(bad), Catch::Contains("surface_factor"));
}

TEST_CASE("a missing scene file is an error naming it") {
  Document d;
  CHECK_THROWS_WITH(d.load_scene("/nonexistent/dir/x.scene.json"), Catch::Contains("/nonexistent/dir/x.scene.json"));
}
