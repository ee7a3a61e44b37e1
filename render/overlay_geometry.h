#pragma once
// Overlay geometry built on the CPU (no GL, so it is testable alone and the viewport's logic builds
// without a context): the vertex the overlay pass streams, and line-list builders for the ground grid
// and circles (brush, gizmo rings). render/overlay_pass.h draws them.
#include <vector>

#include <Eigen/Core>

namespace dfm::gl {

struct OverlayVertex {
  float position[3];
  float color[4];
};

inline OverlayVertex overlay_vertex(const Eigen::Vector3d& p, const Eigen::Vector4f& c) {
  return {{float(p.x()), float(p.y()), float(p.z())}, {c[0], c[1], c[2], c[3]}};
}

// Line-list builders (pairs of vertices).
// A square grid in the plane y = height centred on (cx, cz), lines every `spacing`, fading out to the
// edge; every 5th line brighter; the x and z axes through the origin tinted red and blue.
std::vector<OverlayVertex> grid_lines(double cx, double cz, double height, double half_extent,
                                      double spacing);
// A circle of `segments` lines around `center` in the plane with normal `normal`.
std::vector<OverlayVertex> circle_lines(const Eigen::Vector3d& center, const Eigen::Vector3d& normal,
                                        double radius, const Eigen::Vector4f& color, int segments = 48);
// A "nice" grid spacing (1, 2 or 5 times a power of ten) giving about `lines` lines over `extent`.
double nice_spacing(double extent, int lines);

}  // namespace dfm::gl
