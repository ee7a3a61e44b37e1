#pragma once
// The middle of a transition as a space-time prism stack (issue 30): one tetrahedralization K of the
// middle points, repeated at every middle layer time and joined across each layer interval by the
// staircase split of tet x interval into four 4-simplices (vertices in K's index order, so that
// neighbouring prisms split their shared faces alike). The field there is the blend itself at every
// point (linear in time at a fixed point), so the slice at a layer time is marching tetrahedra on K,
// and K can be a lattice's well-shaped tetrahedra rather than a 4D Delaunay's slivers.
#include <vector>

#include <Eigen/Core>

#include "core/anim/delaunay_4d.h"
#include "core/anim/manifold.h"

namespace dfm {

// The tetrahedra of D lying in a hyperplane that bounds its points: the facets on its hull (no
// neighbour across) whose four corners all lie in [first, last), as indices minus `first`, each sorted
// ascending, the list sorted. For the 4D Delaunay triangulation of points on two parallel hyperplanes
// these are the Delaunay tetrahedra of either layer's points (Southern 2008, Theorem 5.2.1).
MatrixX4iRow hull_facets_in(const Delaunay4& D, int first, int last);

// The staircase 4-simplices of the prisms tet x [layer k, layer k + 1] for k = 0 .. #bases - 2, where
// layer k's copy of point p has index bases[k] + p, for the tetrahedra of K (each sorted ascending)
// that `keep(tet, k)` accepts.
template <class Keep>
MatrixX5iRow extrude_tets(const MatrixX4iRow& K, const std::vector<int>& bases, const Keep& keep) {
  std::vector<Eigen::Matrix<int, 1, 5>> out;
  for (size_t k = 0; k + 1 < bases.size(); ++k)
    for (Eigen::Index t = 0; t < K.rows(); ++t) {
      if (!keep(t, static_cast<int>(k))) continue;
      const int lo = bases[k], hi = bases[k + 1];
      const int a = K(t, 0), b = K(t, 1), c = K(t, 2), d = K(t, 3);
      out.push_back((Eigen::Matrix<int, 1, 5>() << lo + a, lo + b, lo + c, lo + d, hi + d).finished());
      out.push_back((Eigen::Matrix<int, 1, 5>() << lo + a, lo + b, lo + c, hi + c, hi + d).finished());
      out.push_back((Eigen::Matrix<int, 1, 5>() << lo + a, lo + b, hi + b, hi + c, hi + d).finished());
      out.push_back((Eigen::Matrix<int, 1, 5>() << lo + a, hi + a, hi + b, hi + c, hi + d).finished());
    }
  MatrixX5iRow S(static_cast<Eigen::Index>(out.size()), 5);
  for (size_t i = 0; i < out.size(); ++i) S.row(static_cast<Eigen::Index>(i)) = out[i];
  return S;
}

}  // namespace dfm
