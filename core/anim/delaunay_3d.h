#pragma once
// The Delaunay tetrahedralization of a point set in R^3 (CGAL, exact predicates, ties broken by
// symbolic perturbation), as plain arrays.
#include <Eigen/Core>

namespace dfm {

// A point set's Delaunay tetrahedralization: tets (#T x 4 point indices), neighbours(t, i) the tet
// across the face opposite corner i, -1 on the hull.
struct Tetrahedralization {
  Eigen::MatrixXi tets, neighbours;
};

// CGAL's (exact predicates, ties broken by symbolic perturbation). points: #P x 3, distinct, not
// coplanar; throws dfm::Error otherwise.
Tetrahedralization delaunay_3d(const Eigen::MatrixXd& points);

}  // namespace dfm
