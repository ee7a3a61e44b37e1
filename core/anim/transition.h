#pragma once
// Transitions between keys of different topology and density (Southern 2008, ch. 5 and 8).
//
// Each key surface is made conforming Delaunay (5.1.3: surface Steiner points until every triangle is
// a face of the Delaunay tetrahedralization of the key's points), both point sets are embedded in 4D
// at their times and joined by one Delaunay triangulation of the union (Theorem 5.2.1: each key's
// Delaunay tetrahedra survive as facets). A 4-simplex s has its lower vertices B (at t0) and upper
// vertices U (at t1); its slice at local time u is (1 - u) B + u U. Southern strips s when B lies
// outside the source or U outside the target (8.5); that leaves the ambiguities of 8.5.3 (a simplex
// whose lower face is inside the source and upper face outside the target has to fill the source
// near t0 and to vanish before t1). Instead of pushing a skeleton through time (8.6), the time span is
// cut into three layers: near the source the source alone decides (B inside), in the middle both
// (B and U inside), near the target the target alone (U inside); the boundary 3-manifold of the kept
// pieces, with the tetrahedra clipped to their layer, is the transition.
#include <string>

#include <Eigen/Core>

#include "core/anim/manifold.h"
#include "core/mesh/mesh.h"

namespace dfm {

struct TransitionOptions {
  // The local times (in (0, 1), early < late) where the source's and the target's own say ends.
  double early = 0.15;
  double late = 0.85;
  // Rounds of surface flips and Steiner points allowed to make a key conforming Delaunay.
  int max_conform_rounds = 12;
  // Interior points on a grid this many mean surface edge lengths apart (0: surface points only).
  double interior_spacing = 2.0;
};

struct TransitionStats {
  int source_points = 0, target_points = 0;      // after the conforming step, interior points included
  int source_steiner = 0, target_steiner = 0;    // surface Steiner points added
  int source_missing = 0, target_missing = 0;    // surface triangles the conforming step left missing
  int simplices = 0;                             // 4-simplices of the Delaunay triangulation
  int kept_early = 0, kept_middle = 0, kept_late = 0;
  int repairs = 0;                               // simplices flipped to keep the boundary manifold
  int tets = 0;                                  // of the resulting manifold
  double conform_seconds = 0, delaunay_seconds = 0, classify_seconds = 0, extract_seconds = 0;
  double total_seconds = 0;

  // Adds another transition's counts and times (a sequence's sum).
  TransitionStats& operator+=(const TransitionStats& o);
};

// Checks a key surface for a transition: finite coordinates, valid indices, no repeated vertex in a
// triangle, closed and consistently oriented, positive enclosed volume. Throws dfm::Error naming
// `what` (e.g. the file) and the problem.
void check_transition_key(const TriMesh& key, const std::string& what);

// The transition manifold between `source` at time t0 and `target` at time t1 (t0 < t1): one slab.
// Its slice at t0 is the source surface (with its surface Steiner points), at t1 the target's.
AnimationManifold build_transition(const TriMesh& source, double t0, const TriMesh& target, double t1,
                                   const TransitionOptions& options = {}, TransitionStats* stats = nullptr);

}  // namespace dfm
