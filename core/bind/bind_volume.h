#pragma once
// The volume a bind works on, with the handles' boundary conditions (contract between the volume
// stage -- tetrahedralize / winding numbers -- and the weights stage -- fem + bbw).
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>

#include "core/bind/graph_cut_segmentation.h"
#include "core/mesh/mesh.h"
#include "core/rig/rig.h"

namespace dfm {

struct VolumeOptions {
  std::string tetgen_switches = "pq1.414Y";
  // Robust (generalized winding number) volume: Auto = when the surface is not closed/manifold/clean
  // or TetGen fails on it.
  enum class Robust { Auto, Never, Always } robust = Robust::Auto;
  // Which tets the robust volume keeps: Cut minimizes Jacobson 2013's energy (8.5.1) with a graph cut,
  // Threshold keeps those with winding number > 1/2 (Eq. 8.7).
  enum class Segmentation { Cut, Threshold } segmentation = Segmentation::Cut;
  GraphCutOptions cut;
  bool operator==(const VolumeOptions& o) const {
    return tetgen_switches == o.tetgen_switches && robust == o.robust && segmentation == o.segmentation && cut == o.cut;
  }
};

// A piece of the volume (connected component of its tets, numbered in order of first vertex) that no
// handle touches: it moves rigidly, every vertex taking the weights of `anchor` (rigid_pieces.h).
struct RigidPiece {
  int piece = -1;
  int vertices = 0;               // the user's mesh vertices in it
  int anchor = -1;                // tet vertex of the nearest handled piece
  std::vector<int> tet_vertices;  // the piece's tet vertices
};

struct BindVolume {
  TetMesh tets;            // positively oriented tets
  Eigen::VectorXi b;       // constrained tet-vertex indices
  Eigen::MatrixXd bc;      // #b x #handles values at those vertices (rows in [0,1], summing to 1)
  // Maps weights on tet vertices to the user's mesh vertices (#user V x #tet V). When the user's
  // vertices are the first tet vertices this is [I 0].
  Eigen::SparseMatrix<double> to_user;
  std::vector<RigidPiece> rigid_pieces;  // pieces without a handle (their rows in b, bc are placeholders)
  std::vector<std::string> notes;  // what happened (e.g. "surface has 12 boundary edges: robust volume")
  double meshing_seconds = 0;
};

// Surface input: tetrahedralizes with TetGen (subprocess) conforming to every handle's geometry.
BindVolume build_bind_volume(const TriMesh& surface, const Rig& rig, const VolumeOptions& opts = {});
// Tet-mesh input used as it is; throws dfm::Error naming the handle if its geometry is missing
// from the mesh or lies outside the domain.
BindVolume bind_volume_from_tets(const TetMesh& tets, const Rig& rig);

}  // namespace dfm
