#pragma once
// A transition's level set at a key's time. The key's surface vertices are anchored just inside, so a
// tetrahedron of the key's own tetrahedralization with all four corners on its surface holds no
// crossing: outside the key (a bridge over a concavity) it reads as inside, and where the 4-simplex
// above it has a positive corner it lies flat in the key's plane as a lid. The level set's boundary
// in the plane, read as a chain (the triangles of its tetrahedra standing on the plane and the
// boundaries of the lids lying in it), then encloses a region of the key's tetrahedra that is not the
// key's inside, and a slice at the key's time (after seal_key_time) is not the key.
//
// The chain's difference from the key's surface is a cycle, the boundary of a chain P of the key's
// tetrahedra (labelled from outside the hull across it); lids -P go in, or cancel lids of the
// opposite orientation already there, so that the chain is the key's surface. Everything added lies
// in the plane, so the manifold stays closed off it; seal_key_time then cones what folds.
//
// Southern 2008 meets the same plane when stripping: 8.5.1 projects the 4-simplices into a key's
// plane and finds duplicates there in opposite orientations, and 8.5.2 tells inside from outside by
// a front grown from the manifold's facets that cancels where it meets itself. Here the plane's
// pieces are summed as an oriented chain, so duplicates cancel by construction, and the walk from
// the hull plays the front's part against the key's own inside.
#include <vector>

#include <Eigen/Core>

#include "core/anim/conforming_surface.h"
#include "core/anim/manifold.h"

namespace dfm {

// A key's tetrahedralization at its time.
struct KeyTets {
  Eigen::MatrixXd points;      // the surface's vertices, then its fill points
  Eigen::MatrixXi tets;        // positively oriented
  Eigen::MatrixXi neighbours;  // neighbours(t, i): across the face opposite corner i, -1 outside the hull
  std::vector<char> inside;    // per tet: inside the key (winding number of its centroid)
};

// The Delaunay tetrahedralization of a conforming surface and its fill points (delaunay_3d.h);
// a tet with a fill point is on that point's side (fill_values: their signed distances, negative
// inside), one with all corners on the surface where the winding number puts its centroid.
KeyTets key_tets(const ConformingSurface& s, const Eigen::VectorXd& fill_values);

struct KeyPlaneStats {
  int bridges = 0;    // outside tetrahedra the chain enclosed
  int carved = 0;     // inside tetrahedra the chain left out
  int added = 0;      // lids put in
  int cancelled = 0;  // lids already there that the correction cancels
  int conflicts = 0;  // faces where the labels disagree (the chain is not a boundary there); 0 expected
};

// V, T: the level set (iso_manifold.h), its vertices in the plane at the key's points; time: the
// key's time. Adds vertices for key points that become lid corners.
KeyPlaneStats correct_key_plane(MatrixX4dRow& V, MatrixX4iRow& T, double time, const KeyTets& key);

}  // namespace dfm
