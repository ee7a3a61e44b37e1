#pragma once
// Smooth 4D vertex normals of an animation manifold (Southern 2008, 2.3.1, Eq. 2.3) and the 3D normal
// a slice along one axis sees (2.3.2: forget that component, renormalise).
//
// A tetrahedron's facet normal is the unnormalised generalized cross product of (p1-p0, p2-p0, p3-p0),
// <N, w> = det[w, p1-p0, p2-p0, p3-p0] (manifold.h's orientation: out of the space-time solid). Its
// length is 6 times the tetrahedron's 3-volume, so summing these vectors is Eq. 2.3 with volume weights.
// On build_manifold's staircase, a vertex of an inner layer between equal time steps thus gets its
// layer's area-weighted normal; in the first (last) layer a triangle weighs 1, 2, 3 (3, 2, 1) at its
// vertices by index rank, the number of its prism's tetrahedra that touch them.
#include <utility>

#include <Eigen/Core>

#include "core/anim/manifold.h"
#include "core/anim/slice.h"

namespace dfm {

// The unnormalised 4D normal of tetrahedron k.
Eigen::Vector4d tet_normal4(const AnimationManifold& m, int k);

// Adds tet_normal4 of every tetrahedron in rows [first_tet, last_tet) of m.T to row (v - vertex_offset)
// of sum, for each of its vertices v. sum must already hold those rows.
void accumulate_tet_normals(const AnimationManifold& m, int first_tet, int last_tet, int vertex_offset,
                            Eigen::MatrixXd& sum);

// sum / |sum|, or zero when sum is zero (a vertex in no tetrahedron, or cancelling facets).
Eigen::Vector4d unit_or_zero(const Eigen::Vector4d& sum);

// #V x 4 unit vertex normals (Eq. 2.3); zero rows for vertices no tetrahedron uses.
Eigen::MatrixXd manifold_vertex_normals(const AnimationManifold& m);

// The slice's 3D normal: n4 without the axis component, renormalised (zero stays zero). Components are
// in the slice's display order (the coordinates left after dropping the axis, as in slice.h).
Eigen::Vector3d slice_normal3(const Eigen::Vector4d& n4, SliceAxis axis);

}  // namespace dfm
