// `deform manifold`: join keyframe meshes into an animation manifold and save slices of it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>

#include "app/cli/command.h"
#include "core/anim/manifold.h"
#include "core/anim/manifold_frame.h"
#include "core/anim/manifold_io.h"
#include "core/anim/frame_sequence.h"
#include "core/anim/inbetween.h"
#include "core/anim/manifold_sequence.h"
#include "core/anim/pair_file.h"
#include "core/anim/slice.h"
#include "core/anim/surface_checks.h"
#include "core/mesh/io.h"
#include "core/util/error.h"
#include "core/view/camera.h"
#include "render/gl_context.h"
#include "render/screenshot.h"
#include "render/slice_pass.h"
#include "render/surface_pass.h"

namespace {

const char* kUsage =
    "usage: deform manifold (--keyframes K0.obj K1.obj ... [--times t0 t1 ...] | --manifold M.tet4)\n"
    "                       [--axis t|x|y|z] [--at VALUE -o SLICE.obj] [--save-manifold M.tet4] [--stats]\n"
    "                       [--frames N [--sequence PREFIX] [--strip STRIP.png]] [--inbetween arap|linear [--inbetweens N]]\n"
    "                       [--pairs P.txt]\n"
    "  Keyframes are meshes of any connectivity (default times 0, 1, 2, ...), joined into 4D tetrahedra\n"
    "  (x, y, z, t): neighbours sharing one triangle list by the exact prism build, others by a transition\n"
    "  (those keys must be closed, oriented and not self-intersecting; a transition removes the keys' relative\n"
    "  placement, centroid, rotation and scale, morphs, and puts it back along the way: a moved key travels, a\n"
    "  turned key turns). --at slices at that value of --axis (default t; x, y, z give the sweep\n"
    "  through time drawn in the other three coordinates) and writes the welded slice with normals.\n"
    "  --inbetween arap puts N (default 8) layers between neighbouring keyframes of one connectivity,\n"
    "  interpolated as rigidly as possible (Alexa 2002, 4.4: a turning limb keeps its shape); linear blends\n"
    "  vertices (the prism build's own in-between); handles needs the editor's pose keys.\n"
    "  --sequence writes N slices on t evenly spaced over the animation as PREFIX0000.obj, ...\n"
    "  (PREFIX ending in .ply, .off or .stl picks that format)\n"
    "  --strip renders those N frames side by side (transitions on the GPU slicer; needs a display: xvfb-run).\n"
    "  --pairs picks points that travel to each other in transitions: one pair a line, x0 y0 z0 x1 y1 z1 (a\n"
    "  point on a key, its partner on the next); a line 'pair K' sends the lines after it to keys K and K+1\n"
    "  (0-based, default 0); blank lines and # comments are skipped. Each point must lie on its key (within 2%\n"
    "  of its bounding-box diagonal); neighbours of one connectivity take no pairs.\n"
    "  --stats prints the build (prism / transition slabs, Steiner points, the last transition's turn and\n"
    "  scale, the closest-point pairs the warp also went through, seconds per stage: align, conform, field, delaunay, extract and its relax, total), the tetrahedron count and the slice's triangles, vertices,\n"
    "  closedness, volume.";

void print_stats(const dfm::AnimationManifold& M, const dfm::ManifoldSlice& s, dfm::SliceAxis axis, double at) {
  const bool closed = s.mesh.num_faces() > 0 && dfm::is_closed_and_oriented(s.mesh.F);
  std::cout << "tets: " << M.num_tets() << "\nlayers: " << M.num_layers() << "\nslice: " << dfm::slice_axis_name(axis)
            << " = " << at << "\nslice triangles: " << s.mesh.num_faces() << "\nslice vertices: " << s.mesh.num_vertices()
            << "\nclosed: " << (closed ? "yes" : "no") << "\n";
  if (closed)
    std::cout << "volume: " << dfm::enclosed_volume(s.mesh.V, s.mesh.F) << "\n";
  else if (axis != dfm::SliceAxis::T && dfm::is_oriented_manifold(s.mesh.F))
    // A sweep is open only where the animation starts or ends; the flux along a spatial axis
    // counts those missing caps correctly.
    std::cout << "volume (open only at the first/last time): " << dfm::flux_volume(s.mesh.V, s.mesh.F, 0) << "\n";
  else
    std::cout << "volume: n/a (open slice)\n";
}

// What the build did and how long each stage took (transitions: conforming Delaunay and the keys'
// fill, the blended field's layers, the 4D Delaunay, extracting the level set).
void print_sequence_stats(const dfm::SequenceStats& s) {
  const dfm::TransitionStats& t = s.transitions;
  std::cout << "prism slabs: " << s.prism_slabs << "\ntransition slabs: " << s.transition_slabs
            << "\nsteiner points: " << t.source.steiner + t.target.steiner << "\nturn degrees: " << t.turn_degrees
            << "\nscale: " << t.scale << "\nelastic pairs: " << t.elastic_pairs << "\nmiddle points: " << t.middle_points
            << " (refined: " << t.refined_points << ")\nshort-lived events merged: " << t.transients << "\nalign seconds: " << t.align_seconds << "\nconform seconds: " << t.conform_seconds
            << "\nfield seconds: " << t.field_seconds << "\ndelaunay seconds: " << t.delaunay_seconds
            << "\nextract seconds: " << t.extract_seconds << "\nrelax seconds: " << t.relax_seconds
            << "\ntransition seconds: " << t.total_seconds
            << "\ntotal seconds: " << s.seconds << "\n";
}

// N frames side by side: between keys of one connectivity the keys' mesh (manifold_frame), in a
// transition the GPU slice (slice shader -> transform feedback -> surface pass).
void render_strip(const dfm::AnimationManifold& M, int frames, const std::string& png) {
  namespace gl = dfm::gl;
  namespace view = dfm::view;
  const int w = std::max(64, std::min(320, 1260 / frames)), h = 400;
  gl::ContextOptions opts;
  opts.width = w * frames;
  opts.height = h;
  gl::Context ctx(opts);
  gl::SlicePass slicer;
  slicer.upload(M);
  gl::SurfacePass surface;
  view::Camera cam;
  cam.width = w;
  cam.height = h;
  const Eigen::Vector3d lo = M.V.leftCols<3>().colwise().minCoeff().transpose();
  const Eigen::Vector3d hi = M.V.leftCols<3>().colwise().maxCoeff().transpose();
  view::set_view_preset(cam, view::ViewPreset::Front);
  view::frame_box(cam, lo, hi);
  glViewport(0, 0, w * frames, h);
  glClearColor(0.145f, 0.15f, 0.165f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  const double t0 = M.times.front(), t1 = M.times.back();
  for (int i = 0; i < frames; ++i) {
    const double t = dfm::frame_time(t0, t1, i, frames);
    glViewport(i * w, 0, w, h);
    if (dfm::prism_slab_at(M, t) >= 0) {  // the keys' own mesh, as --sequence writes it
      surface.upload_mesh(dfm::manifold_frame(M, t).mesh);
    } else {  // a transition: the GPU slicer
      const int n = slicer.slice(dfm::SliceAxis::T, t);
      surface.set_geometry(slicer.output().id(), 3 * n, 0, 0);
    }
    surface.draw(cam, gl::SurfaceStyle{});
  }
  glFinish();
  glReadBuffer(GL_BACK);
  gl::write_png(png, gl::read_framebuffer(w * frames, h));
  std::printf("wrote %s (%d frames, t = %g .. %g, %s)\n", png.c_str(), frames, t0, t1, ctx.renderer().c_str());
}

// Reads --pairs into the keys (KeySurface::pairs_to_next), checking each pair against its keys: errors
// name the file and line.
void attach_pairs(const std::string& path, std::vector<dfm::KeySurface>& keys) {
  const dfm::PairFile pf = dfm::read_pair_file(path, static_cast<int>(keys.size()));
  for (size_t k = 0; k + 1 < keys.size(); ++k) {
    if (pf.pairs[k].rows() == 0) continue;
    const int first_line = pf.lines[k].front();
    if (dfm::same_connectivity(keys[k], keys[k + 1]))
      throw dfm::file_error(path, first_line, "keys " + std::to_string(k) + " and " + std::to_string(k + 1) + " (" +
                                                  keys[k].name + ", " + keys[k + 1].name +
                                                  ") share one triangle list: pairs apply to transitions only");
    const dfm::TriMesh a{keys[k].V, keys[k].F, {}}, b{keys[k + 1].V, keys[k + 1].F, {}};
    dfm::check_transition_key(a, keys[k].name);
    dfm::check_transition_key(b, keys[k + 1].name);
    if (const auto bad = dfm::transition_pair_problem(a, b, pf.pairs[k]))
      throw dfm::file_error(path, pf.lines[k][bad->pair], bad->problem + " (keys " + keys[k].name + ", " + keys[k + 1].name + ")");
    keys[k].pairs_to_next = pf.pairs[k];
  }
}

// What the command line asks for.
struct Options {
  std::vector<std::string> keyframes, times_text;
  std::string manifold_in, out, save_manifold, sequence, strip, pairs_file;
  std::optional<double> at;
  dfm::SliceAxis axis = dfm::SliceAxis::T;
  bool stats = false;
  int frames = 0;
  std::optional<dfm::InbetweenMethod> inbetween;
  int inbetweens = 8;
};

template <class Parse>
auto parsed(const Parse& parse) {
  try {
    return parse();
  } catch (const dfm::Error& e) {
    throw dfm::cli::UsageError(e.what());
  }
}

Options parse_options(const dfm::cli::Args& args) {
  using dfm::cli::UsageError;
  dfm::cli::ArgReader r(args);
  Options o;
  while (!r.done()) {
    const std::string f = r.next();
    if (f == "--keyframes") o.keyframes = r.values(f);
    else if (f == "--times") o.times_text = r.values(f);
    else if (f == "--manifold") o.manifold_in = r.value(f);
    else if (f == "--axis") o.axis = parsed([&] { return dfm::parse_slice_axis(r.value(f)); });
    else if (f == "--at") o.at = r.number(f);
    else if (f == "-o" || f == "--output") o.out = r.value(f);
    else if (f == "--save-manifold") o.save_manifold = r.value(f);
    else if (f == "--stats") o.stats = true;
    else if (f == "--frames") o.frames = r.integer(f);
    else if (f == "--sequence") o.sequence = r.value(f);
    else if (f == "--strip") o.strip = r.value(f);
    else if (f == "--inbetween") {
      o.inbetween = parsed([&] { return dfm::parse_inbetween_method(r.value(f)); });
      if (*o.inbetween == dfm::InbetweenMethod::Handles)
        throw UsageError("--inbetween handles needs pose keys and a rig (the editor's timeline); keyframe files have "
                         "no handles: use arap or linear");
    } else if (f == "--inbetweens") o.inbetweens = r.integer(f);
    else if (f == "--pairs") o.pairs_file = r.value(f);
    else throw UsageError("unknown argument '" + f + "'");
  }
  return o;
}

void check_options(const Options& o) {
  using dfm::cli::UsageError;
  if (o.keyframes.empty() == o.manifold_in.empty()) throw UsageError("give either --keyframes or --manifold");
  if (o.inbetween && o.keyframes.empty()) throw UsageError("--inbetween goes with --keyframes");
  if (!o.pairs_file.empty() && o.keyframes.empty()) throw UsageError("--pairs goes with --keyframes");
  if (o.inbetweens < 0 || o.inbetweens > 1000) throw UsageError("--inbetweens needs a count in 0..1000");
  if (!o.manifold_in.empty() && !o.times_text.empty()) throw UsageError("--times goes with --keyframes");
  if (!o.out.empty() && !o.at) throw UsageError("-o needs --at VALUE");
  if (o.at && o.out.empty() && !o.stats) throw UsageError("--at needs -o SLICE.obj (or --stats)");
  if ((o.frames != 0) != (!o.sequence.empty() || !o.strip.empty()))
    throw UsageError("--frames N goes with --sequence PREFIX and/or --strip STRIP.png");
  if (o.frames < 0 || o.frames > 100000) throw UsageError("--frames needs a count >= 1");
  if (!o.at && o.sequence.empty() && o.strip.empty() && o.save_manifold.empty())
    throw UsageError("nothing to do: give --at, --sequence, --strip or --save-manifold");
  if (!o.keyframes.empty() && o.keyframes.size() < 2) throw UsageError("--keyframes needs at least 2 meshes");
}

// --times, or 0, 1, 2, ...
std::vector<double> key_times(const Options& o) {
  using dfm::cli::UsageError;
  std::vector<double> times;
  if (o.times_text.empty()) {
    for (size_t i = 0; i < o.keyframes.size(); ++i) times.push_back(static_cast<double>(i));
    return times;
  }
  if (o.times_text.size() != o.keyframes.size())
    throw UsageError("--times has " + std::to_string(o.times_text.size()) + " values for " +
                     std::to_string(o.keyframes.size()) + " keyframes");
  for (const auto& s : o.times_text) {
    char* end = nullptr;
    const double t = std::strtod(s.c_str(), &end);
    if (end == s.c_str() || *end || !std::isfinite(t)) throw UsageError("--times: not a number '" + s + "'");
    if (!times.empty() && !(t > times.back())) throw UsageError("--times must be strictly increasing");
    times.push_back(t);
  }
  return times;
}

// Neighbours sharing one triangle list: the exact prism build (with in-between layers as rigid as
// possible, or linear, when asked); others: a transition, whose keys build_manifold_sequence checks
// first (errors name the file).
dfm::AnimationManifold build_from_keyframes(const Options& o) {
  const std::vector<double> times = key_times(o);
  std::vector<dfm::KeySurface> keys;
  for (size_t i = 0; i < o.keyframes.size(); ++i) {
    dfm::TriMesh k = dfm::read_surface(o.keyframes[i]);
    if (k.num_faces() == 0) throw dfm::Error(o.keyframes[i] + ": mesh has no triangles");
    keys.push_back({times[i], std::move(k.V), std::move(k.F), o.keyframes[i]});
  }
  if (!o.pairs_file.empty()) attach_pairs(o.pairs_file, keys);
  if (o.inbetween)
    keys = dfm::with_mesh_inbetweens(keys, std::vector<dfm::InbetweenMethod>(keys.size(), *o.inbetween), o.inbetweens);
  dfm::SequenceStats seq;
  dfm::AnimationManifold M = dfm::build_manifold_sequence(keys, {}, &seq);
  if (o.stats) print_sequence_stats(seq);
  return M;
}

int run(const dfm::cli::Args& args) {
  const Options o = parse_options(args);
  check_options(o);
  const dfm::AnimationManifold M = o.manifold_in.empty() ? build_from_keyframes(o) : dfm::read_manifold(o.manifold_in);
  if (!o.save_manifold.empty()) dfm::write_manifold(o.save_manifold, M);
  if (o.at) {
    // In time, the frame (a same-connectivity interval's own mesh); across it, the sweep's slice.
    const dfm::ManifoldSlice s =
        o.axis == dfm::SliceAxis::T ? dfm::manifold_frame(M, *o.at) : dfm::slice_manifold(M, o.axis, *o.at);
    if (!o.out.empty()) dfm::write_surface(o.out, s.mesh);
    if (o.stats) print_stats(M, s, o.axis, *o.at);
  }
  if (!o.sequence.empty()) {
    const std::vector<std::string> paths = dfm::write_frame_sequence(M, o.sequence, o.frames);
    std::printf("wrote %d frames: %s .. %s\n", o.frames, paths.front().c_str(), paths.back().c_str());
  }
  if (!o.strip.empty()) render_strip(M, o.frames, o.strip);
  return 0;
}

dfm::cli::Register reg{"manifold", "animation manifold from keyframes: slice, save, sequence", kUsage, &run};

}  // namespace
