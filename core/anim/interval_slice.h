#pragma once
// The slice topology of one time interval of an animation manifold, for playback (issue 16).
//
// Between two consecutive distinct vertex times tl < th of a manifold, no vertex lies on the plane
// t = c for tl < c < th, so every tetrahedron's case in the slice table is the same for all such c:
// the slice's welded triangles and the manifold edge behind each slice vertex do not change; only
// the interpolation parameter moves. The same holds for a frame between two prism layers (the
// layers' mesh, core/anim/manifold_frame.h). build_interval_slice extracts that topology once
// (manifold_frame at the interval's midpoint); evaluate_interval_slice (and the GPU's render/interval_slice_pass)
// then gives the slice at any c of the open interval by interpolating along the stored edges, with the
// rules of core/anim/slice.h: from the above endpoint (the one at the later time),
//   mu = (t_up - c) / (t_up - t_down),   p = p_up + mu (p_down - p_up),
//   n = normalize(n_up + mu (n_down - n_up)),  n_* = slice_normal3(4D vertex normal, t).
// At a vertex time itself (c == tl or c == th) slice_manifold gives another topology (vertices on the
// plane); the interval's slice there, its limit, is the same surface with some triangles collapsed
// (two of their vertices become the one manifold vertex on the plane), which is what display needs.
#include <array>
#include <vector>

#include <Eigen/Core>

#include "core/anim/manifold.h"
#include "core/mesh/mesh.h"

namespace dfm {

// The distinct t coordinates of the manifold's vertices, increasing.
std::vector<double> manifold_vertex_times(const AnimationManifold& m);

// The index i with times[i] < t < times[i + 1] (times increasing), or -1 when t is one of the times,
// before the first or after the last.
int open_interval_of(const std::vector<double>& times, double t);

struct IntervalSlice {
  double t_lo = 0, t_hi = 0;  // the open interval (t_lo, t_hi)
  // Per slice vertex: the manifold vertices (up, down) of its edge, t(up) > t(down).
  std::vector<std::array<int, 2>> edges;
  Eigen::MatrixXi F;  // welded triangles, oriented outward (manifold_frame's)
  // The slice is closed with positive volume (is_closed_outward at the interval's midpoint; a case
  // that holds over the whole interval, since its topology and orientation do not change inside it).
  bool closed_outward = false;

  int num_vertices() const { return static_cast<int>(edges.size()); }
  int num_faces() const { return static_cast<int>(F.rows()); }
  bool contains(double t) const { return t_lo < t && t < t_hi; }
  bool reaches(double t) const { return t_lo <= t && t <= t_hi; }  // contains, or an end
};

// The topology of the open interval (t_lo, t_hi), which must hold no vertex time inside (two
// consecutive entries of manifold_vertex_times). vertex_normals4: manifold_vertex_normals(m).
// Throws dfm::Error when t_lo >= t_hi or a slice vertex lies on a vertex (a vertex time inside).
IntervalSlice build_interval_slice(const AnimationManifold& m, const Eigen::MatrixXd& vertex_normals4,
                                   double t_lo, double t_hi);

// The slice at time t, t_lo < t < t_hi, from the topology (double precision; the GPU pass does the
// same in float). The result's V, F, N are what manifold_frame(m, t) gives, vertex for vertex.
// At t = t_lo or t_hi it is the limit: for a transition the slice_manifold surface there with collapsed
// triangles, for a prism slab its layer (up to the rounding of p_up + 1 (p_down - p_up)).
TriMesh evaluate_interval_slice(const IntervalSlice& s, const AnimationManifold& m,
                                const Eigen::MatrixXd& vertex_normals4, double t);

}  // namespace dfm
