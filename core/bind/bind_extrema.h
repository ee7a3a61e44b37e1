#pragma once
// A bind's spurious local extrema (local_extrema.h), on the tet edge graph the weights were solved on
// and on the user's surface.
#include <Eigen/Core>

#include "core/bind/bind.h"
#include "core/bind/local_extrema.h"

namespace dfm {

struct BindExtrema {
  LocalExtrema tet;      // tet_weights on the tets' edges; handle vertices: volume.b
  LocalExtrema surface;  // weights on F's edges; handle vertices: those that are (or sit on) a tet vertex of b
};

// F: the user's triangles (a surface input's faces; for a tet-mesh input, tet_boundary_faces of its tets).
BindExtrema bind_local_extrema(const BindResult& res, const Eigen::MatrixXi& F);

}  // namespace dfm
