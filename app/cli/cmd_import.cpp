// `deform import`: a rigged, animated glTF file as a scene (core/export/gltf_scene_import.h).
#include <cstdio>
#include <string>

#include "app/cli/command.h"
#include "core/export/gltf_scene_import.h"
#include "core/scene/scene_file.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace {

const char* kUsage =
    "usage: deform import FILE.glb|FILE.gltf -o SCENE.scene.json\n"
    "  FILE               a glTF 2.0 file with a skinned mesh: its mesh (vertices welded), one bone per\n"
    "                     joint, the file's weights (the scene is bound) and its first animation as keys\n"
    "  -o SCENE           the scene to write (JSON + .scene.bin sidecar); prints what was imported";

int run(const dfm::cli::Args& args) {
  std::string in, out;
  dfm::cli::ArgReader r(args);
  while (!r.done()) {
    const std::string f = r.next();
    if (f == "-o" || f == "--output") out = r.value(f);
    else if (!f.empty() && f[0] == '-') throw dfm::cli::UsageError("unknown option " + f);
    else if (in.empty()) in = f;
    else throw dfm::cli::UsageError("more than one FILE: " + in + ", " + f);
  }
  if (in.empty()) throw dfm::cli::UsageError("FILE is required");
  if (out.size() < 11 || out.compare(out.size() - 11, 11, ".scene.json") != 0)
    throw dfm::cli::UsageError("-o must name a .scene.json file");
  const std::string ext = dfm::file_extension(in);
  if (ext != "glb" && ext != "gltf") throw dfm::Error(in + ": not a glTF file (.glb or .gltf)");
  dfm::GltfImportReport rep;
  const dfm::SceneData scene = dfm::import_gltf_scene(in, &rep);
  dfm::write_scene(out, scene);
  std::printf("import: %s\n%s\nwrote %s\n", in.c_str(), rep.text().c_str(), out.c_str());
  return 0;
}

dfm::cli::Register reg{"import", "a rigged, animated glTF file as a scene", kUsage, &run};

}  // namespace
