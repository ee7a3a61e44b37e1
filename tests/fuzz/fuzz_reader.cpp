// libFuzzer target for one reader, chosen by the program's name fuzz_<reader> (one binary, linked
// under each name): obj off ply stl mesh tetgen dmat tgf points scene glb (a rigged glTF imported as a scene)
// bvh (a BVH opened alone, then its motion onto the skeleton it made). The input is written to a temp file and read back
// through the public API. A dfm::Error is the expected outcome for bad input; any other exception,
// a sanitizer report, or a failed round trip (read -> write -> read must give the same data) is a bug.
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/export/bvh_motion.h"
#include "core/export/gltf_scene_import.h"
#include "core/mesh/io.h"
#include "core/mesh/mesh_info.h"
#include "core/rig/rig_io.h"
#include "core/scene/scene_file.h"
#include "core/util/error.h"
#include "tests/fuzz/fuzz_scene_fixture.h"

namespace {

std::string g_reader;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string temp_base() {
  static const std::string base = [] {
    const char* dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    return std::string(dir) + "/dfm_fuzz_" + std::to_string(getpid());
  }();
  return base;
}

// The scene reader's folder: the fixed sidecar fixture.scene.bin (see fuzz_scene_fixture.h) beside
// the fuzzed in.scene.json, and out1/ out2/ for the save -> load -> save check.
std::string scene_dir() {
  static const std::string dir = [] {
    const std::string d = temp_base() + "_scene";
    mkdir(d.c_str(), 0700);
    mkdir((d + "/out1").c_str(), 0700);
    mkdir((d + "/out2").c_str(), 0700);
    dfm::write_scene(d + "/fixture.scene.json", dfm::fuzz::fixed_scene());
    return d;
  }();
  return dir;
}

void put(const std::string& path, const uint8_t* data, size_t size) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
}

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "round trip mismatch: %s\n", what);
    std::abort();
  }
}

void exercise_surface(const dfm::TriMesh& m) {
  dfm::bounding_box(m.V);
  dfm::is_closed(m.F);
  dfm::connected_component_count(m.F);
  dfm::degenerate_face_count(m.V, m.F);
  dfm::duplicate_vertex_count(m.V, 1e-3);
}

void surface_round_trip(const dfm::TriMesh& m, const std::string& ext, bool binary) {
  const std::string out = temp_base() + "_out" + ext;
  dfm::write_surface(out, m, binary);
  dfm::TriMesh r = dfm::read_surface(out);
  check(r.V == m.V && r.F == m.F, "surface V/F");
  check(r.N.size() == 0 || r.N == m.N, "surface N");
}

void one_input(const uint8_t* data, size_t size) {
  const std::string& reader = g_reader;
  const std::string base = temp_base();
  if (reader == "obj" || reader == "off" || reader == "ply" || reader == "stl") {
    const std::string path = base + "." + reader;
    put(path, data, size);
    dfm::TriMesh m = dfm::read_surface(path);
    exercise_surface(m);
    if (reader != "stl") surface_round_trip(m, "." + reader, false);
    if (reader == "ply") surface_round_trip(m, ".ply", true);
  } else if (reader == "mesh") {
    const std::string path = base + ".mesh";
    put(path, data, size);
    dfm::TetMesh m = dfm::read_tet_mesh(path);
    dfm::tet_boundary_faces(m.T);
    dfm::write_tet_mesh(base + "_out.mesh", m);
    dfm::TetMesh r = dfm::read_tet_mesh(base + "_out.mesh");
    check(r.V == m.V && r.F == m.F, "mesh V/F");
    check(r.T.rows() == m.T.rows(), "mesh T");  // zero-volume tets may differ in orientation only
  } else if (reader == "tetgen") {
    // "node text" [ "@@\n" "ele text" ]; without a separator a fixed one-tet .ele is used.
    std::string s(reinterpret_cast<const char*>(data), size);
    size_t sep = s.find("@@\n");
    std::string node = s.substr(0, sep), ele = sep == std::string::npos ? "1 4 0\n1 1 2 3 4\n" : s.substr(sep + 3);
    put(base + ".node", reinterpret_cast<const uint8_t*>(node.data()), node.size());
    put(base + ".ele", reinterpret_cast<const uint8_t*>(ele.data()), ele.size());
    dfm::TetMesh m = dfm::read_tet_mesh(base + ".node");
    dfm::non_positive_tet_count(m.V, m.T);
  } else if (reader == "dmat") {
    const std::string path = base + ".dmat";
    put(path, data, size);
    Eigen::MatrixXd M = dfm::read_dmat(path);
    for (bool binary : {false, true}) {
      dfm::write_dmat(base + "_out.dmat", M, binary);
      Eigen::MatrixXd R = dfm::read_dmat(base + "_out.dmat");
      // Shape first: an empty 0 x 10^8 matrix is legal and costs nothing, but comparing it entry-wise walks
      // 10^8 empty columns (a fuzzer timeout in the harness, not in the reader).
      check(R.rows() == M.rows() && R.cols() == M.cols() && (M.size() == 0 || R == M), "dmat");
    }
  } else if (reader == "tgf") {
    const std::string path = base + ".tgf";
    put(path, data, size);
    dfm::TgfData t = dfm::read_tgf(path);
    dfm::Rig rig;
    try {
      dfm::add_tgf_to_rig(rig, t, path);  // may refuse (cycles, pseudo-edges on bones): dfm::Error
    } catch (const dfm::Error&) {
      return;
    }
    dfm::Rig again;
    dfm::add_tgf_to_rig(again, dfm::rig_to_tgf(rig), "again");
    check(again.skeleton.num_bones() == rig.skeleton.num_bones() && again.points.size() == rig.points.size() &&
              again.pseudo_edges == rig.pseudo_edges,
          "tgf rig");
  } else if (reader == "glb") {
    // Whatever imports is a valid scene: it saves and loads back.
    const std::string path = base + ".glb";
    put(path, data, size);
    const dfm::SceneData sc = dfm::import_gltf_scene(path);
    const std::string dir = scene_dir();
    dfm::write_scene(dir + "/out1/g.scene.json", sc);
    const dfm::SceneData back = dfm::read_scene(dir + "/out1/g.scene.json");
    check(back.surface.V.rows() == sc.surface.V.rows() && back.rig.skeleton.num_bones() == sc.rig.skeleton.num_bones() &&
              back.keys.size() == sc.keys.size(),
          "glb scene");
  } else if (reader == "bvh") {
    // Whatever opens alone is a valid scene, and its motion applies back onto its own bones by name.
    const std::string path = base + ".bvh";
    put(path, data, size);
    dfm::SceneData sc = dfm::import_bvh_skeleton(path);
    const size_t keys = sc.keys.size();
    dfm::apply_bvh_motion(sc, path);
    check(sc.keys.size() == keys, "bvh motion onto its own skeleton");
    const std::string dir = scene_dir();
    dfm::write_scene(dir + "/out1/b.scene.json", sc);
    check(dfm::read_scene(dir + "/out1/b.scene.json").rig.skeleton.num_bones() == sc.rig.skeleton.num_bones(), "bvh scene");
  } else if (reader == "scene") {
    const std::string dir = scene_dir();
    put(dir + "/in.scene.json", data, size);
    const dfm::SceneData sc = dfm::read_scene(dir + "/in.scene.json");
    // Whatever loads must save, and save -> load -> save must give the same bytes.
    dfm::write_scene(dir + "/out1/x.scene.json", sc);
    dfm::write_scene(dir + "/out2/x.scene.json", dfm::read_scene(dir + "/out1/x.scene.json"));
    check(slurp(dir + "/out1/x.scene.json") == slurp(dir + "/out2/x.scene.json"), "scene json");
    check(slurp(dir + "/out1/x.scene.bin") == slurp(dir + "/out2/x.scene.bin"), "scene sidecar");
  } else if (reader == "points") {
    const std::string path = base + ".xyz";
    put(path, data, size);
    dfm::read_points(path);
  } else {
    std::fprintf(stderr, "unknown reader '%s': run this program as fuzz_<reader>\n", reader.c_str());
    std::abort();
  }
}

// Removes this process's temp files (dfm_fuzz_<pid>*) when the fuzzer exits normally.
void remove_temp_files() {
  namespace fs = std::filesystem;
  const fs::path base(temp_base());
  std::error_code ec;
  const std::string prefix = base.filename().string();
  for (const auto& e : fs::directory_iterator(base.parent_path(), ec)) {
    const std::string name = e.path().filename().string();  // prefix + '.' or '_' (not another pid's 1234 for 123)
    if (name.size() > prefix.size() && name.rfind(prefix, 0) == 0 && (name[prefix.size()] == '.' || name[prefix.size()] == '_'))
      fs::remove_all(e.path(), ec);
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  temp_base();  // constructed before the handler is registered, so destroyed only after it has run
  std::atexit(remove_temp_files);
  std::string name = (*argv)[0];
  name = name.substr(name.find_last_of('/') + 1);
  g_reader = name.rfind("fuzz_", 0) == 0 ? name.substr(5) : name;
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    one_input(data, size);
  } catch (const dfm::Error&) {
    // the expected, clean failure
  }
  return 0;
}
