#pragma once
// Overlays drawn over the surface: ground grid, handles (round point sprites), bones and cage
// wireframes (wide anti-aliased lines), the paint brush circle. Geometry is built on the CPU each
// frame (a few thousand vertices at most, render/overlay_geometry.h) and streamed.
#include <vector>

#include "core/view/camera.h"
#include "render/gl_buffer.h"
#include "render/gl_program.h"
#include "render/overlay_geometry.h"

namespace dfm::gl {

class OverlayPass {
 public:
  OverlayPass();
  // Pairs of vertices; width in pixels. depth_test=false draws on top of the surface (x-ray).
  void draw_lines(const view::Camera& cam, const std::vector<OverlayVertex>& pairs, float width, bool depth_test);
  void draw_points(const view::Camera& cam, const std::vector<OverlayVertex>& points, float size_px,
                   bool depth_test);

 private:
  void bind_stream(const view::Camera& cam, const std::vector<OverlayVertex>& v, const Program& prog);
  Program lines_, points_;
  VertexArray vao_;
  Buffer stream_;
};

}  // namespace dfm::gl
