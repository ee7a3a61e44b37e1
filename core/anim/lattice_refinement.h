#pragma once
// Where a transition's middle lattice is too coarse for the blend (issue 30). A part thinner than a
// lattice spacing (a bunny's ear shrinking away into another key) curves the blend's zero set
// within one cell: the lattice's simplices cut it by chords, and a slice between two layers, which
// joins crossings of both, misses it by up to a third of a spacing (1% of the bounding diagonal in
// test_transition_quality) even where every crossing lies on the field. Near edges along which the
// field bulges away from its chord, the coarse lattice is refined by the body-centred cubic lattice
// of half its cube edge, which holds every coarse point, so the Delaunay tetrahedra stay the two
// lattices' own away from the seam between them. (Southern 2008 inserts points into a manifold by
// barycentric splits, ch. 6, adaptively in 4.5, and notes that they do not make fair, regular
// meshes; splitting the bulging lattice edges at their midpoints likewise raised the slices'
// normals by about 5 degrees at the 99th percentile, which the nested lattice does not.)
#include <array>
#include <vector>

#include <Eigen/Core>

namespace dfm {

// The midpoints of `edges` (point pairs of X) along which the blend F(., u) = (1 - u) d_s + u d_t,
// at one of the times u, bulges away from its chord by more than tolerance * a in distance: the
// cubic Hermite of the ends' values and gradients (F's gradient likewise from g_s, g_t, #X x 3)
// against the linear, divided by |grad F|. Only edges within one edge length of F's zero set (by
// the ends' values and gradients) count. Throws dfm::Error when the sizes disagree or an index is out
// of range.
Eigen::MatrixXd bulging_edge_midpoints(const Eigen::MatrixXd& X, const std::vector<std::array<int, 2>>& edges,
                                       const Eigen::VectorXd& d_s, const Eigen::VectorXd& d_t, const Eigen::MatrixXd& g_s,
                                       const Eigen::MatrixXd& g_t, const std::vector<double>& u, double a,
                                       double tolerance);

// The points of the body-centred cubic lattice with origin lo and cube edge a / 2 (corners at even
// multiples of a / 4 from lo in every coordinate, centres at odd ones) within `reach` of a row of
// `centres`, less those of the lattice of cube edge a (coordinates all 0 or all 2 modulo 4, in
// quarters of a), each once.
Eigen::MatrixXd finer_lattice_points(const Eigen::RowVector3d& lo, double a, const Eigen::MatrixXd& centres,
                                     double reach);

}  // namespace dfm
