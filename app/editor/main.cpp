// deform-editor [FILE] [--script S.txt] [--screenshot OUT.png] [--quit]
// Opens the editor on FILE (a scene .json, a surface or tet mesh) or on the default scene.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "app/editor/editor.h"
#include "core/util/error.h"
#include "render/gl_context.h"
#include "core/bind/numeric_setup.h"
#include "core/export/assimp_scene_import.h"
#include "core/export/gltf_scene_import.h"

namespace {

void usage(std::FILE* out) {
  std::fprintf(out,
               "usage: deform-editor [FILE] [--script S.txt] [--screenshot OUT.png] [--quit] [--size WxH] [--ui K=V,...]\n"
               "                     [--play-frames N] [--drag-frames N] [--msaa N] [--bind-screenshot F.png]\n"
               "  FILE              a scene (.scene.json), a surface (.obj .off .ply .stl) or tet mesh (.mesh)\n"
               "  --script S.txt    run editor commands (see README.md) after loading\n"
               "  --screenshot F    write a PNG of the window after the script\n"
               "  --quit            exit after the script / screenshot instead of staying open\n"
               "  --size WxH        window size (default 1280x800)\n"
               "  --ui K=V,...      initial state: tool=select|point|bone|paint|paint-weights|move|rotate|pair|\n"
               "                    sculpt|sculpt-transition|spacetime,\n"
               "                    weights=off|selected|all|mask|difference, wireframe=0|1, ortho=0|1, grid=0|1,\n"
               "                    preset=front|right|top|iso..., sweep=t|x|y|z, sweep_at=F (0..1), vertex=N,\n"
               "                    cursor=XxY (mouse held there), frame=all|selection|X:Y:Z:R,\n"
               "                    panels=view:bind:weights:transform:posing (the right panel's open sections)\n"
               "  --play-frames N   play the timeline for N frames and print frame times (benchmark)\n"
               "  --drag-frames N   drag the last space-time edit N frames, print frame times against posing\n"
               "  --bind-screenshot F  write a PNG of the window while the script's bind runs (progress bar)\n"
               "  --msaa N          multisample anti-aliasing samples, 0..8 (default 4; 0 on llvmpipe)\n"
               "Without a display, run it under a virtual X server:\n"
               "  xvfb-run -a -s \"-screen 0 1280x1024x24\" deform-editor ...\n");
}

}  // namespace

// The process-wide numeric settings (core/bind/numeric_setup.h): serial OpenMP regions here,
// setup_numerics() first thing in main.
DFM_RUN_OPENMP_REGIONS_SERIALLY()

int main(int argc, char** argv) {
  dfm::setup_numerics();  // before any bind (numeric_setup.h)
  dfm::register_gltf_scene_importer();     // File > Open and `open` read rigged glTF as scenes
  dfm::register_assimp_scene_importers();  // ... FBX and Collada; load-motion reads BVH
  dfm::editor::EditorOptions opts;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const char* flag) -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "deform-editor: %s needs a value\n", flag);
        usage(stderr);
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      usage(stdout);
      return 0;
    } else if (a == "--script") {
      opts.script = value("--script");
    } else if (a == "--screenshot") {
      opts.screenshot = value("--screenshot");
    } else if (a == "--play-frames") {
      opts.play_frames = std::atoi(value("--play-frames").c_str());
    } else if (a == "--drag-frames") {
      opts.drag_frames = std::atoi(value("--drag-frames").c_str());
    } else if (a == "--bind-screenshot") {
      opts.bind_screenshot = value("--bind-screenshot");
    } else if (a == "--msaa") {
      const std::string v = value("--msaa");
      char* end = nullptr;
      const long n = std::strtol(v.c_str(), &end, 10);
      if (v.empty() || *end || n < 0 || n > 8) {
        std::fprintf(stderr, "deform-editor: --msaa wants 0..8, got '%s'\n", v.c_str());
        return 2;
      }
      opts.msaa = static_cast<int>(n);
    } else if (a == "--ui") {
      opts.ui = value("--ui");
    } else if (a == "--quit") {
      opts.quit = true;
    } else if (a == "--size") {
      const std::string v = value("--size");
      if (std::sscanf(v.c_str(), "%dx%d", &opts.width, &opts.height) != 2 || opts.width < 320 || opts.height < 240) {
        std::fprintf(stderr, "deform-editor: --size wants WxH (at least 320x240), got '%s'\n", v.c_str());
        return 2;
      }
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "deform-editor: unknown option %s\n", a.c_str());
      usage(stderr);
      return 2;
    } else if (opts.file.empty()) {
      opts.file = a;
    } else {
      std::fprintf(stderr, "deform-editor: more than one file given (%s, %s)\n", opts.file.c_str(), a.c_str());
      return 2;
    }
  }
  try {
    dfm::editor::Editor editor(opts);
    return editor.run();
  } catch (const dfm::Error& e) {
    std::fprintf(stderr, "deform-editor: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "deform-editor: unexpected error: %s\n", e.what());
    return 1;
  }
}
