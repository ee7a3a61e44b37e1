// `deform decompress`: one frame of a .pca animation (written by `deform compress`) as a mesh, and/or
// the whole animation as glTF morph targets.
#include <cstdio>

#include "app/cli/command.h"
#include "core/anim/pca_animation.h"
#include "core/anim/pca_file.h"
#include "core/export/gltf_pca.h"
#include "core/mesh/io.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace {

const char* kUsage =
    "usage: deform decompress ANIM.pca [--frame I -o OUT.obj|.ply|.off|.stl] [--gltf OUT.glb|OUT.gltf] [--no-normals]\n"
    "  --frame I -o OUT   frame I (0-based): R_I (mean + sum_j c_Ij B_j) + t_I, with the file's triangles\n"
    "  --gltf OUT         the animation as glTF 2.0 morph targets (as `deform compress --gltf`)\n"
    "  --no-normals       glTF without NORMAL";

int run(const dfm::cli::Args& args) {
  using dfm::cli::UsageError;
  std::string input, out, gltf;
  int frame = -1;
  bool frame_given = false, normals = true;
  dfm::cli::ArgReader r(args);
  while (!r.done()) {
    const std::string f = r.next();
    if (f == "--frame") frame = r.integer(f), frame_given = true;
    else if (f == "-o" || f == "--output") out = r.value(f);
    else if (f == "--gltf") gltf = r.value(f);
    else if (f == "--no-normals") normals = false;
    else if (!f.empty() && f[0] == '-') throw UsageError("unknown option " + f);
    else if (input.empty()) input = f;
    else throw UsageError("more than one input: " + input + ", " + f);
  }
  if (input.empty()) throw UsageError("no ANIM.pca given");
  if (frame_given != !out.empty()) throw UsageError("--frame I and -o OUT go together");
  if (!frame_given && gltf.empty()) throw UsageError("nothing to do: give --frame I -o OUT and/or --gltf OUT");
  if (!gltf.empty() && dfm::file_extension(gltf) != "glb" && dfm::file_extension(gltf) != "gltf")
    throw UsageError("--gltf must name a .glb or .gltf file");

  const dfm::PcaAnimation a = dfm::read_pca(input);
  std::printf("decompress: %s: %d frames of %d vertices and %d triangles, %d base shapes\n", input.c_str(),
              a.num_frames(), a.num_vertices(), static_cast<int>(a.F.rows()), a.num_bases());
  if (frame_given) {
    if (frame < 0 || frame >= a.num_frames())
      throw dfm::Error(input + ": has frames 0 to " + std::to_string(a.num_frames() - 1) + "; --frame " +
                       std::to_string(frame) + " is out of range");
    dfm::write_surface(out, {dfm::pca_frame(a, frame), a.F, {}});
    std::printf("wrote %s: frame %d (t = %g s)\n", out.c_str(), frame, a.times[frame]);
  }
  if (!gltf.empty()) {
    dfm::PcaGltfOptions o;
    o.normals = normals;
    const dfm::PcaGltfReport g = dfm::export_pca_gltf(gltf, a, o);
    std::printf("wrote %s: %d morph targets, %d frames\n", gltf.c_str(), g.morph_targets, g.frames);
  }
  return 0;
}

dfm::cli::Register reg{"decompress", "a frame of a .pca animation as a mesh, or the animation as glTF", kUsage, &run};

}  // namespace
