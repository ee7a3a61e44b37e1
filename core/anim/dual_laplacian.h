#pragma once
// The dual graph Laplacian of Au et al. 2006 on an animation manifold (Southern 2008, 4.2.1), with the
// dual boundary condition of 4.4.2.
//
// The dual mesh has a vertex at each tetrahedron's centroid c_i (D: c_i = sum of its 4 vertices / 4). A
// tetrahedron has 4 face neighbours, whose centroids span a 3D hyperplane of R^4; the dual differential
// coordinate is c_i minus its projection onto that hyperplane,
//   delta'_i = c_i - sum_j w_ij c_j,   w_ij the projection's affine (barycentric) weights, sum 1,
// so delta'_i has no tangential part and there is no choice of weights ("exactly n vertices in the dual
// facet, so there is no ambiguity"). The rows of L = L' D act on the primal vertices.
//
// 4.4.2: a face on the manifold's open boundary (its first and last layers) has no neighbour across it.
// The ghost of the tetrahedron, turned by pi about the face (its opposite vertex v_l reflected through
// the face's centroid c_f: v_l -> 2 c_f - v_l), stands in for it; its centroid is
//   ghost = (n + 1) / (n (n - 1)) sum_k v_k - v_l / n   over the face's n - 1 = 3 vertices v_k,
// i.e. 5/12 (v_a + v_b + v_c) - 1/4 v_l for tetrahedra. (Southern writes 2/n for the face's weights,
// derived on a triangle, where n = 3 makes the two agree; 2/n sums to 5/4, not 1, for n = 4.)
#include <vector>

#include <Eigen/Core>

#include "core/anim/manifold.h"

namespace dfm {

// A row of L' D over manifold vertices: sum_k coeffs[k] V(vertices[k]) is delta'_i.
struct DualLaplacianRow {
  int tet = -1;
  std::vector<int> vertices;     // sorted, unique
  std::vector<double> coeffs;    // summing to 0 (translations are in the kernel)
  int ghosts = 0;                // boundary faces replaced by ghosts (4.4.2)
};

// One row per tetrahedron in `tets`. The projection weights are measured with t multiplied by time_scale
// (as manifold_laplacian.h's edge lengths). Throws dfm::Error for a time_scale that is not positive and
// finite, a tetrahedron index out of range, or a face shared by more than two tetrahedra.
std::vector<DualLaplacianRow> dual_laplacian_rows(const AnimationManifold& m, const std::vector<int>& tets,
                                                  double time_scale = 1.0);

// The ghost dual vertex of 4.4.2: face (3 x 4 rows) on the boundary, opposite: the tetrahedron's fourth
// vertex.
Eigen::RowVector4d ghost_dual_vertex(const Eigen::Matrix<double, 3, 4>& face, const Eigen::RowVector4d& opposite);

// Affine weights w (sum 1) of the point of aff(P) nearest c (P: k x 4, k >= 1). A degenerate P (its
// points affinely dependent) gets the least-norm weights of that point (a complete orthogonal
// decomposition's pseudo-inverse).
Eigen::VectorXd affine_projection_weights(const Eigen::RowVector4d& c, const Eigen::MatrixXd& P);

}  // namespace dfm
