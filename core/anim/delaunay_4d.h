#pragma once
// The Delaunay triangulation of a point set in R^4 (CGAL's dD triangulation, Epick_d).
#include <Eigen/Core>

namespace dfm {

using MatrixX5iRow = Eigen::Matrix<int, Eigen::Dynamic, 5, Eigen::RowMajor>;

struct Delaunay4 {
  MatrixX5iRow simplices;  // #S x 5 point indices of the finite 4-simplices
  // #S x 5: the simplex across the facet opposite corner i, -1 outside the convex hull.
  MatrixX5iRow neighbors;
};

// points: #P x 4, distinct, spanning R^4. Throws dfm::Error otherwise.
Delaunay4 delaunay_4d(const Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>& points);

// Sign of det[p1 - p0, p2 - p0, p3 - p0, p4 - p0] (exact): +1, 0 or -1. The rows of P are p0..p4.
int orientation_4d(const Eigen::Matrix<double, 5, 4, Eigen::RowMajor>& P);

}  // namespace dfm
