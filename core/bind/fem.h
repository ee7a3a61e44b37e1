#pragma once
// Linear FEM on tetrahedra: stiffness, lumped mass, per-tet gradients.
//
// Sign convention: K is the POSITIVE semi-definite stiffness, w^T K w = integral of |grad w|^2.
// Per tet, the entry for edge ij is K_ij = -(l_kl / 6) cot(theta_kl), with kl the opposite edge and
// theta_kl the dihedral angle at kl; K_ii = -sum_{j != i} K_ij (rows sum to 0). This is minus libigl's
// cotmatrix (which is negative semi-definite with positive off-diagonals).
#include <Eigen/Core>
#include <Eigen/Sparse>

namespace dfm {

// Signed volume of each tet (positive for positively oriented tets). #T.
Eigen::VectorXd tet_volumes(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T);

// Cotangent stiffness K (#V x #V), convention above. Throws dfm::Error on a degenerate or inverted tet.
Eigen::SparseMatrix<double> cotangent_stiffness(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T);

// Lumped mass: a quarter of each incident tet's volume per vertex (#V). Sums to the total volume.
Eigen::VectorXd lumped_mass(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T);

// Piecewise-constant gradient operator G (3#T x #V): rows 3t..3t+2 hold grad of a P1 function on tet t.
// For any per-tet weights a (#T), G^T diag(kron(a .* vol, 1_3)) G with a = 1 equals K.
Eigen::SparseMatrix<double> tet_gradient(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T);

// The shape-preservation (Eq. 4.7) term G^T (R D) G for a per-tet mask rho (#T), D = tet volumes.
Eigen::SparseMatrix<double> masked_stiffness(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                                             const Eigen::VectorXd& rho);

}  // namespace dfm
