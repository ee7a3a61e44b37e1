#pragma once
// Handle points just outside a closed surface (issue 19: within 1% of the bbox diagonal, always accepted).
// TetGen keeps only the inside, so it drops them; each is glued to the volume by one tet standing on the
// nearest surface facet that faces it.
#include <vector>

#include <Eigen/Core>

#include "core/mesh/mesh.h"

namespace dfm {

// SV, SF: the closed surface (each piece consistently oriented, either way); surface_to_tet: surface
// vertex -> vertex of `mesh` (-1: not in it). X: the points, each within `reach` of the surface. Appends a
// vertex and a positively oriented tet to `mesh` per point that a facet faces (the point more than a tenth
// of its distance above the facet's plane, on the outer side); returns per point its new vertex or -1.
std::vector<int> glue_outside_points(const Eigen::MatrixXd& SV, const Eigen::MatrixXi& SF,
                                     const Eigen::VectorXi& surface_to_tet, const Eigen::MatrixXd& X,
                                     double reach, TetMesh& mesh);

}  // namespace dfm
