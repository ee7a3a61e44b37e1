#pragma once
// An animation manifold (Southern 2008, ch. 2): a 3-manifold of tetrahedra in (x, y, z, t) whose
// slice by t = const is the animated surface at that time.
//
// Built from time layers (posed meshes sharing one triangle list F): every triangle of layer i and
// its copy in layer i+1 span a prism, split into 3 tetrahedra. Vertex v of layer i is manifold
// vertex i * #V + v. The split of a prism orders its triangle's vertices by index (v0 < v1 < v2) and
// takes 4 consecutive entries of [v0 v1 v2 v0' v1' v2'] (primes = next layer) as each tetrahedron
// (the "staircase"); so the quad between vertices p < q always gets the diagonal q -- p', whichever
// prism it belongs to, and neighbouring prisms meet without cracks.
//
// Orientation: each tetrahedron (p0, p1, p2, p3) is ordered so that its 4D normal
//   N = generalized cross product of (p1-p0, p2-p0, p3-p0), <N, w> = det[w, p1-p0, p2-p0, p3-p0],
// points out of the space-time solid swept by the (outward-oriented) layers.
//
// The prism build also records, per slab, the layer mesh its prisms stand on (PrismSlab), so a frame
// between two layers of one connectivity can be that mesh (core/anim/manifold_frame.h).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/anim/bake.h"

namespace dfm {

using MatrixX4dRow = Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>;
using MatrixX4iRow = Eigen::Matrix<int, Eigen::Dynamic, 4, Eigen::RowMajor>;

// A slab made by the prism build: vertex v (0 <= v < count) of its lower layer is manifold vertex
// lower + v, of its upper layer upper + v, and its triangles are layer_faces[faces]. faces = -1 for a
// slab made otherwise (a transition).
struct PrismSlab {
  int faces = -1;
  int lower = 0, upper = 0, count = 0;
  bool is_prism() const { return faces >= 0; }
};

// A key surface standing in the manifold at `time` (a transition's end, whose slice there is the key
// with its surface Steiner points): its triangles are layer_faces[faces] on manifold vertices
// vertices[v], so a frame at that time can be the key itself.
struct ManifoldKey {
  double time = 0;
  int faces = -1;
  std::vector<int> vertices;
};

struct AnimationManifold {
  MatrixX4dRow V;             // #V x 4: x, y, z, t
  MatrixX4iRow T;             // #T x 4 vertex indices, oriented as above
  std::vector<double> times;  // m layer times, strictly increasing
  // m entries: the tetrahedra between times[i] and times[i+1] (slab i) are rows
  // [slab_offsets[i], slab_offsets[i+1]) of T; slab_offsets.back() == #T.
  std::vector<int> slab_offsets;
  // Empty, or one entry per slab saying how it was made; layer_faces holds the triangle lists
  // (#F x 3, outward) the prism slabs and key layers refer to.
  std::vector<PrismSlab> prism_slabs;
  std::vector<ManifoldKey> key_layers;
  std::vector<Eigen::MatrixXi> layer_faces;

  int num_vertices() const { return static_cast<int>(V.rows()); }
  int num_tets() const { return static_cast<int>(T.rows()); }
  int num_layers() const { return static_cast<int>(times.size()); }
  int num_slabs() const { return num_layers() > 0 ? num_layers() - 1 : 0; }
};

// Layers: m >= 2 matrices #V x 3 (the same #V), F: #F x 3 triangles (0-based, outward), times:
// m strictly increasing values. Gives exactly 3 #F (m - 1) tetrahedra, and every slab a PrismSlab. Throws dfm::Error on
// mismatched sizes, indices out of range, a triangle with a repeated vertex, or unsorted times.
AnimationManifold build_manifold(const std::vector<Eigen::MatrixXd>& layers, const Eigen::MatrixXi& F,
                                 const std::vector<double>& times);
AnimationManifold build_manifold(const BakedLayers& layers, const Eigen::MatrixXi& F);

// The 3 oriented tetrahedra (manifold vertex indices) of the prism over triangle f = (a, b, c):
// lower-layer vertex v is lower_offset + v, its upper copy lower_offset + stride + v.
std::vector<Eigen::Vector4i> prism_tets(const Eigen::Vector3i& f, int lower_offset, int stride);

// Checks the invariants above (sizes, index range, sorted times, offsets, that every vertex of slab
// i's tetrahedra has times[i] <= t <= times[i+1], and that a prism slab's layers and a key layer lie
// at their times with triangles on them); throws dfm::Error naming `what` and the first problem.
void validate_manifold(const AnimationManifold& m, const std::string& what = "manifold");

}  // namespace dfm
