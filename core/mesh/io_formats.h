#pragma once
// Per-format readers and writers behind the extension dispatch in io.h. Internal to dfm_mesh.
#include <string>

#include "core/mesh/io.h"

namespace dfm::io {

TriMesh read_obj(const std::string& path);
void write_obj(const std::string& path, const TriMesh& mesh);
TriMesh read_off(const std::string& path);
void write_off(const std::string& path, const TriMesh& mesh);
TriMesh read_ply(const std::string& path);
void write_ply(const std::string& path, const TriMesh& mesh, bool binary);
TriMesh read_stl(const std::string& path);
void write_stl(const std::string& path, const TriMesh& mesh, bool binary);

TetMesh read_medit(const std::string& path);
void write_medit(const std::string& path, const TetMesh& mesh);
TetMesh read_tetgen(const std::string& path);  // X.node + X.ele (either name)
void write_tetgen(const std::string& path, const TetMesh& mesh);

// Flips (swaps the last two vertices of) every negatively oriented tet; returns how many were flipped.
int orient_tets_positively(const Eigen::MatrixXd& V, Eigen::MatrixXi& T);

}  // namespace dfm::io
