#pragma once
// Retiming part of an animation manifold (issue 35: "a retime option lets the handle move in t as
// well"), and what keeps it a manifold the slicer can cut.
//
// On a prism slab every tetrahedron's vertical edge (layer vertex v to its copy in the next layer) has a
// tetrahedron edge along it, and t is linear on each tetrahedron; while every such time edge still rises
// (t(upper) > t(lower)), t rises along every vertical line of every prism, so each t-slice crosses it
// once and stays a closed surface of the layer mesh's shape. A time edge that stops rising folds the
// slab back in time (a slice would cut it twice): check_time_edges refuses it.
//
// Moved layer vertices leave their layer time, so the slabs around them no longer span [times[i],
// times[i + 1]] as validate_manifold and the slicer's slab ranges need: merge_retimed_slabs joins them.
#include <array>
#include <vector>

#include "core/anim/manifold.h"

namespace dfm {

// The (lower, upper) time edges of prism slabs at `vertices`. Throws dfm::Error when a vertex lies in a
// slab not made by the prism build (a transition), or on the animation's first or last layer (whose
// times bound the animation: moving them would open a hole in the first or last slice).
std::vector<std::array<int, 2>> prism_time_edges(const AnimationManifold& m, const std::vector<int>& vertices);

// Throws dfm::Error naming the first time edge whose upper vertex is not strictly later than its lower.
void check_time_edges(const MatrixX4dRow& V, const std::vector<std::array<int, 2>>& edges);

// After vertices' t changed (time edges rising, nothing moved before the first layer or past the
// last): slabs whose tetrahedra leave their time span merge with their neighbours (the layer time
// between them is dropped), a prism slab with a layer vertex off its layer time becomes a plain slab
// (faces = -1), and key layers off their time are dropped. Then validate_manifold; dfm::Error if not.
void merge_retimed_slabs(AnimationManifold& m);

}  // namespace dfm
