// `deform edit-manifold`: drag a handle on an animation manifold and save the edited manifold
// (Southern 2008, 4.3: Laplacian editing of the space-time shape; core/anim/manifold_edit.h).
#include <chrono>
#include <cstdio>

#include <Eigen/Geometry>

#include "app/cli/command.h"
#include "core/anim/manifold_edit.h"
#include "core/anim/manifold_edit_region.h"
#include "core/anim/manifold_io.h"
#include "core/anim/manifold_laplacian.h"
#include "core/anim/manifold_refine.h"
#include "core/anim/manifold_retime.h"
#include "core/util/error.h"

namespace {

const char* kUsage =
    "usage: deform edit-manifold IN.tet4 --region CX CY CZ RADIUS T0 T1 --handle HX HY HZ T --move DX DY DZ\n"
    "                            [--rotate AX AY AZ DEGREES] [--retime DT] [--weights W] [--time-scale S] [--volume]\n"
    "                            [--brush X Y Z ...] [--refine] -o OUT.tet4\n"
    "  Laplacian editing of the animation manifold (Southern 2008, 4.3): the region is every vertex within\n"
    "  RADIUS of (CX, CY, CZ) whose neighbourhood lies in the time window [T0, T1] (so frames outside the\n"
    "  window are unchanged); its boundary ring stays put. The handle is the region's vertices within\n"
    "  RADIUS / 4 of (HX, HY, HZ) on the layers at (or either side of) time T, moved by (DX, DY, DZ) after\n"
    "  turning DEGREES about the axis (AX, AY, AZ) through the handle point. The rest of the region follows\n"
    "  smoothly in space and time, its details turned with the handle (4.2.1). Vertices keep their times.\n"
    "  --brush X Y Z  one more ball of the region's radius at (X, Y, Z) (a brushed region, as the editor's\n"
    "                Shift stroke and the script's edit-brush make); repeatable\n"
    "  --retime DT   move the handle by DT in time as well (the region follows by its reach); refused when\n"
    "                it would fold a slab back in time or the region holds the first or last layer\n"
    "  --weights W   equal, reciprocal (1 / edge length; default), primal-boundary (reciprocal, and at the\n"
    "                manifold's first and last layers the least-|delta| weights of 4.4.1, Eq. 4.3) or dual\n"
    "                (the dual graph Laplacian, rows per tetrahedron, ghost tetrahedra at the boundary: 4.4.2)\n"
    "  --time-scale S  t's factor in the weights' edge lengths (default 1): larger keeps each frame's shape\n"
    "                stiffer against the time edges, so parts past the handle follow it (10 on the keyed arm)\n"
    "  --volume      each edited time layer keeps its enclosed volume (4.2.2; keyframe-built manifolds)\n"
    "  --refine      refine what the edit stretched (4.5.1): the layer triangles with an edge past twice the\n"
    "                region's mean edge length, and two rings round them, split 1:4 (red-green) in every\n"
    "                layer, then the edit made again; prints the vertices added. Needs prism layers of one\n"
    "                mesh (no transition)\n"
    "  Prints the region's sizes and the initialise and deform times in seconds (with --refine, the whole\n"
    "  edit's).";

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

int run(const dfm::cli::Args& args) {
  using dfm::cli::UsageError;
  dfm::cli::ArgReader a(args);
  std::string in, out;
  bool region = false, handle = false, move = false, volume = false, refine = false;
  dfm::EditRegionSpec rs;
  dfm::EditHandleSpec hs;
  dfm::ManifoldDrag drag;
  dfm::ManifoldEditOptions options;
  while (!a.done()) {
    const std::string f = a.next();
    if (f == "--region") {
      for (int i = 0; i < 3; ++i) rs.center[i] = a.number(f);
      rs.radius = a.number(f);
      rs.t0 = a.number(f);
      rs.t1 = a.number(f);
      region = true;
    } else if (f == "--brush") {
      Eigen::Vector3d d;
      for (int i = 0; i < 3; ++i) d[i] = a.number(f);
      rs.dabs.push_back(d);
    } else if (f == "--handle") {
      for (int i = 0; i < 3; ++i) hs.point[i] = a.number(f);
      hs.time = a.number(f);
      handle = true;
    } else if (f == "--move") {
      for (int i = 0; i < 3; ++i) drag.translation[i] = a.number(f);
      move = true;
    } else if (f == "--rotate") {
      Eigen::Vector3d axis;
      for (int i = 0; i < 3; ++i) axis[i] = a.number(f);
      const double degrees = a.number(f);
      if (!(axis.norm() > 0)) throw UsageError("--rotate needs a nonzero axis");
      drag.rotation = Eigen::AngleAxisd(degrees * M_PI / 180, axis.normalized()).toRotationMatrix();
    } else if (f == "--retime") {
      drag.retime = a.number(f);
    } else if (f == "--weights") {
      try {
        options.weights = dfm::parse_laplacian_weights(a.value(f));
      } catch (const dfm::Error& e) {
        throw UsageError(e.what());
      }
    } else if (f == "--time-scale") {
      options.time_scale = a.number(f);
      if (!(options.time_scale > 0)) throw UsageError("--time-scale needs a positive number");
    } else if (f == "--volume") {
      volume = true;
    } else if (f == "--refine") {
      refine = true;
    } else if (f == "-o") {
      out = a.value(f);
    } else if (!f.empty() && f[0] == '-') {
      throw UsageError("unknown option " + f);
    } else if (in.empty()) {
      in = f;
    } else {
      throw UsageError("unexpected argument " + f);
    }
  }
  if (in.empty()) throw UsageError("no input manifold");
  if (!region || !handle || !move) throw UsageError("--region, --handle and --move are required");
  if (out.empty()) throw UsageError("-o OUT.tet4 is required");
  options.preserve_volume = volume;

  dfm::AnimationManifold m = dfm::read_manifold(in);
  const auto t0 = std::chrono::steady_clock::now();
  try {
    dfm::EditRegion sel = dfm::select_edit_region(m, rs, hs);
    std::printf("region: %zu vertices, %zu anchors, %zu handle vertices\n", sel.region.size(), sel.anchors.size(),
                sel.handle.size());
    if (refine) {
      dfm::RefineStats stats;
      m = dfm::edit_refined(m, rs, hs, options, drag, {}, &stats);
      std::printf("refine: %d vertices added to each layer in %d rounds (%d vertices); longest region edge %.3f mean lengths\n",
                  stats.added, stats.rounds, m.num_vertices(), stats.longest);
      std::printf("edit seconds: %.4f\n", seconds_since(t0));
    } else {
      const dfm::ManifoldEditor editor(m, std::move(sel), hs.point, options);
      std::printf("initialise seconds: %.4f\n", seconds_since(t0));
      const auto t1 = std::chrono::steady_clock::now();
      m.V = editor.drag(drag);
      if (drag.retime != 0) dfm::merge_retimed_slabs(m);
      std::printf("deform seconds: %.4f\n", seconds_since(t1));
    }
  } catch (const dfm::Error& e) {
    throw dfm::Error(in + ": " + e.what());
  }
  dfm::write_manifold(out, m);
  std::printf("wrote %s\n", out.c_str());
  return 0;
}

dfm::cli::Register reg{"edit-manifold", "drag a handle on an animation manifold (space-time Laplacian editing)", kUsage, &run};

}  // namespace
