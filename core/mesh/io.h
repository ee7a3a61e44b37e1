#pragma once
// Mesh, skeleton and matrix files. Every reader throws dfm::Error naming the file, the line (or byte
// offset) and the problem; never crashes on malformed input. Every writer is atomic (temp + rename).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/mesh/mesh.h"

namespace dfm {

// Surfaces by extension: .obj .off .ply (ascii/binary) .stl (ascii/binary). Polygons are triangulated.
TriMesh read_surface(const std::string& path);
// Writes V, F and (where the format has them, and mesh.N is non-empty) normals.
// `binary` applies to PLY and STL.
void write_surface(const std::string& path, const TriMesh& mesh, bool binary = false);

// Tet meshes by extension: .mesh (MEDIT, 1-based) or .node/.ele (TetGen; either name may be given).
TetMesh read_tet_mesh(const std::string& path);
void write_tet_mesh(const std::string& path, const TetMesh& mesh);

// True for extensions read_tet_mesh understands.
bool is_tet_mesh_path(const std::string& path);

// .dmat dense matrices (text, or binary when the first line is "0 0").
Eigen::MatrixXd read_dmat(const std::string& path);
void write_dmat(const std::string& path, const Eigen::MatrixXd& M, bool binary = false);

// Vertex index list: one 0-based index per line ('#' comments and blank lines allowed), e.g. a region
// for `deform sculpt`. Throws dfm::Error naming the file and line for junk or an index outside
// [0, num_vertices).
std::vector<int> read_vertex_indices(const std::string& path, int num_vertices);

// .tgf skeleton file, as written (see ../shared/data/README.md). 0-based here.
struct TgfData {
  Eigen::MatrixXd joints;   // #J x 3
  Eigen::MatrixXi edges;    // #E x 2 joint indices
  Eigen::MatrixXi flags;    // #E x 3: is_bone, is_pseudo_edge, is_cage_edge (an edge with 2 numbers is a bone)
};
TgfData read_tgf(const std::string& path);
void write_tgf(const std::string& path, const TgfData& tgf);

// Plain text points, one "x y z" per line ('#' comments and blank lines allowed).
Eigen::MatrixXd read_points(const std::string& path);
void write_points(const std::string& path, const Eigen::MatrixXd& P);

}  // namespace dfm
