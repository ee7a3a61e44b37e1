#pragma once
// Generalized winding number of a triangle soup (Jacobson et al. 2013): the sum of the signed solid
// angles its triangles subtend at a query point, divided by 4 pi. 1 inside / 0 outside a closed,
// outward-oriented surface, -1 inside a flipped one, and a smooth, meaningful value for open, non-manifold
// or self-intersecting surfaces (about 0.5 across a hole).
#include <Eigen/Core>

namespace dfm {

// Signed solid angle of triangle (a, b, c) seen from p (Van Oosterom & Strackee 1983), in [-2pi, 2pi].
double solid_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& p);

// Direct O(#F) evaluation at one point.
double winding_number(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::Vector3d& p);

// Direct evaluation at every row of P (#P x 3). threads <= 0 uses every core.
Eigen::VectorXd winding_numbers_direct(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                       const Eigen::MatrixXd& P, int threads = 0);

}  // namespace dfm
