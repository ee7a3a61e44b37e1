#include "render/overlay_pass.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "render/surface_pass.h"  // to_gl

namespace dfm::gl {

OverlayPass::OverlayPass()
    : lines_(ProgramDesc{"overlay.vert.glsl", "overlay_line.geom.glsl", "overlay_line.frag.glsl", {}, {}}),
      points_(ProgramDesc{"overlay.vert.glsl", "", "overlay_point.frag.glsl", {}, {}}) {}

void OverlayPass::bind_stream(const view::Camera& cam, const std::vector<OverlayVertex>& v, const Program& prog) {
  prog.use();
  float m[16];
  to_gl(view::projection_matrix(cam) * view::view_matrix(cam), m);
  glUniformMatrix4fv(prog.uniform("u_view_proj"), 1, GL_FALSE, m);
  glUniform2f(prog.uniform("u_viewport"), float(cam.width), float(cam.height));
  vao_.bind();
  stream_.upload(GL_ARRAY_BUFFER, v, GL_STREAM_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(OverlayVertex),
                        reinterpret_cast<void*>(offsetof(OverlayVertex, position)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(OverlayVertex),
                        reinterpret_cast<void*>(offsetof(OverlayVertex, color)));
}

void OverlayPass::draw_lines(const view::Camera& cam, const std::vector<OverlayVertex>& pairs, float width,
                             bool depth_test) {
  if (pairs.size() < 2) return;
  bind_stream(cam, pairs, lines_);
  glUniform1f(lines_.uniform("u_line_width"), width);
  if (depth_test) glEnable(GL_DEPTH_TEST); else glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(pairs.size() / 2 * 2));
  glDepthMask(GL_TRUE);
  glBindVertexArray(0);
}

void OverlayPass::draw_points(const view::Camera& cam, const std::vector<OverlayVertex>& points, float size_px,
                              bool depth_test) {
  if (points.empty()) return;
  bind_stream(cam, points, points_);
  glUniform1f(points_.uniform("u_point_size"), size_px);
  glEnable(GL_PROGRAM_POINT_SIZE);
  if (depth_test) glEnable(GL_DEPTH_TEST); else glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(points.size()));
  glDepthMask(GL_TRUE);
  glBindVertexArray(0);
}

}  // namespace dfm::gl
