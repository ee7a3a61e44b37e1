#pragma once
// Pieces of the bind volume that no handle touches (a separate eyeball, a button, a piece of a kitbashed
// asset): their weights would be undetermined (the case where Blender's bone heat "failed to find a
// solution"). Each moves rigidly with the nearest handled piece instead (issue 19).
#include <Eigen/Core>

#include "core/bind/bind_volume.h"

namespace dfm {

// Finds the unhandled pieces of vol (connected components of its tets), records them in vol.rigid_pieces
// with a note naming them, and constrains their vertices to the row of the nearest constrained vertex so
// the weight solve stays well posed. Needs vol.to_user (for the vertex counts).
void attach_free_pieces(BindVolume& vol);

// After the solve: every tet vertex of a rigid piece takes its anchor's weights (one row per piece).
void apply_rigid_pieces(const BindVolume& vol, Eigen::MatrixXd& tet_weights);

}  // namespace dfm
