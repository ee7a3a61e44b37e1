#pragma once
// Which surface vertices the bind fixed (Jacobson 2013, Eq. 4.3-4.4: w_j = delta_jk on handle H_k,
// linear on cage facets), so the weight tools can leave their values alone.
//
// The bind constrains the tet vertices that coincide with a handle; a surface vertex is one of them
// when it lies on a handle: at a point handle or cage vertex, on a bone segment, in a region, or on a
// cage facet or edge (the same rules as build_bind_volume / bind_volume_from_tets, with
// handle_geometry.h's helpers). Few surface vertices are constrained in practice (handles usually lie
// inside the shape); regions are the common case.
#include <vector>

#include <Eigen/Core>

#include "core/rig/rig.h"

namespace dfm {

struct WeightConstraints {
  Eigen::VectorXi b;   // constrained surface vertices, sorted
  Eigen::MatrixXd bc;  // #b x #handles: the values the bind imposed there (rows sum to 1)
  // #V flags: true where the vertex is constrained.
  std::vector<bool> mask(int num_vertices) const;
};

// rel_tol: how close (times the bounding-box diagonal of the surface and cages) a vertex must be to a
// handle. 1e-5 is the tet-mesh bind's tolerance, the looser of the two binds' (a vertex kept that the
// bind left free costs nothing; a constrained one changed would break Eq. 4.3). Throws dfm::Error for
// a region vertex out of range.
WeightConstraints surface_weight_constraints(const Eigen::MatrixXd& V, const Rig& rig, double rel_tol = 1e-5);

}  // namespace dfm
