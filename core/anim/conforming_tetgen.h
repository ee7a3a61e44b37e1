#pragma once
// A conforming start for a key surface from TetGen's constrained Delaunay tetrahedralization of its
// interior (switch p): TetGen puts Steiner points on the surface's edges until every segment is
// strongly Delaunay, and its boundary is then almost all made of Delaunay faces (bunny.off: 18 of
// 8,174 triangles missing, against 246 after plain midpoint splitting). make_conforming mends the rest.
#include <Eigen/Core>

#include "core/anim/conforming_surface.h"

namespace dfm {

// The boundary of TetGen's tetrahedralization of the closed surface (V, F): the input's vertices
// first (same order), then TetGen's surface Steiner points, triangles oriented as F. `missing` is
// not computed (-1). Throws dfm::Error when TetGen fails or drops an input vertex.
ConformingSurface tetgen_conforming_start(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

}  // namespace dfm
