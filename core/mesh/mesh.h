#pragma once
// Plain mesh data: Eigen matrices, one row per element, 0-based indices.
#include <Eigen/Core>

namespace dfm {

using MatrixX3d = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

// Triangle surface. V: #V x 3 positions, F: #F x 3 vertex indices (counter-clockwise = outward).
struct TriMesh {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  Eigen::MatrixXd N;  // optional per-vertex normals (#V x 3) or empty
  int num_vertices() const { return static_cast<int>(V.rows()); }
  int num_faces() const { return static_cast<int>(F.rows()); }
};

// Tetrahedral mesh. T: #T x 4 vertex indices, positively oriented (det[v1-v0, v2-v0, v3-v0] > 0).
// F: optional boundary/surface triangles (#F x 3), e.g. the triangles stored in a MEDIT file.
struct TetMesh {
  Eigen::MatrixXd V;
  Eigen::MatrixXi T;
  Eigen::MatrixXi F;
  int num_vertices() const { return static_cast<int>(V.rows()); }
  int num_tets() const { return static_cast<int>(T.rows()); }
};

}  // namespace dfm
