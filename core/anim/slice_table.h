#pragma once
// The marching-tetrahedra case table for slicing a tetrahedron by a level set of a linear function
// f (f >= c "above", else "below"), derived in code (slice_table.cpp), not copied from a paper.
//
// Case index: bit i set when vertex i is above. Edges are the 6 vertex pairs kEdges. Each case gives
// 0, 1 or 2 triangles of edge indices. Winding: in the tetrahedron's own orientation, the triangle's
// normal points from "below" to "above" (towards increasing f).
//
// For a tetrahedron of an animation manifold (oriented as in manifold.h) sliced on axis k and drawn
// in the remaining coordinates in order, this winding faces outward when k is y or t and inward when
// k is x or z (a sign (-1)^k with x=1 .. t=4); slice_flips_winding() says which. See slice.cpp.
#include <array>

namespace dfm {

struct SliceCase {
  int num_triangles = 0;
  std::array<std::array<int, 3>, 2> triangles{};  // edge indices into kSliceEdges
};

inline constexpr std::array<std::array<int, 2>, 6> kSliceEdges = {
    {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};

// The 16 cases, computed once on first use.
const std::array<SliceCase, 16>& slice_table();

// Axis 0..3 = x, y, z, t. True for x and z: their outward winding is the table's reversed.
inline bool slice_flips_winding(int axis) { return axis == 0 || axis == 2; }

}  // namespace dfm
