#pragma once
// Conforming Delaunay surfaces (Southern 2008, 5.1.3): surface Steiner points (edge midpoints) until
// every triangle of a closed surface is a face of the Delaunay tetrahedralization of its vertices,
// so that a Delaunay triangulation one dimension up keeps the surface (Theorem 5.2.1).
#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

namespace dfm {

struct ConformingSurface {
  Eigen::MatrixXd V;  // the input's vertices first (same order), then the Steiner points
  Eigen::MatrixXi F;  // the input's triangles, split where Steiner points were added (same orientation)
  int steiner = 0;
  int rounds = 0;
  int missing = 0;  // triangles still not faces of the Delaunay tetrahedralization (0: conforming)
  // Edges that flip_nearly_flat put across nearly flat quads (edge keys: smaller index << 32 | larger):
  // they lie off the input surface by at most its gap, so no Steiner point goes on them.
  std::vector<std::uint64_t> flipped;
  // Points off the surface (inside or outside), part of the Delaunay tetrahedralization.
  Eigen::MatrixXd fill = Eigen::MatrixXd(0, 3);
};

// Splits the given edge (0..2: corners e, e+1) of each listed triangle at its midpoint (both
// triangles on the edge are split, orientation kept). Returns the number of points added.
int split_edges(ConformingSurface& s, const std::vector<std::pair<int, int>>& triangle_edges);

// Makes a closed, edge-manifold surface conforming Delaunay, as far as max_rounds rounds of flips
// (coplanar neighbours) and edge splits get; it stops early when a round leaves no fewer triangles
// missing (near sharp or nearly touching parts splitting cascades). `missing` says how far it got.
// Throws dfm::Error when two vertices coincide.
ConformingSurface conforming_delaunay_surface(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int max_rounds);
// Where a missing triangle and its neighbour are nearly coplanar (their quad's diagonals pass within
// max_gap of each other) and the other diagonal is a Delaunay edge, the surface takes it: every
// vertex stays, the surface moves by at most max_gap (a last resort for surfaces whose splits
// cascade). Returns the number of flips.
int flip_nearly_flat(ConformingSurface& s, double max_gap);

// Where the functions below get the surface's Delaunay tetrahedralization when given one (it follows
// the surface's points from call to call; surface_delaunay.h), else it is built afresh.
class GrowingSurfaceDelaunay;

// Continues on a surface that is already partly conforming (e.g. after split_longest_edges).
void make_conforming(ConformingSurface& s, int max_rounds, GrowingSurfaceDelaunay* growing = nullptr);

// How added points spare the surface's conformity. Protect admits only points that leave every
// surface triangle that is a Delaunay face one (face_protection.h), and none near the others. Repair
// adds them all, then drops those inside the diametral spheres of the triangles they cost: it fills
// more where the surface is co-spherical (regular grids), where protecting balls are tight.
enum class FillRule { Protect, Repair };

// Adds points off the surface to the tetrahedralization (as TetGen's quality mesh fills the keys in
// Southern's 8.7: small tetrahedra keep the simplices of a transition small), as the rule allows.
// Returns the number of points added.
int add_fill_points(ConformingSurface& s, const Eigen::MatrixXd& candidates, FillRule rule,
                    GrowingSurfaceDelaunay* growing = nullptr);
// The same for groups of alternatives: of each group, the first candidate that the rule admits and
// `accept` (if given; called with the group's index) takes.
int add_fill_points(ConformingSurface& s, const std::vector<std::vector<Eigen::RowVector3d>>& groups, FillRule rule,
                    const std::function<bool(size_t, const Eigen::RowVector3d&)>& accept = {},
                    GrowingSurfaceDelaunay* growing = nullptr);

// Tetrahedra with all four corners on the surface, and outside tetrahedra with a triangle of three
// surface vertices that is not a surface triangle (they bridge concavities), get a point in their
// circumball, as far as add_fill_points keeps them (for `rounds` rounds): so that every tetrahedron
// has a corner off the surface and the outside touches the surface only through surface triangles,
// edges and vertices. Returns the number of such tetrahedra left.
int cover_outside_chords(ConformingSurface& s, FillRule rule, int rounds = 1, GrowingSurfaceDelaunay* growing = nullptr);

}  // namespace dfm
