#pragma once
// Conforming Delaunay surfaces (Southern 2008, 5.1.3): surface Steiner points (edge midpoints) until
// every triangle of a closed surface is a face of the Delaunay tetrahedralization of its vertices,
// so that a Delaunay triangulation one dimension up keeps the surface (Theorem 5.2.1).
#include <vector>

#include <Eigen/Core>

namespace dfm {

struct ConformingSurface {
  Eigen::MatrixXd V;  // the input's vertices first (same order), then the Steiner points
  Eigen::MatrixXi F;  // the input's triangles, split where Steiner points were added (same orientation)
  int steiner = 0;
  int rounds = 0;
};

// Splits the longest edge of each listed triangle at its midpoint (both triangles on the edge are
// split, orientation kept). Returns the number of points added.
int split_longest_edges(ConformingSurface& s, const std::vector<int>& triangles);

// Makes a closed, edge-manifold surface conforming Delaunay. Throws dfm::Error when it is not after
// max_rounds rounds of splitting.
ConformingSurface conforming_delaunay_surface(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int max_rounds);
// Continues on a surface that is already partly conforming (e.g. after split_longest_edges).
void make_conforming(ConformingSurface& s, int max_rounds);

}  // namespace dfm
