#pragma once
// The animation's frame at a time: what the editor draws and picks, and what save-posed, save-frames
// and `deform manifold --at / --sequence` write (issue 38).
//
// Between two layers the prism build joined (keys of one connectivity and their baked in-betweens), the
// frame IS the layers' mesh: vertex v where the plane t = c crosses its own time edge from the upper
// layer's copy to the lower one's, by slice.h's rule on that edge,
//   mu = (t_up - c) / (t_up - t_down),   p = p_up + mu (p_down - p_up),   n likewise from the 4D normals,
// with the layers' triangles, so a frame has the artist's vertex and triangle counts and order. (The
// exact slice of a prism's three tetrahedra kinks on the side diagonals and splits every triangle into
// four.) At a layer's own time the frame is that layer, bit for bit, and at the time of a key a
// transition ends at, that key (ManifoldKey: its vertices and triangles, without the transition's
// surface Steiner points). Elsewhere (inside a transition between meshes of different connectivity, or
// a manifold without these records) the frame is the per-tetrahedron slice, slice_manifold; so are the
// x, y, z sweeps.
#include <Eigen/Core>

#include "core/anim/manifold.h"
#include "core/anim/slice.h"

namespace dfm {

// The prism slab whose closed time span holds t (at a time two slabs share, the earlier prism one), or
// -1 when none does.
int prism_slab_at(const AnimationManifold& m, double t);

// The frame inside prism slab `slab` (times[slab] <= t <= times[slab + 1]): the layers' vertex count
// and triangles; edges[v] is the time edge (lower + v, upper + v), or that one vertex at a layer time.
// vertex_normals4 as in slice_manifold. Throws dfm::Error when slab is not a prism slab or t is
// outside it.
ManifoldSlice prism_frame(const AnimationManifold& m, int slab, double t,
                          const Eigen::MatrixXd* vertex_normals4 = nullptr);

// The key layer at exactly time t, or -1.
int key_layer_at(const AnimationManifold& m, double t);

// Key layer `layer` as a frame: its vertices in the key's order (each that manifold vertex: edges
// (v, v)), its triangles, normals by slice.h's rule. Throws dfm::Error for a missing layer.
ManifoldSlice key_frame(const AnimationManifold& m, int layer, const Eigen::MatrixXd* vertex_normals4 = nullptr);

// prism_frame where a prism slab holds t, else key_frame at a key layer's time, else
// slice_manifold(m, SliceAxis::T, t, vertex_normals4).
ManifoldSlice manifold_frame(const AnimationManifold& m, double t, const Eigen::MatrixXd* vertex_normals4 = nullptr);

}  // namespace dfm
