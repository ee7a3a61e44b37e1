#pragma once
// Where a level set meets a key's time it can fold back along the key's hyperplane: tetrahedra that
// lie flat in it (a key's all-surface tetrahedra, "lids") and triangles in it held by two
// tetrahedra (a fold along a chord). Both are interior to the 3-manifold, but a slice at exactly
// that time would show them, so the manifold's own boundary there (the key's surface) would not be
// what a slice returns. Each connected cluster of such tetrahedra is replaced by the cone over its
// boundary from one new point just inside the slab: the same boundary, nothing left in the plane.
#include "core/anim/manifold.h"

namespace dfm {

// V, T: an oriented 3-manifold (manifold.h's convention); time: the key's time; inside: the time
// of the cone points (just after time for a first key, just before for a last one). Returns the
// number of clusters replaced.
int seal_key_time(MatrixX4dRow& V, MatrixX4iRow& T, double time, double inside);

}  // namespace dfm
