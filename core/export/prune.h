#pragma once
// Influence pruning for glTF, which stores a fixed number of joints per vertex (4 per JOINTS_n set).
// Builds on core/skin's top_influences, adding what the format requires of every vertex.
#include <vector>

#include <Eigen/Core>

#include "core/rig/pose.h"
#include "core/skin/influences.h"

namespace dfm {

// The k largest weights per vertex, renormalized to sum to 1, with glTF's rules on top:
//  - negative weights count as 0 (glTF weights are non-negative);
//  - no row is ever all zero: a vertex with no positive weight gets weight 1 on its
//    largest-magnitude handle;
//  - unused slots (weight 0) name handle 0 (the validator warns about a zero weight on another joint).
// Throws dfm::Error for k < 1, no handles, or a non-finite weight.
Influences prune_for_export(const Eigen::MatrixXd& W, int k);

// Re-solves the kept weights of every vertex that lost weight in pruning so the pruned skin matches
// LBS with all weights W over `poses` in the least-squares sense (the kept handles stay; weights stay
// >= 0 and sum to 1; a tiny pull towards the renormalized weights keeps rank-deficient cases stable).
// Dropped weight whose handles move like the kept ones is thereby redistributed instead of lost.
// Returns how many vertices were refit. V: #V x 3 rest positions.
int refit_influences(Influences& inf, const Eigen::MatrixXd& V, const Eigen::MatrixXd& W,
                     const std::vector<Pose>& poses);

}  // namespace dfm
