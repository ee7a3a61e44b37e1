#pragma once
// In-between layers from two keyed meshes of one connectivity (inbetween_method.h says which method does
// what). They sit at the times bake_times gives: `count` evenly spaced inside the interval.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/anim/inbetween_method.h"
#include "core/anim/manifold_sequence.h"

namespace dfm {

// `count` in-between surfaces strictly between a and b (same connectivity; dfm::Error otherwise), at
// a.time + (b.time - a.time) j / (count + 1), j = 1..count, by arap (a closed) or linear; handles: dfm::Error
// (it needs the rig: bake_layers).
std::vector<KeySurface> mesh_inbetweens(const KeySurface& a, const KeySurface& b, int count, InbetweenMethod method);

// The same for a whole sequence: between neighbours of one connectivity whose method (methods[i], for
// keys[i] -> keys[i + 1]) is arap or linear, `count` in-betweens are inserted; other intervals are kept.
std::vector<KeySurface> with_mesh_inbetweens(const std::vector<KeySurface>& keys,
                                             const std::vector<InbetweenMethod>& methods, int count);

}  // namespace dfm
