#pragma once
// Smooth region deformation by the mixed finite elements of Jacobson 2013, ch. 3: a fixed region stays,
// a handle region moves by an affine map, and the free vertices between take the displacement that
// minimizes the Laplacian energy (order 2: biharmonic, C1 at the region boundaries) or the Laplacian
// gradient energy (order 3: triharmonic, C2), 3.3.1-3.3.2.
//
// Discretization (3.4.1, Eq. 3.12; 3.4.2, the reduced form of 3.16): piecewise-linear u, v = Delta u (and
// w = Delta v for order 3) with lumped mass, v and w eliminated, gives for the free vertices Omega
//   Q_{Omega,Omega} d_Omega = -Q_{Omega,known} d_known,  Q = K M^-1 K (order 2) or K M^-1 K M^-1 K (3),
// K the cotangent stiffness (unclamped: the P1 FEM matrix) and M the barycentric lumped mass of the
// rest surface. The region conditions of 3.3.2/3.7 come for free: the constraint Delta u = v is kept on
// every vertex, so the rows of Q reach one (order 2) or two (order 3) rings into the known regions, whose
// values then set the derivatives at the boundary (3.8.2: k rings fix C^{k-1}). Solved for the
// displacement d, not the positions, so the free region keeps its detail (3.5, "Smooth
// detail-preserving deformations"). Barycentric rather than Voronoi lumping: 3.5 finds the rate the same
// and only the constant smaller with Voronoi areas; on the lifted-disk test the two differ by 4e-6 of
// the lift at h = 1/64. The region conditions place the continuous boundary about half a ring inside
// the known regions (test_variational_deform: against an annulus with its edges moved by h/2 the error
// falls like h^2, against the nominal edges like h).
//
// Q depends only on the region choice, so it is factored once (CHOLMOD); a handle move is a sparse
// product and one back substitution (3.5: "the system can be prefactored").
#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>

#include "core/bind/cholesky.h"

namespace dfm {

struct VariationalDeformOptions {
  int order = 2;  // 2: biharmonic (Laplacian energy, C1); 3: triharmonic (Laplacian gradient energy, C2)
};

// A handle's affine map in row-vector form: p' = p * T.topRows(3) + T.row(3).
using HandleTransform = Eigen::Matrix<double, 4, 3>;
HandleTransform handle_translation(const Eigen::RowVector3d& d);

class VariationalDeform {
 public:
  // V, F: the rest surface. fixed, handle: vertex indices (duplicates allowed); the free region is the
  // rest. Throws dfm::Error for an index out of range, a vertex in both sets, an empty handle or free
  // region, free vertices with no path through the mesh to a fixed or handle vertex (a part of the
  // surface nothing holds), or an order other than 2 or 3.
  VariationalDeform(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<int>& fixed,
                    const std::vector<int>& handle, const VariationalDeformOptions& opts = {});

  // The deformed positions (#V x 3): fixed vertices are V's rows unchanged (bit for bit), handle vertices
  // are exactly p * T, free vertices are V plus the solved displacement.
  Eigen::MatrixXd solve(const HandleTransform& T) const;

  const std::vector<int>& free_vertices() const { return free_; }
  const std::vector<int>& handle_vertices() const { return handle_; }
  double factor_seconds() const { return factor_seconds_; }

 private:
  Eigen::MatrixXd V_;
  std::vector<int> free_, handle_;
  Eigen::SparseMatrix<double> Q_free_handle_;  // Q_{Omega, handle}
  SpdSolver solver_;                           // Q_{Omega, Omega}
  double factor_seconds_ = 0;
};

}  // namespace dfm
