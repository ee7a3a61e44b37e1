#pragma once
// Smooth 4D vertex normals of an animation manifold (Southern 2008, 2.3.1, Eq. 2.3) and the 3D normal
// a slice along one axis sees (2.3.2: forget that component, renormalise).
//
// A tetrahedron's facet normal is the unnormalised generalized cross product of (p1-p0, p2-p0, p3-p0),
// <N, w> = det[w, p1-p0, p2-p0, p3-p0] (manifold.h's orientation: out of the space-time solid). Its
// length is 6 times the tetrahedron's 3-volume, so summing these vectors is Eq. 2.3 with volume weights.
// On build_manifold's staircase, a vertex of an inner layer between equal time steps thus gets its
// layer's area-weighted normal, and so does one of the first or last layer (the key planes' rule of
// accumulate_tet_normals).
#include <utility>

#include <Eigen/Core>

#include "core/anim/manifold.h"
#include "core/anim/slice.h"

namespace dfm {

// The unnormalised 4D normal of tetrahedron k.
Eigen::Vector4d tet_normal4(const AnimationManifold& m, int k);
// The generalized cross product of three 4D edge vectors: <N, w> = det[w, e1, e2, e3].
Eigen::Vector4d cross4(const Eigen::Vector4d& e1, const Eigen::Vector4d& e2, const Eigen::Vector4d& e3);

// Adds tet_normal4 of every tetrahedron in rows [first_tet, last_tet) of m.T to row (v - vertex_offset)
// of sum (8 columns, rows already there), for each of its vertices v: columns 0-3 the sum the normal
// is, 4-7 a fallback. A vertex at the manifold's first or last time (a key's plane, where a slice is
// the key) sums only the tetrahedra with a face in that plane, whose normals, without t, are those
// faces' normals, so a slice at the key's time is shaded as the key (2.3.2 asks for the slice's
// normal; tetrahedra leaving the plane at a grazing angle tilt it). Only if it has none does it take
// them all (columns 4-7).
void accumulate_tet_normals(const AnimationManifold& m, int first_tet, int last_tet, int vertex_offset,
                            Eigen::MatrixXd& sum);

// accumulate_tet_normals for one corner: adds n (tet_normal4 of tetrahedron k) to row `row` of sum as
// corner c's vertex sees it. Summing a vertex's tetrahedra in increasing k gives the same bits.
void add_tet_normal(const AnimationManifold& m, int k, int c, const Eigen::RowVector4d& n, Eigen::MatrixXd& sum, int row);
// Which of the row's sums add_tet_normal adds to: 1 columns 0-3, 2 columns 4-7, 3 both. Depends on t
// only (a caller summing the same stars again while only x, y, z move can keep it).
int tet_normal_sums(const AnimationManifold& m, int k, int c);

// sum / |sum|, or zero when sum is zero (a vertex in no tetrahedron, or cancelling facets).
Eigen::Vector4d unit_or_zero(const Eigen::Vector4d& sum);

// A vertex's unit normal from its row of accumulate_tet_normals' sums.
Eigen::Vector4d vertex_normal4(const Eigen::Matrix<double, 1, 8>& sums);

// #V x 4 unit vertex normals (Eq. 2.3, with the key planes' rule above); zero rows for vertices no
// tetrahedron uses.
Eigen::MatrixXd manifold_vertex_normals(const AnimationManifold& m);

// Unit 4D normals of single vertices: rows of a caller's #V x 4 manifold_vertex_normals, or, without
// one, summed over rows [first_tet, last_tet) of m.T only (the same tetrahedra in the same order as
// manifold_vertex_normals sees around a vertex, so the same bits, when the range holds all of them).
class VertexNormalSource {
 public:
  // Throws dfm::Error when `given` is not #V x 4.
  VertexNormalSource(const AnimationManifold& m, const Eigen::MatrixXd* given, int first_tet, int last_tet);
  Eigen::Vector4d operator()(int v) const;

 private:
  const Eigen::MatrixXd* given_;
  Eigen::MatrixXd sum_;
  int offset_ = 0;
};

// The slice's 3D normal: n4 without the axis component, renormalised (zero stays zero). Components are
// in the slice's display order (the coordinates left after dropping the axis, as in slice.h).
Eigen::Vector3d slice_normal3(const Eigen::Vector4d& n4, SliceAxis axis);

}  // namespace dfm
