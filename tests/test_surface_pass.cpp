// The surface pass: the wireframe geometry shader runs only when the wireframe is on, and the
// shaded-only program draws the same surface (same pixels away from the edges, no edge lines).
#include <cstdlib>

#include <catch2/catch.hpp>

#include "core/view/camera.h"
#include "render/gl_buffer.h"
#include "render/gl_context.h"
#include "render/screenshot.h"
#include "render/surface_pass.h"
#include "tests/gl_offscreen_target.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;

namespace {

// Whether the program in use has a geometry shader: GL_GEOMETRY_VERTICES_OUT is an error without one.
bool current_program_has_geometry_shader() {
  GLint prog = 0;
  glGetIntegerv(GL_CURRENT_PROGRAM, &prog);
  while (glGetError() != GL_NO_ERROR) {
  }
  GLint out = 0;
  glGetProgramiv(static_cast<GLuint>(prog), GL_GEOMETRY_VERTICES_OUT, &out);
  const bool has = glGetError() == GL_NO_ERROR;
  return has && out == 3;
}

gl::Image draw(gl::SurfacePass& pass, const view::Camera& cam, bool wireframe, bool* used_geometry,
               bool cull = false) {
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  gl::SurfaceStyle style;
  style.wireframe = wireframe;
  style.cull_back_faces = cull;
  pass.draw(cam, style);
  *used_geometry = current_program_has_geometry_shader();
  glFinish();
  return gl::read_framebuffer(static_cast<int>(cam.width), static_cast<int>(cam.height));
}

}  // namespace

TEST_CASE("the surface pass skips the wireframe geometry shader when the wireframe is off", "[gl][render]") {
  gl::Context ctx;
  const int n = 160;
  test::OffscreenTarget target(n);
  REQUIRE(glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
  // A unit square facing the camera, split along its diagonal into two triangles.
  TriMesh m;
  m.V.resize(4, 3);
  m.V << -0.5, -0.5, 0, 0.5, -0.5, 0, 0.5, 0.5, 0, -0.5, 0.5, 0;
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 0, 2, 3;
  gl::SurfacePass pass;
  pass.upload_mesh(m);
  view::Camera cam;
  cam.width = cam.height = n;
  bool off_gs = true, on_gs = false;
  const gl::Image off = draw(pass, cam, false, &off_gs);
  const gl::Image on = draw(pass, cam, true, &on_gs);
  CHECK_FALSE(off_gs);
  CHECK(on_gs);
  auto px = [&](const gl::Image& im, int x, int y) { return &im.rgba[(static_cast<size_t>(y) * n + x) * 4]; };
  // Along the shared diagonal (x = y in the image, up to the flip), the wireframe darkens the surface.
  int darker = 0, samples = 0, same = 0, lit = 0;
  for (int i = n / 2 - 20; i <= n / 2 + 20; i += 4) {
    const int x = i, y = n - 1 - i;  // rows are top first: the diagonal from (0,0) to (1,1) in the view
    ++samples;
    int best = 255 * 3;
    for (int dx = -1; dx <= 1; ++dx) {  // the line is anti-aliased: its darkest pixel near the diagonal
      const unsigned char* p = px(on, x + dx, y);
      best = std::min(best, p[0] + p[1] + p[2]);
    }
    const unsigned char* q = px(off, x, y);
    darker += best + 30 < q[0] + q[1] + q[2];
  }
  // Away from the edges the two programs shade identically.
  for (int y = 0; y < n; y += 2)
    for (int x = 0; x < n; x += 2) {
      const unsigned char *a = px(off, x, y), *b = px(on, x, y);
      const bool near_diagonal = std::abs(x - (n - 1 - y)) < 6;
      if (a[0] == 0 && a[1] == 0 && a[2] == 0) continue;  // background
      if (near_diagonal) continue;
      ++lit;
      const bool eq = std::abs(a[0] - b[0]) <= 1 && std::abs(a[1] - b[1]) <= 1 && std::abs(a[2] - b[2]) <= 1;
      same += eq;
    }
  INFO("darker diagonal samples " << darker << " of " << samples << "; identical " << same << " of " << lit);
  CHECK(darker == samples);
  CHECK(lit > 800);
  // The outer edges of the square are wireframe too: allow a border band of differing pixels.
  CHECK(same >= 0.8 * lit);
}

TEST_CASE("culling back faces leaves a closed surface's picture unchanged and hides a back face", "[gl][render]") {
  gl::Context ctx;
  const int n = 160;
  test::OffscreenTarget target(n);
  REQUIRE(glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
  view::Camera cam;
  cam.width = cam.height = n;
  gl::SurfacePass pass;
  bool gs = false;
  auto lit_pixels = [&](const gl::Image& im) {
    int lit = 0;
    for (size_t i = 0; i < im.rgba.size(); i += 4) lit += im.rgba[i] + im.rgba[i + 1] + im.rgba[i + 2] > 0;
    return lit;
  };
  // A closed sphere seen from outside: its back faces lie behind its front faces, so culling them
  // changes no pixel.
  TriMesh sphere = test::icosphere(Eigen::Vector3d::Zero(), 0.6, 3);
  pass.upload_mesh(sphere);
  const gl::Image all = draw(pass, cam, false, &gs, false), culled = draw(pass, cam, false, &gs, true);
  REQUIRE(lit_pixels(all) > n * n / 8);
  CHECK(all.rgba == culled.rgba);
  // One triangle turned away from the camera (clockwise on screen): shown in the back colour, or culled.
  TriMesh back;
  back.V.resize(3, 3);
  back.V << -0.5, -0.5, 0, 0.5, 0.5, 0, 0.5, -0.5, 0;
  back.F.resize(1, 3);
  back.F << 0, 1, 2;
  pass.upload_mesh(back);
  CHECK(lit_pixels(draw(pass, cam, false, &gs, false)) > n * n / 16);
  CHECK(lit_pixels(draw(pass, cam, false, &gs, true)) == 0);
}
