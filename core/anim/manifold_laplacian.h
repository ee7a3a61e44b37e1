#pragma once
// The differential coordinates of an animation manifold's vertices (Southern 2008, 4.2, Eq. 4.1):
//   delta_i = v_i - sum_j w_ij v_j,   sum_j w_ij = 1,  w_ij > 0,
// over the 1-ring N_i (vertices sharing a tetrahedron edge with i), in 4D (x, y, z, t).
//
// Weights: reciprocal 4D edge lengths, normalised, w_ij ~ 1 / |v_i - v_j| -- the closed-form solution of
// Eq. 4.2 without its quadratic term (4.2.2: "quickly solved by setting w_j = 1/||v_i - v_j||"). 4.6.1:
// cotangent weights do not exist for tetrahedra in R^4, and 4.3: equal weights distort on irregular
// tetrahedral grids (Fig. 4.6) because a prism manifold's time edges and space edges differ in length.
// These weights need no one-ring on both sides of an edge, so they hold across the manifold's open
// boundary at its first and last layer unchanged (the primal boundary condition of 4.4.1 asks only for
// positive weights summing to 1 there; 4.4.1's quadratic program minimises |delta| further, which the
// reciprocal weights approximate without a QP per vertex).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/anim/manifold.h"

namespace dfm {

// 4.6.1's weighting schemes for R^4 (cotangent weights do not exist there):
//   Equal           w_ij = 1 / |N_i| (Taubin 1995; distorts on irregular tetrahedra, 4.3 / Fig. 4.6),
//   Reciprocal      w_ij ~ 1 / |v_i - v_j| (the default, above),
//   PrimalBoundary  Reciprocal inside, and at vertices on the manifold's open boundary (a face of their
//                   star lies in one tetrahedron only) the least-|delta| weights of Eq. 4.3 (4.4.1;
//                   core/anim/primal_boundary_weights.h).
//   Dual            the dual graph Laplacian of Au et al. 2006 with 4.4.2's ghost boundary condition: rows
//                   per tetrahedron, not per vertex (core/anim/dual_laplacian.h); manifold_laplacian_rows
//                   does not build it (dfm::Error), ManifoldEditor does.
enum class LaplacianWeights { Equal, Reciprocal, PrimalBoundary, Dual };

// "equal", "reciprocal", "primal-boundary", "dual"; dfm::Error otherwise.
LaplacianWeights parse_laplacian_weights(const std::string& name);
const char* laplacian_weights_name(LaplacianWeights w);  // parse_laplacian_weights' inverse

struct LaplacianRow {
  std::vector<int> neighbours;   // sorted manifold vertex indices
  std::vector<double> weights;   // w_ij, summing to 1
};

// One row per vertex in `rows` (any order; the rows' order). Edge lengths are measured with t multiplied
// by time_scale (t is in seconds, x, y, z in model units; larger values weaken the time edges, so each
// frame keeps its shape more and the time edges mostly carry the motion). Throws dfm::Error for a vertex
// without neighbours, a zero-length edge or a time_scale that is not positive and finite.
std::vector<LaplacianRow> manifold_laplacian_rows(const AnimationManifold& m, const std::vector<int>& rows,
                                                  LaplacianWeights weights = LaplacianWeights::Reciprocal,
                                                  double time_scale = 1.0);

// Per row: whether the vertex lies on the manifold's boundary (a triangle of its star belongs to exactly
// one tetrahedron).
std::vector<char> manifold_boundary_rows(const AnimationManifold& m, const std::vector<int>& rows);

// delta_i of Eq. 4.1 for each row (#rows x 4).
Eigen::MatrixXd differential_coordinates(const AnimationManifold& m, const std::vector<int>& rows,
                                         const std::vector<LaplacianRow>& L);

}  // namespace dfm
