#pragma once
// Smoothing a sampled level set in space-time without changing its connectivity (issue 30):
// marching pentatopes put each vertex where the piecewise linear field crosses an edge, so where the
// lattice is coarse for the shape the pieces zigzag and the slices show creases. A round moves each
// movable vertex part of the way to the hyperplane fitted to the vertices around it (up to two edges
// away and within `radius` in 4D, time scaled to lengths; weights (1 - d^2 / radius^2)^2 times each
// vertex's share of the tetrahedra's 3-volume, so slivers count little), along that hyperplane's
// spatial normal: x, y, z change, t does not, so every vertex stays in its slab. The fit reaches a
// fixed radius because the vertices cluster irregularly (near the lattice's points): the
// neighbours' mean (the umbrella operator) moves each vertex by the curvature times its own
// neighbourhood's size, which varies from vertex to vertex and roughens a curved level set
// (test_transition_relax's sphere).
// A move that turns an incident tetrahedron over (its 4D normal, or the spatial part of it a slice's
// triangle takes, reversing) is halved, then undone.
//
// Not a projection onto the exact field: the blend of two triangle meshes' distances, snapped onto
// at these irregular vertices, roughens the slices (bench_transition_quality).
#include <vector>

#include <Eigen/Core>

#include "core/anim/manifold.h"

namespace dfm {

struct LevelSetRelaxOptions {
  int rounds = 1;
  double weight = 0.5;    // the share of the way to the fitted hyperplane
  double radius = 1;      // of the fit, in 4D (t times time_scale)
  double max_move = 0;    // a longer move in one round is dropped (0: no limit)
  double time_scale = 1;  // lengths per unit of t
};

struct LevelSetRelaxStats {
  int moved = 0;   // vertex moves kept (half-way ones included), over all rounds
  int undone = 0;  // moves undone because a tetrahedron would turn over
};

// Moves the vertices with movable[v] set (x, y, z only) of the oriented tetrahedra T; the other
// vertices stay bit for bit. Throws dfm::Error when the sizes disagree, an index is out of range or
// the radius or time scale is not positive.
LevelSetRelaxStats relax_level_set(MatrixX4dRow& V, const MatrixX4iRow& T, const std::vector<char>& movable,
                                   const LevelSetRelaxOptions& options);

}  // namespace dfm
