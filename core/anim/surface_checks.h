#pragma once
// Measures of a triangle surface used to judge slices: closedness, orientation, enclosed volume.
#include <Eigen/Core>

namespace dfm {

// True when every directed edge (a, b) of F occurs exactly once and its reverse (b, a) exactly once:
// a closed, consistently oriented, edge-manifold surface. mesh_info's is_closed, except that an
// empty F counts as closed here (an empty slice).
bool is_closed_and_oriented(const Eigen::MatrixXi& F);

// True when no directed edge occurs twice and none is degenerate: an oriented, edge-manifold
// surface, possibly with boundary.
bool is_oriented_manifold(const Eigen::MatrixXi& F);

// The directed edges (a, b) of F whose reverse (b, a) is absent: the boundary loops.
Eigen::MatrixXi boundary_edges(const Eigen::MatrixXi& F);

// Flux of the field (x_axis, 0, 0)-style through F: sum over triangles of centroid[axis] times the
// triangle's vector area along `axis`. Equals the enclosed volume of a closed surface, and stays
// exact when F misses only caps perpendicular to another axis (e.g. the open ends of a sweep slice
// at the first and last time).
double flux_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int axis);

// Signed volume enclosed by a closed surface (divergence theorem); positive when wound outward.
// mesh_info's signed_volume, under the name the slice checks use.
double enclosed_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

}  // namespace dfm
