#pragma once
// CPU slicer: the intersection of an animation manifold with the hyperplane {axis = value}.
// Axis 3 (t) gives the animated surface at a time; axes 0..2 (x, y, z) give the "sweep through time"
// view (Southern 2008, Fig. 2.7) drawn in the remaining coordinates, e.g. (y, z, t) for x.
//
// Rules:
// - A vertex with coordinate >= value is "above" (on the hyperplane counts as above), except when
//   value is at or below the manifold's lowest coordinate on that axis, where on-plane vertices count
//   as below. So the slice at any layer time is exactly that layer's mesh (same positions, bit for
//   bit, same vertex order when the layer is a keyframe; faces may be cyclically rotated), including
//   the first and last layer.
// - Edge points interpolate linearly from the above endpoint: p = pa + sa / (sa - sb) (pb - pa),
//   s = coordinate - value; a point on a vertex is that vertex exactly.
// - Vertices are welded by the manifold edge (or vertex) they lie on; triangles collapsed by the weld
//   are dropped. Triangles face outward of the space-time solid (outward surfaces for t).
// - Normals are smooth (Southern 2008, 2.3; core/anim/manifold_normals.h): each endpoint's 4D vertex
//   normal loses the axis and is renormalised, then n = normalize(na + mu (nb - na)) with the same
//   endpoint and mu as the position; a point on a vertex takes that vertex's normal.
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "core/anim/manifold.h"
#include "core/mesh/mesh.h"

namespace dfm {

enum class SliceAxis : int { X = 0, Y = 1, Z = 2, T = 3 };

// "t", "x", "y", "z" (any case); dfm::Error otherwise.
SliceAxis parse_slice_axis(const std::string& name);
const char* slice_axis_name(SliceAxis axis);

struct ManifoldSlice {
  TriMesh mesh;  // V, F and unit vertex normals N, in the coordinates left after dropping the axis
  // Per slice vertex: the manifold vertices (a, b), a <= b, of the edge it lies on; a == b when it is
  // that manifold vertex itself.
  std::vector<std::array<int, 2>> edges;
};

// vertex_normals4: #V x 4 unit normals from manifold_vertex_normals(m), to reuse them across slices;
// when null, only the normals the slice needs are computed (for t, from the neighbouring slabs).
ManifoldSlice slice_manifold(const AnimationManifold& m, SliceAxis axis, double value,
                             const Eigen::MatrixXd* vertex_normals4 = nullptr);

// The tetrahedra a slice has to visit, as a row range [first, second) of m.T: for t only the slabs
// whose time span holds `value` (empty outside the animation), for x, y, z all of them.
std::pair<int, int> slice_tet_range(const AnimationManifold& m, SliceAxis axis, double value);

// The tetrahedra around every vertex of the ones slice_tet_range gives: for t the slabs on either
// side as well (a vertex of slab i lies in slabs i-1..i+1 only, by validate_manifold's invariant),
// else all. Their sums are the slice's vertex normals.
std::pair<int, int> normal_tet_range(const AnimationManifold& m, SliceAxis axis, double value);

// How many vertices slice_manifold(m, axis, value) has (its weld, by the same rule), without building
// the slice: only the weld keys, no positions or normals (the editor's HUD asks every frame).
int welded_slice_vertex_count(const AnimationManifold& m, SliceAxis axis, double value);

// True when vertices exactly on the hyperplane count as above (see the rules).
bool slice_on_plane_is_above(const AnimationManifold& m, SliceAxis axis, double value);

}  // namespace dfm
