#pragma once
// Transitions between keys of different topology and density (Southern 2008, ch. 5 and 8).
//
// The morph (what a test can compute independently). Keys S (time t0) and T (time t1), u = (t - t0)
// / (t1 - t0):
// - The placement (key_alignment.h; TransitionOptions::align): c0, c1 the solids' centroids, R the
//   rotation between their principal axes of second moments (the smallest turn the moments allow),
//   scale the ratio of their radii of gyration. A(x) = c0 + R^T (x - c1) / scale maps T into S's
//   frame; P_u(x) = c0 + u (c1 - c0) + ((1 - u) + u scale) R(u) (x - c0), R(u) turning by u times R's
//   angle about its axis (Alexa 4.1.1), interpolates it: P_0 = identity, P_1 = A's inverse.
//   Without alignment A and P_u are the identity.
// - The warp (space_warp.h; TransitionOptions::pairs): W with W(x0_i) = A(x1_i) for each picked pair,
//   taken in 8 steps (WarpPath): step k the warp through the pairs from x0_i + (k - 1)/8 (A(x1_i) -
//   x0_i) to x0_i + k/8 (A(x1_i) - x0_i), W_u the first floor(8u) steps and the next one's share of
//   the rest (x + s D_k(x), s = 8u - k). Each picked point travels its straight path; far-moved pairs
//   that one warp would fold space with (the teddy's hands and feet sent round a ring) stay
//   invertible. With picked pairs, W also goes through pairs found as closest points
//   (elastic_pairs.h; TransitionOptions::elastic_samples): the rest of the keys then meet too,
//   where the picked pairs alone leave most of them apart and the blend drops them. Those pairs
//   are reported (TransitionStats::elastic_pairs) and W is defined by all of them. Without pairs W
//   is the identity.
// - The field, in S's frame: the reference target T^ has T's triangles and vertices W^-1(A(v)), and
//   F(r, u) = (1 - u) s_S(r) + u s_T^(r), d the signed distance (negative inside) and s(r) the mean
//   of d at the six points r +- c |d(r)| e_x, e_y, e_z (TransitionOptions::crease_rounding c;
//   rounded_distance.h): s vanishes exactly where d does and has its sign, but the creases d has
//   on the key's medial axis are rounded. (The keys' own layers carry d itself: at u = 0 and 1
//   the zero set is the key either way.)
// - The in-between at u is P_u(W_u({r : F(r, u) = 0})). A picked pair's point travels along
//   P_u(x0 + u (A(x1) - x0)): x0 is on S and (nearly) on T^, so F(x0, u) is about 0 throughout.
//
// How the zero set is built (Southern 2008, ch. 5 and 8). Each key surface (S, and T^) is made
// conforming Delaunay (5.1.3: surface Steiner points until every triangle is a face of the Delaunay
// tetrahedralization of the key's points; starting from TetGen's constrained tetrahedralization,
// conforming_tetgen.h; where splits cascade, nearly flat quads take their other diagonal) and filled
// with points inside and outside (face_protection.h keeps an irregular key's triangles Delaunay faces
// while it is filled). Between the keys sit `layers` middle layers at u_k = (k - 1/2) / layers, all
// holding one point set: a body-centred cubic lattice (cube edge the finer key's spacing) wherever
// some middle layer's zero set may pass, coarser jittered points elsewhere, each carrying F(x, u_k)
// refitted (crossing_fit.h): where F changes sign along a lattice edge, the cubic matching F and its
// gradient at both ends (the rounded distances' gradients, rounded_distance.h) gives the crossing,
// and each point's value moves half way to the one that would put its edges' linear crossings
// there. Linear interpolation of F itself cuts the zero set's curves by chords, a fraction of a
// spacing where a part thins away (the bunny's ears); the refit keeps every simplex's piece flat,
// so the slices' normals stay those of a piecewise linear field (test_transition_quality). Where a
// part is thinner than a spacing, F dips between two lattice points of one sign; near the lattice
// edges along which F's cubic (its values and gradients at the ends) leaves the chord by more than
// TransitionOptions::refine_tolerance spacings close to F's zero set, the lattice is refined to half
// its cube edge (lattice_refinement.h).
//
// Where the blend is nearly flat, as when the air gap between two parts closes, the field's zero set
// changes topology through bridges here and there and pockets filling a moment later: the slices
// show slits for a short while, as F does. TransitionOptions::transient_life can merge such
// short-lived events before the 4D build (layer_transients.h): the lattice points crossing near them
// during one move their crossing to its start, so the gap closes at once, and the slices then leave
// F's zero set there by up to the gap's width (off by default; the lattice is then not refined near
// them, where a finer lattice reads the gap closing earlier and the merge would move more).
//
// The 4D triangulation: each key and its nearest middle layer are joined by one 4D Delaunay
// triangulation (Theorem 5.2.1: the key's tetrahedra and the layer's, the lattice's well-shaped
// Delaunay tetrahedra K, survive as facets), read off the two layers' Voronoi diagrams
// (layer_pair_delaunay.h); between middle layers K x [u_k, u_k+1] is split into the
// staircase 4-simplices of layer_extrusion.h. (A 4D Delaunay triangulation of jittered points in
// every layer cuts slices full of slivers; bench_transition_quality measures the slices.)
//
// Southern strips the 4-simplices that lie outside the keys (8.5) and resolves the ambiguities that
// leaves (8.5.3) by pushing a Voronoi skeleton through time (8.6). Here the simplices carry the field
// instead: the signed distance to the key at the key's points (its surface vertices just inside), the
// blend F at the layers in between, as in distance-field metamorphosis (Payne and Toga 1992; Cohen-Or
// et al. 1998). The transition is the field's zero level set (iso_manifold.h), each of its vertices
// then moved by W_u and P_u at its own u. Before that, the vertices from the first middle layer's
// time to the last's are smoothed in x, y, z (TransitionOptions::relax_rounds; level_set_relax.h:
// each round half way to the hyperplane fitted within 0.8 lattice spacings, a layer interval counted
// as half a spacing; a move that would turn a tetrahedron over is halved or undone): that takes the
// marching facets' zigzag out of the slices (bench_transition_quality) and leaves the connectivity,
// every vertex's time and the keys' planes as they were. It moves vertices off F = 0 by a fraction
// of a lattice spacing (half of one at most); snapping them onto F = 0 instead roughens the slices
// (F of two triangle meshes is itself creased at the lattice's scale, and the marching vertices
// cluster). It is a closed
// 3-manifold by construction, its slices change topology where the blend does, and at a key's time
// the crossings on the key's own edges are its surface vertices; the level set's boundary in the
// key's plane is corrected to the key's surface (key_plane.h) and what folds there sealed
// (key_time_seal.h), so the slice there is the key (at t1 T's own vertices, bit for bit, and its
// Steiner points carried to T by their barycentric coordinates).
// At a middle layer's time the slice is marching tetrahedra of F on K; in between, the staircase
// interpolates. Slices interpolate linearly between vertices of different times: a turn by angle a
// across a layer interval cuts its arcs by chords (1 - cos(a/2) of the radius), so a turning
// transition gets a layer per max_turn_per_layer degrees. Without alignment, keys far apart shrink
// away and grow back.
#include <optional>
#include <string>

#include <Eigen/Core>

#include "core/anim/key_alignment.h"
#include "core/anim/manifold.h"
#include "core/mesh/mesh.h"

namespace dfm {

struct TransitionOptions {
  // Middle layers between the keys (one lattice, its blend at each layer's time; layer_extrusion.h).
  // A slice between two layers crosses their staircase prisms' 4-simplices; close layers keep those
  // pieces nearly coplanar (bench_transition_quality measures the slices).
  int layers = 28;
  // Spacing of the points off the surfaces, in mean surface edge lengths: each key's own near it;
  // the middle lattice's cube edge is the finer key's (in-betweens as finely sampled as it).
  double spacing = 2.0;
  // Rounds of surface flips and Steiner points allowed to make a key conforming Delaunay.
  int max_conform_rounds = 12;
  // Remove the keys' relative placement (centroid, rotation, scale) before the morph and put it back
  // interpolated along the way (above: "The placement").
  bool align = true;
  // Degrees the placement may turn per layer interval: a larger turn gets more layers (a multiple of
  // 4), each cutting its arcs by chords (bench_transition: a box turned a quarter).
  double max_turn_per_layer = 15;
  // Rounds of smoothing the middle layers' zero set (level_set_relax.h); 0 for none.
  int relax_rounds = 1;
  // Topology the lattice reads for less than this part of the transition (a gap closing through
  // bridges and pockets) happens at once, where it starts (layer_transients.h; 0.08 merges the
  // teddy's neck closing at t = 0.47 to 0.50 in the default scene); 0 keeps F's own.
  double transient_life = 0;
  // The keys' distances are averaged over the six points this many times the distance away along the
  // axes before they are blended (rounded_distance.h; above: "The field"): the blend's creases on the
  // keys' medial axes, which show as notches and knife-edged rims in the in-betweens, are rounded. 0
  // blends the signed distances themselves; less than 1.
  double crease_rounding = 0.5;
  // The middle lattice's values refitted to F's own crossings of its edges (above; crossing_fit.h);
  // false: each point carries F itself.
  bool fit_crossings = true;
  // Where the blend bulges off the lattice's chords near its zero set by more than this many lattice
  // spacings (a part thinner than a spacing shrinking away), the lattice is refined to half its
  // spacing (lattice_refinement.h); 0: one spacing everywhere.
  double refine_tolerance = 0.1;
  // Picked pairs, one a row: x0 y0 z0 (a point on the source key) x1 y1 z1 (its partner on the
  // target); #pairs x 6, or none.
  Eigen::MatrixXd pairs = Eigen::MatrixXd(0, 6);
  // With picked pairs: points on each key per round of the closest-point pairs added to them
  // (elastic_pairs.h; above: "The warp"); 0 warps by the picked pairs alone.
  int elastic_samples = 16;

  bool operator==(const TransitionOptions& o) const {
    return layers == o.layers && spacing == o.spacing && max_conform_rounds == o.max_conform_rounds &&
           align == o.align && max_turn_per_layer == o.max_turn_per_layer && relax_rounds == o.relax_rounds &&
           transient_life == o.transient_life && crease_rounding == o.crease_rounding &&
           fit_crossings == o.fit_crossings && refine_tolerance == o.refine_tolerance &&
           elastic_samples == o.elastic_samples &&
           pairs.rows() == o.pairs.rows() &&
           pairs.cols() == o.pairs.cols() && pairs == o.pairs;
  }
};

// One key's side of a transition build.
struct KeyBuildStats {
  int points = 0;       // at the key's time, fill points included
  int steiner = 0;      // surface Steiner points added
  int missing = 0;      // surface triangles the conforming step left missing
  int flipped = 0;      // nearly flat quads that took their other diagonal
  int chords = 0;       // outside tetrahedra still bridging a concavity
  int plane_fixes = 0;  // tets the key's plane read wrongly, corrected (key_plane.h)
  int tied = 0;         // 1 when an exact tie sent its end of the 4D triangulation to CGAL's dD (slower)
  KeyBuildStats& operator+=(const KeyBuildStats& o);
};

struct TransitionStats {
  KeyBuildStats source, target;
  int middle_points = 0;                         // in the layers between
  int refined_points = 0;                        // of them, added where the lattice is refined
  int sealed = 0;                                // folds at the keys' times replaced (key_time_seal.h)
  int relaxed = 0;                               // vertex moves of the smoothing (level_set_relax.h)
  int transients = 0;                            // short-lived events merged (layer_transients.h)
  int simplices = 0;                             // 4-simplices of the Delaunay triangulation
  int tets = 0;                                  // of the resulting manifold
  double turn_degrees = 0, scale = 1;           // the placement's (the last transition's in a sum)
  int elastic_pairs = 0;                         // closest-point pairs the warp also goes through
  double align_seconds = 0;                      // moments, warp, and placing the manifold's vertices
  // Each key's conforming, filling and 4D Delaunay end run on a thread of their own and the middle
  // layers on a third (field: the lattice and its values; extract includes cutting the middle while the
  // keys are still being built): a stage's time is its longest thread's, and the stages add up to more
  // than the total.
  double conform_seconds = 0, field_seconds = 0, delaunay_seconds = 0, extract_seconds = 0;
  double relax_seconds = 0;  // the part of extract_seconds that smooths the level set (level_set_relax.h)
  double total_seconds = 0;

  // Adds another transition's counts and times (a sequence's sum).
  TransitionStats& operator+=(const TransitionStats& o);
};

// Checks a key surface for a transition: finite coordinates, valid indices, no repeated vertex in a
// triangle, closed and consistently oriented, positive enclosed volume. Throws dfm::Error naming
// `what` (e.g. the file) and the problem.
void check_transition_key(const TriMesh& key, const std::string& what);

// A picked pair the transition refuses: its row in `pairs` and why (not 6 columns, not finite, a
// point farther from its key than 2% of the key's bounding-box diagonal, a repeated first point).
struct PairProblem {
  int pair = 0;
  std::string problem;
};
std::optional<PairProblem> transition_pair_problem(const TriMesh& source, const TriMesh& target,
                                                   const Eigen::MatrixXd& pairs);

// The placement a transition between these keys removes and puts back (above: "The placement"):
// key_placement of their solid moments, the identity without TransitionOptions::align.
KeyPlacement transition_placement(const TriMesh& source, const TriMesh& target, const TransitionOptions& options = {});

// Where a picked pair (x0 y0 z0 on the source, x1 y1 z1 on the target) is at u in [0, 1] (above: "The
// in-between"): P_u(x0 + u (A(x1) - x0)), x0 at 0 and x1 at 1.
Eigen::RowVector3d pair_position(const KeyPlacement& placement, const Eigen::Matrix<double, 1, 6>& pair, double u);

// The transition manifold between `source` at time t0 and `target` at time t1 (t0 < t1), in one slab
// per layer interval. Its slice at t0 is the source surface (with its surface Steiner points), at t1
// the target's. Throws dfm::Error on a bad option or pair (transition_pair_problem), or picked pairs
// whose warp folds space.
AnimationManifold build_transition(const TriMesh& source, double t0, const TriMesh& target, double t1,
                                   const TransitionOptions& options = {}, TransitionStats* stats = nullptr);

}  // namespace dfm
