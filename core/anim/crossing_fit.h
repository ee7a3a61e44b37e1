#pragma once
// Values for a piecewise linear field whose zero set passes where the field's own does (issue 30).
// Marching a lattice interpolates the field linearly along each edge, so where the zero set curves
// within a spacing (a thin part shrinking away) the crossings miss it by a fraction of a spacing.
// Moving the crossings themselves onto the field (Hermite roots along the edges) puts the vertices
// of one simplex off a common hyperplane, and the slices' small triangles then take noisy normals
// (bench_transition_quality); refitting the values instead keeps each simplex's piece flat.
#include <array>
#include <vector>

#include <Eigen/Core>

#include "core/anim/manifold.h"

namespace dfm {

// The root in (0, 1) of the cubic with values fa < 0 < fb and derivatives da, db at 0 and 1 (along
// the edge, per its whole length), the derivatives first limited to [0, 3 (fb - fa)] so that it
// rises monotonically (Fritsch and Carlson 1980) and has exactly one root.
double hermite_root(double fa, double fb, double da, double db);

// The edges of tetrahedra T, each once as (a < b), sorted.
std::vector<std::array<int, 2>> tet_edges(const MatrixX4iRow& T);

// f refitted at the points X: for each edge whose ends' values differ in sign, r its Hermite root
// (f and the gradient G, #X x 3); each end's value moves half way to the value that alone would put
// the linear crossing at r, (1 - r) f_a + r f_b = 0, averaged over its crossing edges with weights
// (1 - r)^2 at a and r^2 at b (the least-squares fit with the other end held). For an edge alone both
// halves together put the crossing exactly at r. Signs are kept; points on no crossing edge keep f.
// Throws dfm::Error when the sizes disagree or an index is out of range.
Eigen::VectorXd fit_crossings(const Eigen::MatrixXd& X, const std::vector<std::array<int, 2>>& edges,
                              const Eigen::VectorXd& f, const Eigen::MatrixXd& G);

}  // namespace dfm
