#pragma once
// Transitions between keys of different topology and density (Southern 2008, ch. 5 and 8).
//
// Each key surface is made conforming Delaunay (5.1.3: surface Steiner points until every triangle is
// a face of the Delaunay tetrahedralization of the key's points; starting from TetGen's constrained
// tetrahedralization, conforming_tetgen.h; where splits cascade, nearly flat quads take their other
// diagonal) and filled with points inside and outside (face_protection.h keeps an irregular key's
// triangles Delaunay faces while it is filled); the keys are embedded in 4D at their times, with layers of grid points in between, and
// joined by one Delaunay triangulation (Theorem 5.2.1: each key's tetrahedra survive as facets).
//
// Southern strips the 4-simplices that lie outside the keys (8.5) and resolves the ambiguities that
// leaves (8.5.3) by pushing a Voronoi skeleton through time (8.6). Here the simplices carry a field
// instead: the signed distance to the key at the key's points (its surface vertices just inside), the
// blend (1 - u) d_source + u d_target of both keys' signed distances at the layers in between, as in
// distance-field metamorphosis (Payne and Toga 1992; Cohen-Or et al. 1998). The transition is the
// field's zero level set (iso_manifold.h). It is a closed 3-manifold by construction, its slices
// change topology where the blend does, and at a key's time the crossings on the key's own edges are
// its surface vertices; the level set's boundary in the key's plane is corrected to the key's surface
// (key_plane.h) and what folds there sealed (key_time_seal.h), so the slice there is the key. Keys are blended
// where they are (no alignment): keys far apart shrink away and grow back.
#include <string>

#include <Eigen/Core>

#include "core/anim/manifold.h"
#include "core/mesh/mesh.h"

namespace dfm {

struct TransitionOptions {
  // Layers of blended points between the keys.
  int layers = 4;
  // Grid spacing of the points off the surfaces, in mean surface edge lengths: each key's own near
  // it, the coarser key's in the layers between.
  double spacing = 2.0;
  // Rounds of surface flips and Steiner points allowed to make a key conforming Delaunay.
  int max_conform_rounds = 12;

  bool operator==(const TransitionOptions& o) const {
    return layers == o.layers && spacing == o.spacing && max_conform_rounds == o.max_conform_rounds;
  }
};

struct TransitionStats {
  int source_points = 0, target_points = 0;      // at the keys' times, fill points included
  int middle_points = 0;                         // in the layers between
  int source_steiner = 0, target_steiner = 0;    // surface Steiner points added
  int source_missing = 0, target_missing = 0;    // surface triangles the conforming step left missing
  int source_flipped = 0, target_flipped = 0;    // nearly flat quads that took their other diagonal
  int source_chords = 0, target_chords = 0;      // outside tetrahedra still bridging a concavity
  int source_plane_fixes = 0, target_plane_fixes = 0;  // tets the keys' planes read wrongly, corrected (key_plane.h)
  int sealed = 0;                                // folds at the keys' times replaced (key_time_seal.h)
  int simplices = 0;                             // 4-simplices of the Delaunay triangulation
  int tets = 0;                                  // of the resulting manifold
  double conform_seconds = 0, field_seconds = 0, delaunay_seconds = 0, extract_seconds = 0;
  double total_seconds = 0;

  // Adds another transition's counts and times (a sequence's sum).
  TransitionStats& operator+=(const TransitionStats& o);
};

// Checks a key surface for a transition: finite coordinates, valid indices, no repeated vertex in a
// triangle, closed and consistently oriented, positive enclosed volume. Throws dfm::Error naming
// `what` (e.g. the file) and the problem.
void check_transition_key(const TriMesh& key, const std::string& what);

// The transition manifold between `source` at time t0 and `target` at time t1 (t0 < t1), in one slab
// per layer interval. Its slice at t0 is the source surface (with its surface Steiner points), at t1
// the target's.
AnimationManifold build_transition(const TriMesh& source, double t0, const TriMesh& target, double t1,
                                   const TransitionOptions& options = {}, TransitionStats* stats = nullptr);

}  // namespace dfm
