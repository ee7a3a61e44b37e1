#pragma once
// The 4D Delaunay triangulation of two point sets on parallel hyperplanes (a transition's key and its
// nearest middle layer, transition.h), from each set's 3D Delaunay tetrahedralization.
//
// A 4-sphere centred at (c, tau) cuts either hyperplane in a sphere centred at c, and some tau makes
// both cut spheres pass through their layer's points nearest to c. So the 4D Delaunay simplices are
// dual to the vertices of the overlay of the two layers' Voronoi diagrams, whatever the separation
// (Boissonnat 1988 for planar sections; Southern 2008, 5.2):
// - (4,1): a Delaunay tetrahedron of one layer and the other layer's point nearest to its
//   circumcentre;
// - (3,2): a Delaunay triangle of one layer and a Delaunay edge of the other whose Voronoi facet the
//   triangle's Voronoi edge crosses (the segment between its tetrahedra's circumcentres, or the ray
//   out of the hull).
// Each decision compares two distances: certified in interval arithmetic, else made in exact
// rationals. An exact tie (six points on a 4-sphere, where the triangulation is not unique) returns
// no triangulation: delaunay_4d breaks ties by symbolic perturbation.
#include <optional>

#include <Eigen/Core>

#include "core/anim/delaunay_3d.h"
#include "core/anim/delaunay_4d.h"

namespace dfm {

// One layer: its points (#P x 3) and their Delaunay tetrahedralization (as Tetrahedralization's).
struct DelaunayLayer {
  const Eigen::MatrixXd& points;
  const Eigen::MatrixXi &tets, &neighbours;
};

// The 4-simplices of the Delaunay triangulation of a's points at one time and b's at another: a's
// points numbered first, then b's; corners in no particular order. None on an exact tie.
std::optional<MatrixX5iRow> layer_pair_delaunay(const DelaunayLayer& a, const DelaunayLayer& b);

}  // namespace dfm
