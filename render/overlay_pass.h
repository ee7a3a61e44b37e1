#pragma once
// Overlays drawn over the surface: ground grid, handles (round point sprites), bones and cage
// wireframes (wide anti-aliased lines), the paint brush circle. Geometry is built on the CPU each
// frame (a few thousand vertices at most) and streamed.
#include <vector>

#include <Eigen/Core>

#include "render/camera.h"
#include "render/gl_buffer.h"
#include "render/gl_program.h"

namespace dfm::gl {

struct OverlayVertex {
  float position[3];
  float color[4];
};

inline OverlayVertex overlay_vertex(const Eigen::Vector3d& p, const Eigen::Vector4f& c) {
  return {{float(p.x()), float(p.y()), float(p.z())}, {c[0], c[1], c[2], c[3]}};
}

// Line-list builders (pairs of vertices), pure CPU so they are testable.
// A square grid in the plane y = height centred on (cx, cz), lines every `spacing`, fading out to the
// edge; every 5th line brighter; the x and z axes through the origin tinted red and blue.
std::vector<OverlayVertex> grid_lines(double cx, double cz, double height, double half_extent,
                                      double spacing);
// A circle of `segments` lines around `center` in the plane with normal `normal`.
std::vector<OverlayVertex> circle_lines(const Eigen::Vector3d& center, const Eigen::Vector3d& normal,
                                        double radius, const Eigen::Vector4f& color, int segments = 48);
// A "nice" grid spacing (1, 2 or 5 times a power of ten) giving about `lines` lines over `extent`.
double nice_spacing(double extent, int lines);

class OverlayPass {
 public:
  OverlayPass();
  // Pairs of vertices; width in pixels. depth_test=false draws on top of the surface (x-ray).
  void draw_lines(const Camera& cam, const std::vector<OverlayVertex>& pairs, float width, bool depth_test);
  void draw_points(const Camera& cam, const std::vector<OverlayVertex>& points, float size_px,
                   bool depth_test);

 private:
  void bind_stream(const Camera& cam, const std::vector<OverlayVertex>& v, const Program& prog);
  Program lines_, points_;
  VertexArray vao_;
  Buffer stream_;
};

}  // namespace dfm::gl
