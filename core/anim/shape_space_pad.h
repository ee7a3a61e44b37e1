#pragma once
// The shape-space pad: each base of a shape space (core/anim/shape_space.h, Alexa 2002 ch. 5) is a
// point on a 2D pad, and a cursor on the pad gives the coordinates to synthesize. The weights are the
// cursor's barycentric coordinates in the Delaunay triangulation of the points (CGAL): piecewise
// linear, >= 0, summing to 1, at most three nonzero, and e_i at base i's own point. Outside the convex
// hull the cursor is clamped to the nearest hull point; with collinear points, to the nearest point
// of the segments between neighbours. Points at one place: the first of them gets the weight.
#include <array>
#include <vector>

#include <Eigen/Core>

namespace dfm {

using PadPoints = Eigen::Matrix<double, Eigen::Dynamic, 2>;

// points: n >= 2 rows, finite; cursor finite. Throws dfm::Error. Returns n weights.
Eigen::VectorXd pad_weights(const PadPoints& points, const Eigen::Vector2d& cursor);

// The Delaunay triangles (point indices, counter-clockwise), for drawing; empty when the points are
// collinear. Points at one place appear once (the first of them).
std::vector<std::array<int, 3>> pad_triangles(const PadPoints& points);

// Where coordinates x sit on the pad: sum x_i p_i.
Eigen::Vector2d pad_position(const PadPoints& points, const Eigen::VectorXd& x);

}  // namespace dfm
