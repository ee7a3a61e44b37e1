// Playback from a cached interval (render/interval_slice_pass, shaders/surface.vert.glsl with
// INTERVAL) against the CPU frame (manifold_frame: the layers' mesh between prism layers, the slice
// in a transition); the surface pass drawing the records equals drawing their read-back;
// and the editor's cache-or-general-pass loop (app/editor/slice_cache) on a real GL context.
#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>

#include <catch2/catch.hpp>

#include "app/editor/slice_cache.h"
#include "core/anim/interval_slice.h"
#include "core/anim/manifold_frame.h"
#include "core/anim/manifold_normals.h"
#include "core/anim/slice.h"
#include "render/gl_context.h"
#include "render/interval_slice_pass.h"
#include "render/screenshot.h"
#include "render/slice_pass.h"
#include "render/surface_pass.h"
#include "tests/gl_offscreen_target.h"
#include "tests/interval_slice_test_manifolds.h"

using namespace dfm;

namespace {

double diagonal(const AnimationManifold& M) {
  return (M.V.colwise().maxCoeff() - M.V.colwise().minCoeff()).head<3>().norm();
}

// The GPU's welded vertices equal the CPU slice's as a set (each matches a distinct CPU vertex within
// tol), in fact in the same order, with the same triangles; normals unit and within 1e-4.
void require_same_slice(const ManifoldSlice& cpu, const gl::IntervalSlicePass& pass, double tol) {
  const std::vector<gl::PosNormal> gpu = pass.read_back();
  const int nv = cpu.mesh.num_vertices();
  REQUIRE(nv > 0);
  REQUIRE(static_cast<int>(gpu.size()) == nv);
  REQUIRE(pass.num_triangles() == cpu.mesh.num_faces());
  REQUIRE(pass.faces() == cpu.mesh.F);
  std::vector<std::pair<double, int>> by_x(nv);
  for (int v = 0; v < nv; ++v) by_x[v] = {cpu.mesh.V(v, 0), v};
  std::sort(by_x.begin(), by_x.end());
  // A maximum matching (augmenting paths) of GPU to CPU vertices within tol: a set equality that
  // holds where many slice vertices lie within float rounding of each other.
  std::vector<std::vector<int>> near(nv);
  double worst_same_index = 0, worst_normal = 0, worst_length = 0;
  for (int g = 0; g < nv; ++g) {
    const Eigen::Vector3d q(gpu[g].position[0], gpu[g].position[1], gpu[g].position[2]);
    const Eigen::Vector3d n(gpu[g].normal[0], gpu[g].normal[1], gpu[g].normal[2]);
    for (auto it = std::lower_bound(by_x.begin(), by_x.end(), std::make_pair(q.x() - tol, -1));
         it != by_x.end() && it->first <= q.x() + tol; ++it)
      if ((cpu.mesh.V.row(it->second).transpose() - q).norm() <= tol) near[g].push_back(it->second);
    worst_same_index = std::max(worst_same_index, (cpu.mesh.V.row(g).transpose() - q).norm());
    worst_normal = std::max(worst_normal, (cpu.mesh.N.row(g).transpose() - n).norm());
    worst_length = std::max(worst_length, std::abs(n.norm() - 1));
  }
  std::vector<int> owner(nv, -1);  // CPU vertex -> its GPU vertex
  std::vector<int> seen(nv, -1);
  std::function<bool(int, int)> augment = [&](int g, int round) {
    for (int c : near[g]) {
      if (seen[c] == round) continue;
      seen[c] = round;
      if (owner[c] < 0 || augment(owner[c], round)) {
        owner[c] = g;
        return true;
      }
    }
    return false;
  };
  int unmatched = 0;
  for (int g = 0; g < nv; ++g) unmatched += !augment(g, g);
  REQUIRE(unmatched == 0);
  INFO("largest vertex difference " << worst_same_index << ", normal " << worst_normal);
  REQUIRE(worst_same_index <= tol);
  REQUIRE(worst_normal <= 1e-4);
  REQUIRE(worst_length <= 1e-5);
}

}  // namespace

TEST_CASE("the interval pass equals the CPU slice at times inside each interval", "[gl][manifold][interval]") {
  gl::Context ctx;
  INFO(ctx.renderer());
  gl::IntervalSlicePass pass;
  for (int which = 0; which < 2; ++which) {
    const AnimationManifold M = which == 0 ? test::deforming_sphere_manifold() : test::sphere_to_box_transition();
    const Eigen::MatrixXd N4 = manifold_vertex_normals(M);
    const std::vector<double> times = manifold_vertex_times(M);
    const double tol = 1e-5 * diagonal(M);
    const int n = static_cast<int>(times.size()) - 1;
    std::vector<int> intervals;
    if (which == 0) intervals = {0, 1};
    else intervals = {0, n / 4, n / 2, n - 1};
    for (int i : intervals) {
      INFO((which == 0 ? "prism manifold" : "transition") << ", interval " << i << " of " << n);
      const IntervalSlice s = build_interval_slice(M, N4, times[i], times[i + 1]);
      pass.upload(s, M, N4);
      REQUIRE(pass.num_vertices() == s.num_vertices());
      for (double f : {0.02, 0.3, 0.5, 0.71, 0.98}) {
        const double t = times[i] + f * (times[i + 1] - times[i]);
        if (!(times[i] < t && t < times[i + 1])) continue;
        INFO("t = " << t);
        REQUIRE(pass.contains(t));
        pass.evaluate(t);
        require_same_slice(manifold_frame(M, t, &N4), pass, tol);
      }
      REQUIRE_FALSE(pass.contains(times[i]));
      REQUIRE_FALSE(pass.contains(times[i + 1]));
      REQUIRE(pass.reaches(times[i + 1]));
      REQUIRE_THROWS(pass.evaluate(times[i] - 0.5 * (times[i + 1] - times[i])));
    }
  }
}

// The surface pass draws an interval's records (interpolated in its vertex shader) as the same picture
// as the PosNormal vertices read back from that shader: the records' attributes reach the shader.
TEST_CASE("drawing an interval's records equals drawing its read-back vertices", "[gl][manifold][interval]") {
  gl::Context ctx;
  const int n = 200;
  test::OffscreenTarget target(n);
  REQUIRE(glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
  const AnimationManifold M = test::deforming_sphere_manifold();
  const Eigen::MatrixXd N4 = manifold_vertex_normals(M);
  const std::vector<double> times = manifold_vertex_times(M);
  gl::IntervalSlicePass pass;
  pass.upload(build_interval_slice(M, N4, times[0], times[1]), M, N4);
  pass.evaluate(times[0] + 0.4 * (times[1] - times[0]));
  view::Camera cam;
  cam.width = cam.height = n;
  gl::SurfacePass surface;
  auto draw = [&]() {
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    surface.draw(cam, gl::SurfaceStyle{});
    glFinish();
    return gl::read_framebuffer(n, n);
  };
  surface.set_interval_geometry(pass.record_buffer(), pass.num_vertices(), pass.index_buffer(), pass.index_count(),
                                pass.dt());
  const gl::Image from_records = draw();
  const std::vector<gl::PosNormal> v = pass.read_back();
  gl::Buffer vertices;
  vertices.upload(GL_ARRAY_BUFFER, v);
  surface.set_geometry(vertices.id(), static_cast<int>(v.size()), pass.index_buffer(), pass.index_count());
  const gl::Image from_read_back = draw();
  int lit = 0;
  for (size_t i = 0; i < from_records.rgba.size(); i += 4) lit += from_records.rgba[i] > 0;
  REQUIRE(lit > n * n / 10);
  CHECK(from_records.rgba == from_read_back.rgba);
  // A later time moves the drawing (the time reaches the shader).
  pass.evaluate(times[0] + 0.9 * (times[1] - times[0]));
  surface.set_interval_geometry(pass.record_buffer(), pass.num_vertices(), pass.index_buffer(), pass.index_count(),
                                pass.dt());
  CHECK(draw().rgba != from_records.rgba);
}

// The editor's loop (scene_view.cpp) in miniature: the policy picks a route, a Build fills the slot's
// pass, Cached and Build draw from it, General runs the per-tetrahedron pass. Playback at 1/30 s from
// 0 towards 2.5 on the prism manifold builds each interval once, rebuilds on crossing into the next, and
// every frame equals the CPU slice (on t = 1, the vertex time that ends the cached interval 0, its limit).
TEST_CASE("playback draws from the interval cache and rebuilds when t leaves the interval", "[gl][manifold][interval]") {
  gl::Context ctx;
  const AnimationManifold M = test::deforming_sphere_manifold();
  const Eigen::MatrixXd N4 = manifold_vertex_normals(M);
  const double tol = 1e-5 * diagonal(M);
  editor::IntervalCachePolicy policy(2);
  policy.reset(manifold_vertex_times(M));
  std::vector<std::unique_ptr<gl::IntervalSlicePass>> slots(policy.capacity());
  gl::SlicePass general;
  general.upload(M, &N4);
  const double step = 1.0 / 30.0;
  int cached = 0, built = 0, general_frames = 0;
  std::vector<int> built_intervals;
  double prev = 0;
  for (int frame = 0; frame <= 74; ++frame) {  // t < 2.5, the last vertex time
    const double t = frame == 30 ? 1.0 : frame * step;  // frame 0 and 30: on a vertex time
    INFO("frame " << frame << ", t = " << t);
    const ManifoldSlice cpu = manifold_frame(M, t, &N4);
    editor::SliceDecision d = policy.choose(true, t, frame ? t - prev : 0.0);
    prev = t;
    if (d.route == editor::SliceRoute::Build) {
      const auto& times = policy.times();
      if (!slots[d.slot]) slots[d.slot] = std::make_unique<gl::IntervalSlicePass>();
      slots[d.slot]->upload(build_interval_slice(M, N4, times[d.interval], times[d.interval + 1]), M, N4);
      built_intervals.push_back(d.interval);
      ++built;
    }
    if (d.route == editor::SliceRoute::General) {
      ++general_frames;
      REQUIRE(general.slice(SliceAxis::T, t) == cpu.mesh.num_faces());
      continue;
    }
    cached += d.route == editor::SliceRoute::Cached;
    gl::IntervalSlicePass& pass = *slots[d.slot];
    pass.evaluate(t);
    if (pass.contains(t)) {
      require_same_slice(cpu, pass, tol);
    } else {  // t = 1, the end of the cached interval 0: its limit, the same points as the CPU slice
      REQUIRE(t == 1.0);
      const std::vector<gl::PosNormal> gpu = pass.read_back();
      for (const gl::PosNormal& p : gpu) {
        const Eigen::RowVector3d q(p.position[0], p.position[1], p.position[2]);
        REQUIRE((cpu.mesh.V.rowwise() - q).rowwise().norm().minCoeff() <= tol);
      }
    }
  }
  REQUIRE(general_frames == 1);  // t = 0, before any interval is cached
  REQUIRE(built_intervals == std::vector<int>{0, 1});
  REQUIRE(built == 2);
  REQUIRE(cached == 75 - 1 - 2);
  // Scrubbing back into the first interval: still cached.
  REQUIRE(policy.choose(true, 0.5, -1.0).route == editor::SliceRoute::Cached);
}
