#pragma once
// Laplacians on a triangle surface, for the weight tools (weight_limit.h, weight_smooth.h): weights
// live on the surface vertices, while fem.h's operators act on the bind's tets.
//
// Sign convention as in fem.h: the stiffness K is POSITIVE semi-definite, w^T K w is the Dirichlet
// energy, off-diagonals are -c_ij <= 0 and rows sum to 0.
#include <Eigen/Core>
#include <Eigen/Sparse>

namespace dfm {

// Cotangent stiffness (Jacobson 2013, 2.1.2): c_ij = (cot a_ij + cot b_ij) / 2 over the angles opposite
// edge ij. Each edge's c_ij is clamped at 0, so K is an M-matrix and solves with it obey the maximum
// principle (weights stay in [0, 1]; on an obtuse mesh the plain cotangent weights can break that);
// on a mesh without obtuse angles the clamp changes nothing. clamp_negative = false keeps the plain
// cotangent weights, the P1 finite-element stiffness the mixed discretizations of ch. 3 need (a clamped
// K is no longer the FEM Laplacian, so the bi- and triharmonic solves would not converge to the smooth
// solution). Degenerate (zero-area) triangles add nothing. Throws dfm::Error for an index out of range.
Eigen::SparseMatrix<double> surface_cotangent_stiffness(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                                        bool clamp_negative = true);

// Graph Laplacian with weight 1 per mesh edge (what Blender's weight smoothing averages over).
Eigen::SparseMatrix<double> uniform_stiffness(int num_vertices, const Eigen::MatrixXi& F);

// Lumped mass: a third of each incident triangle's area per vertex (Jacobson 2013, 2.1.3). #V.
Eigen::VectorXd surface_lumped_mass(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

}  // namespace dfm
