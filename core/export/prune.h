#pragma once
// Influence pruning for glTF, which stores a fixed number of joints per vertex (4 per JOINTS_n set).
// Builds on core/skin's top_influences, adding what the format requires of every vertex.
#include <Eigen/Core>

#include "core/skin/influences.h"

namespace dfm {

// The k largest weights per vertex, renormalized to sum to 1, with glTF's rules on top:
//  - negative weights count as 0 (glTF weights are non-negative);
//  - no row is ever all zero: a vertex with no positive weight gets weight 1 on its
//    largest-magnitude handle;
//  - unused slots (weight 0) name handle 0 (the validator warns about a zero weight on another joint).
// Throws dfm::Error for k < 1, no handles, or a non-finite weight.
Influences prune_for_export(const Eigen::MatrixXd& W, int k);

}  // namespace dfm
