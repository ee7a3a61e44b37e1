// `deform import`: a rigged, animated glTF, FBX or Collada file as a scene (core/export/gltf_scene_import.h,
// assimp_scene_import.h), a BVH alone, or BVH motion onto a scene's rig by bone name (bvh_motion.h).
#include <cstdio>
#include <string>

#include "app/cli/command.h"
#include "core/export/bvh_motion.h"
#include "core/scene/scene_file.h"
#include "core/scene/scene_import.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace {

const char* kUsage =
    "usage: deform import FILE.glb|.gltf|.fbx|.dae|.bvh -o SCENE.scene.json\n"
    "       deform import MOTION.bvh --onto SCENE.scene.json -o OUT.scene.json\n"
    "  FILE               a rigged file (glTF 2.0, FBX, Collada) with a skinned mesh: its mesh (vertices welded),\n"
    "                     one bone per joint, the file's weights (the scene is bound) and its first animation\n"
    "                     as keys; a BVH alone: its skeleton as bones and its frames as keys, no mesh\n"
    "  MOTION.bvh --onto  the BVH's motion onto SCENE's bones by name (keys replaced; prints the names\n"
    "                     matched and not)\n"
    "  -o SCENE           the scene to write (JSON + .scene.bin sidecar); prints what was imported";

bool is_scene_json(const std::string& p) { return p.size() >= 11 && p.compare(p.size() - 11, 11, ".scene.json") == 0; }

int run(const dfm::cli::Args& args) {
  std::string in, out, onto;
  dfm::cli::ArgReader r(args);
  while (!r.done()) {
    const std::string f = r.next();
    if (f == "-o" || f == "--output") out = r.value(f);
    else if (f == "--onto") onto = r.value(f);
    else if (!f.empty() && f[0] == '-') throw dfm::cli::UsageError("unknown option " + f);
    else if (in.empty()) in = f;
    else throw dfm::cli::UsageError("more than one FILE: " + in + ", " + f);
  }
  if (in.empty()) throw dfm::cli::UsageError("FILE is required");
  if (!is_scene_json(out)) throw dfm::cli::UsageError("-o must name a .scene.json file");
  const std::string ext = dfm::file_extension(in);
  if (ext == "bvh" && !onto.empty()) {
    dfm::SceneData scene = dfm::read_scene(onto);
    dfm::BvhReport rep;
    dfm::apply_bvh_motion(scene, in, &rep);
    dfm::write_scene(out, scene);
    std::printf("import: %s onto %s\n%s\nwrote %s\n", in.c_str(), onto.c_str(), rep.text().c_str(), out.c_str());
    return 0;
  }
  if (!onto.empty()) throw dfm::cli::UsageError("--onto takes motion (.bvh), not " + in);
  const dfm::SceneImporter* import = dfm::scene_importer_for(in);
  if (!import) throw dfm::Error(in + ": not a rigged file this reads (.glb .gltf .fbx .dae .bvh)");
  std::string report;
  const dfm::SceneData scene = (*import)(in, report);
  dfm::write_scene(out, scene);
  std::printf("import: %s\n%s\nwrote %s\n", in.c_str(), report.c_str(), out.c_str());
  return 0;
}

dfm::cli::Register reg{"import", "a rigged, animated glTF, FBX, Collada or BVH file as a scene; BVH motion onto one", kUsage, &run};

}  // namespace
