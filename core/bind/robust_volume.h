#pragma once
// Pieces of the robust (generalized winding number) volume of Jacobson et al. 2013 and the tet-mesh
// bookkeeping shared by every bind volume: surface diagnosis, welding, inside selection, compaction,
// and interpolation of tet-vertex values at arbitrary points.
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "core/mesh/mesh.h"
#include "core/mesh/mesh_info.h"

namespace dfm {

// What is wrong (if anything) with a surface before TetGen sees it.
struct SurfaceReport {
  int duplicate_vertices = 0;   // exact copies of an earlier vertex (welded)
  int degenerate_faces = 0;     // repeated vertex index or zero area
  int boundary_edges = 0;       // edges with one face (holes)
  int nonmanifold_edges = 0;    // edges with more than two faces
  int inconsistent_edges = 0;   // two faces traversing the edge in the same direction
  int unreferenced_vertices = 0;
  int components = 0;           // face-connected pieces
  bool watertight() const { return boundary_edges == 0 && nonmanifold_edges == 0 && inconsistent_edges == 0 && degenerate_faces == 0; }
  std::string describe() const;  // "12 boundary edges, 3 non-manifold edges" or "closed manifold"
};

// Exact duplicate vertices merged and degenerate faces dropped.
struct WeldedSurface {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  Eigen::VectorXi user_to_welded;  // user vertex -> row of V
  SurfaceReport report;
};
WeldedSurface weld_surface(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// Keeps only the tets whose vertices are used; old_to_new(v) = new index or -1. Order is preserved.
TetMesh compact_tet_mesh(const TetMesh& tets, Eigen::VectorXi& old_to_new);

// tet_boundary_faces: see core/mesh/mesh_info.h.

// Tet centroids (#T x 3).
Eigen::MatrixXd tet_centroids(const TetMesh& tets);

// Rows of a sparse #P x #tet V matrix: each point's barycentric coordinates in the tet containing it,
// or (outside every tet) in the nearest one, clamped to the tet.
Eigen::SparseMatrix<double> tet_interpolation(const TetMesh& tets, const Eigen::MatrixXd& P);

// Face-connected components of the tets (sharing a vertex counts): component id per vertex, -1 if unused.
int tet_vertex_components(const TetMesh& tets, Eigen::VectorXi& comp);

}  // namespace dfm
