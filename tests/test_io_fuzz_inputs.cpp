// Replays the fuzz seed corpus and every kept crash reproducer (tests/fuzz/corpus/<reader>/,
// tests/fuzz/crashes/<reader>/) through the normal readers: each must load or throw dfm::Error.
// Scene inputs are the JSON only, read beside the fuzzer's fixed sidecar (fuzz_scene_fixture.h).
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <unistd.h>

#include <catch2/catch.hpp>

#include "core/export/bvh_motion.h"
#include "core/export/gltf_scene_import.h"
#include "core/mesh/io.h"
#include "core/mesh/mesh_info.h"
#include "core/rig/rig_io.h"
#include "core/scene/scene_file.h"
#include "core/util/error.h"
#include "tests/fuzz/fuzz_scene_fixture.h"
#include "tests/file_bytes.h"

using namespace dfm;
namespace fs = std::filesystem;

namespace {

using dfm::test::slurp;
using dfm::test::spill;

// Feeds `bytes` to `reader` the way tests/fuzz/fuzz_reader.cpp does.
void read_as(const std::string& reader, const std::string& bytes, const fs::path& tmp) {
  if (reader == "scene") {  // and the save -> load -> save check the fuzzer does
    if (!fs::exists(tmp / "fixture.scene.bin")) write_scene((tmp / "fixture.scene.json").string(), fuzz::fixed_scene());
    spill(tmp / "in.scene.json", bytes);
    const SceneData s = read_scene((tmp / "in.scene.json").string());
    fs::create_directories(tmp / "out1");
    fs::create_directories(tmp / "out2");
    write_scene((tmp / "out1" / "x.scene.json").string(), s);
    write_scene((tmp / "out2" / "x.scene.json").string(), read_scene((tmp / "out1" / "x.scene.json").string()));
    REQUIRE(slurp(tmp / "out1" / "x.scene.json") == slurp(tmp / "out2" / "x.scene.json"));
    REQUIRE(slurp(tmp / "out1" / "x.scene.bin") == slurp(tmp / "out2" / "x.scene.bin"));
    return;
  }
  if (reader == "glb") {  // imported as a scene, which saves and loads back
    spill(tmp / "in.glb", bytes);
    const SceneData s = import_gltf_scene((tmp / "in.glb").string());
    write_scene((tmp / "g.scene.json").string(), s);
    REQUIRE(read_scene((tmp / "g.scene.json").string()).keys.size() == s.keys.size());
    return;
  }
  if (reader == "bvh") {  // opened alone, then its motion onto its own bones, saved and loaded back
    spill(tmp / "in.bvh", bytes);
    SceneData s = import_bvh_skeleton((tmp / "in.bvh").string());
    const size_t keys = s.keys.size();
    apply_bvh_motion(s, (tmp / "in.bvh").string());
    REQUIRE(s.keys.size() == keys);
    write_scene((tmp / "b.scene.json").string(), s);
    REQUIRE(read_scene((tmp / "b.scene.json").string()).rig.skeleton.num_bones() == s.rig.skeleton.num_bones());
    return;
  }
  if (reader == "tetgen") {
    size_t sep = bytes.find("@@\n");
    spill(tmp / "in.node", bytes.substr(0, sep));
    spill(tmp / "in.ele", sep == std::string::npos ? "1 4 0\n1 1 2 3 4\n" : bytes.substr(sep + 3));
    read_tet_mesh((tmp / "in.node").string());
    return;
  }
  const std::string ext = reader == "points" ? "xyz" : reader;
  const fs::path p = tmp / ("in." + ext);
  spill(p, bytes);
  if (reader == "mesh") read_tet_mesh(p.string());
  else if (reader == "dmat") {  // and the round trip the fuzzer does (an empty matrix once hit UB)
    Eigen::MatrixXd M = read_dmat(p.string());
    write_dmat((tmp / "out.dmat").string(), M, true);
    const Eigen::MatrixXd R = read_dmat((tmp / "out.dmat").string());
    REQUIRE(R.rows() == M.rows());
    REQUIRE(R.cols() == M.cols());
    REQUIRE((M.size() == 0 || R == M));  // entry-wise only when there are entries (0 x 10^8 is legal)
  }
  else if (reader == "points") read_points(p.string());
  else if (reader == "tgf") {
    Rig rig;
    add_tgf_to_rig(rig, read_tgf(p.string()), p.string());
  } else {  // and the mesh checks the fuzzer runs (huge coordinates once overflowed a cast)
    TriMesh m = read_surface(p.string());
    is_closed(m.F);
    degenerate_face_count(m.V, m.F);
    duplicate_vertex_count(m.V, 1e-3);
  }
}

}  // namespace

TEST_CASE("fuzz corpus and crash reproducers load or fail cleanly", "[io][fuzz]") {
  const fs::path root = DFM_FUZZ_DIR;
  const fs::path tmp = fs::temp_directory_path() / ("dfm_test_io_fuzz_" + std::to_string(::getpid()));
  fs::create_directories(tmp);
  int inputs = 0, seeds_ok = 0;
  std::map<std::string, int> seeds_per_reader;
  for (const char* kind : {"corpus", "crashes"}) {
    if (!fs::exists(root / kind)) continue;
    for (const auto& dir : fs::directory_iterator(root / kind)) {
      if (!dir.is_directory()) continue;
      const std::string reader = dir.path().filename().string();
      for (const auto& f : fs::directory_iterator(dir.path())) {
        INFO(f.path().string());
        ++inputs;
        try {
          read_as(reader, slurp(f.path()), tmp);
          if (std::string(kind) == "corpus") {
            ++seeds_ok;
            ++seeds_per_reader[reader];
          }
        } catch (const Error& e) {
          REQUIRE(std::string(e.what()).find(tmp.string()) == 0);  // the message names the file
        }
      }
    }
  }
  fs::remove_all(tmp);
  REQUIRE(inputs >= 10);
  REQUIRE(seeds_ok >= 10);  // the seeds are meant to be valid files: at least one per reader
  for (const char* r : {"obj", "off", "ply", "stl", "mesh", "tetgen", "dmat", "tgf", "points", "scene", "glb", "bvh"}) {
    INFO(r);
    CHECK(seeds_per_reader[r] >= 1);
  }
}
