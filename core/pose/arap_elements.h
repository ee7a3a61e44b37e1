#pragma once
// The elements of the as-rigid-as-possible energies FAST minimizes (Jacobson 2013, Eq. 7.4, Fig. 7.5):
// triangles of the surface ("spokes and rims", Chao et al. 2010) or tets of the bind's volume. Each
// element's edges carry cotangent coefficients c_ij; the element matrix Le holds them as a Laplacian
// (Le_ij = -c_ij off the diagonal, rows sum to 0), so for any X, Z on the element's vertices
//   sum_{i<j} c_ij (x_i - x_j).(z_i - z_j) = sum_ij Le_ij x_i.z_j.
// On a triangle c_ij = cot(opposite angle) / 2; on a tet c_ij = (l_kl / 6) cot(theta_kl) (kl the opposite
// edge, theta_kl its dihedral angle). Both are measure * grad(phi_i).grad(phi_j) with the sign flipped.
#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>

namespace dfm {

// Element matrices of every row of `elements` (#E x 3 triangles or #E x 4 tets), each (k x k) stored
// column-major in one column of the result (k*k x #E). Throws dfm::Error naming the first degenerate
// element (zero area or volume) or an index out of range.
Eigen::MatrixXd arap_element_matrices(const Eigen::MatrixXd& V, const Eigen::MatrixXi& elements);

// L = sum over elements of (corners per element) * Le: every element belongs to the edge set of each
// of its corners (spokes and rims; the tet analogue), so E_2 of Eq. 7.6 is tr(V'^T L V'). #V x #V.
Eigen::SparseMatrix<double> arap_laplacian(int num_vertices, const Eigen::MatrixXi& elements,
                                           const Eigen::MatrixXd& element_matrices);

}  // namespace dfm
