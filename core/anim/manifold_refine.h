#pragma once
// Space-time edits that refine what they stretch (Southern 2008, 4.5.1, the offline regularisation;
// issue 35). A drag lengthens the region's edges along the move, and a slice through long, thin
// triangles is coarse and faceted where the edit pulled. The loop:
//   edit; mark the layer triangles with an edge the edit lengthened, in any layer of the window, to more
//   than `stretch` times the mean length (before the edit) of the layer edges at region vertices, and
//   `rings` rings of triangles around them; refine the layer mesh red-green (core/mesh/red_green_refine.h: marked triangles 1:4, no hanging
//   vertex), in every layer, new vertices at the unedited layers' edge middles; rebuild the prisms;
//   edit the refined manifold again (a new selection and factorisation);
// until nothing is marked or after max_rounds.
//
// Southern splits single edges of the tetrahedra (his ch. 6 split tuple). Here that gave rougher slices
// than no refinement at all (bench_manifold_refine): a split leaves irregular tetrahedra whose Laplacian
// rows keep a tangential part that the edit turns outwards. Refining the layer mesh keeps every slab a
// prism slab, so frames between layers stay the layers' interpolation, and the refined edit approaches
// the same edit on a mesh fine from the start (bench_manifold_refine: a level-4 sphere's pulled spike,
// t = 2, farthest point from a level-5 sphere's edit 1.2% -> 0.15% of the diagonal). A second round
// refines the green seams again and moves away from it (0.95%), hence one round by default.
//
// The refinement reaches every layer: outside the window the surface is the same (the original vertices
// bit for bit, the new ones at middles of unmoved edges) but has the new vertices. A manifold that is not
// all prism slabs of one layer mesh (a transition, or one already retimed) is refused.
#include <vector>

#include "core/anim/manifold.h"
#include "core/anim/manifold_edit.h"
#include "core/anim/manifold_edit_region.h"

namespace dfm {

struct RefineOptions {
  double stretch = 2.0;  // Southern's tolerance: twice the mean edge length
  int rings = 2;         // triangles refined around the stretched ones (the red-green seam away from the pull)
  int max_rounds = 1;    // each round factors the region again (4.5.1's loop; Southern needed one)
};

struct RefineStats {
  int rounds = 0;       // edits made after refining (0: nothing was stretched that far)
  int added = 0;        // vertices added to each layer, all rounds
  double longest = 0;   // the longest layer edge at a region vertex after the last edit, in mean lengths
  // Where each vertex of m's layers is in the refined layers (new vertices are numbered between their
  // edge's ends: see manifold_refine.cpp).
  std::vector<int> layer_index;
};

// Throws dfm::Error, as edit_refined does, when m is not all prism slabs of one layer mesh.
void check_refinable(const AnimationManifold& m);

// The edited manifold (m with the drag applied, refined as above; a retime's slabs merged). Throws
// dfm::Error with m unchanged for the manifolds above and for what select_edit_region and
// ManifoldEditor refuse.
AnimationManifold edit_refined(const AnimationManifold& m, const EditRegionSpec& region, const EditHandleSpec& handle,
                               const ManifoldEditOptions& options, const ManifoldDrag& drag,
                               const RefineOptions& refine = {}, RefineStats* stats = nullptr);

}  // namespace dfm
