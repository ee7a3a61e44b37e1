#pragma once
// The linear monotonicity constraints of Jacobson 2013, 5.3.2-5.3.3: each weight function is kept
// ordered like a representative function u that provably has no interior extrema, along one edge to
// u's lowest and one to u's highest neighbour of every free vertex (Eq. 5.14, the minimal edge set).
//
// u: harmonic with the bind's boundary values (5.15-5.17), on the tet edge graph with positive edge
// weights (the cotangent weights clamped at 0, plus a small uniform part): a Laplacian with negative
// weights can lose the maximum principle (5.5); with positive ones every free vertex of a connected
// volume has a strictly lower and a strictly higher neighbour unless u is constant around it.
#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>

namespace dfm {

// One inequality x[upper] >= x[lower] between nodes of a handle's QP. A node is a free variable
// (0 .. #free-1, the FreeSystem's numbering) or a fixed value: #free + k stands for fixed_values[k].
struct MonotoneConstraint {
  int upper = 0, lower = 0;
};

struct MonotoneProblem {
  std::vector<MonotoneConstraint> constraints;
  std::vector<double> fixed_values;  // distinct values (the handle's boundary values, 0 and 1)
  int free_without_neighbour = 0;    // sides where u had no strictly lower/higher neighbour (the box instead)
};

// The representative functions u (#V x #handles): harmonic with u(b) = bc under the positive-weight
// Laplacian of K (K: cotangent stiffness, fem.h). Throws dfm::Error if a part of the volume has no b.
Eigen::MatrixXd monotone_representatives(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXi& b,
                                         const Eigen::MatrixXd& bc);

// Handle j's constraints from u_j. vertex: free variable -> mesh vertex (FreeSystem::vertex); b, bc as above.
MonotoneProblem monotone_problem(const std::vector<std::vector<int>>& neighbours, const Eigen::VectorXd& u,
                                 const Eigen::VectorXi& vertex, const Eigen::VectorXi& b, const Eigen::VectorXd& bc);

}  // namespace dfm
