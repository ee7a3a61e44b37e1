#pragma once
// A coarser tet mesh of the same domain, for a multilevel start of the bounded weight solves: the
// weights solved there (cheap) and carried to the fine vertices put each fine solve's active set
// within a ring or two of its final place, where the bound-free solution can be far off.
//
// Coarse vertices: every constrained vertex, then a maximal independent set of the tet graph (about
// an eighth of the vertices); TetGen's Delaunay tetrahedralization of them, carved to the fine domain by
// the winding number of its boundary (tets whose centroid is outside, and slivers, dropped); parts
// without a constrained vertex dropped. A fine vertex takes the average of its coarse neighbours (itself
// when it is one), weighted by inverse distance.
#include <Eigen/Core>
#include <Eigen/Sparse>

namespace dfm {

struct CoarseLevel {
  Eigen::MatrixXd V;                  // coarse vertices
  Eigen::MatrixXi T;                  // coarse tets, positively oriented
  Eigen::VectorXi b;                  // constrained coarse vertices
  Eigen::MatrixXd bc;                 // their values (#b x #handles)
  Eigen::SparseMatrix<double> P;      // #fine V x #coarse V, rows >= 0 summing to 1 (or empty rows)
};

// False when no usable coarse level exists (too small a mesh, a handle with no constrained coarse
// vertex, TetGen failing): the caller then starts from the bound-free solution. min_vertices: below it,
// a coarse level does not pay.
bool build_coarse_level(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, const Eigen::VectorXi& b,
                        const Eigen::MatrixXd& bc, CoarseLevel& out, int min_vertices = 20000);

}  // namespace dfm
