#pragma once
// A key's signed distance with its creases rounded (issue 30): d is creased on the key's medial
// axis, and so is a blend of two keys' distances, whose zero set then shows notches and knife edges
// (a hole opening through a body's middle) that a lattice cuts as jagged rims. Averaging d over the
// sphere of radius r |d(x)| about x rounds those creases over that radius. The sphere stays on x's
// side of the key (r < 1), so the average has d's sign everywhere and vanishes exactly on the key;
// where d is linear it is d.
#include <Eigen/Core>

#include "core/anim/key_distance.h"

namespace dfm {

// The sphere average by the octahedron rule: the mean of d at x +- r |d(x)| along the x, y and z axes
// (exact for polynomials of degree 3; Lebedev's 14-point rule, exact to degree 5, costs twice the
// queries and measured no closer to its own blend's zero set in test_transition_quality), one
// value per row of P (#P x 3). Lipschitz constant at most 1 + r. With `gradient`, also the
// average's gradient (#P x 3), by the chain rule through the points' dependence on |d(x)|:
//   grad s(x) = 1/6 sum_j [grad d(p_j) + sigma_j r sign(d(x)) (e_j . grad d(p_j)) grad d(x)],
// p_j = x + sigma_j r |d(x)| e_j. Throws dfm::Error unless 0 <= r < 1 and P has 3 columns.
Eigen::VectorXd rounded_distance(const SignedDistance& d, const Eigen::MatrixXd& P, double r,
                                 Eigen::MatrixXd* gradient = nullptr);

}  // namespace dfm
