#pragma once
// Mesh checks: free functions on plain matrices (V: #V x 3, F: #F x 3, T: #T x 4; 0-based).
// Used by `deform info` and by the robust bind to tell clean closed manifolds from messy meshes.
#include <vector>

#include <Eigen/Core>

#include "core/mesh/mesh.h"

namespace dfm {

struct BoundingBox {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();
  Eigen::Vector3d max = Eigen::Vector3d::Zero();
  Eigen::Vector3d diagonal() const { return max - min; }
};
// Axis-aligned box of the rows of V (all zero for an empty V).
BoundingBox bounding_box(const Eigen::MatrixXd& V);

// Connected pieces of the surface: faces sharing a vertex are connected. Vertices used by no face
// are not counted (see unreferenced_vertex_count).
int connected_component_count(const Eigen::MatrixXi& F);
// Per face, its component id in [0, connected_component_count(F)).
Eigen::VectorXi face_components(const Eigen::MatrixXi& F);
int unreferenced_vertex_count(int num_vertices, const Eigen::MatrixXi& F);

// Undirected edges used by exactly one face (holes) / by more than two faces (non-manifold).
int boundary_edge_count(const Eigen::MatrixXi& F);
int non_manifold_edge_count(const Eigen::MatrixXi& F);
// Edges shared by two faces that traverse it in the same direction (inconsistent orientation).
int inconsistent_edge_count(const Eigen::MatrixXi& F);
// Every edge used by exactly two faces, in opposite directions; false for an empty F.
bool is_closed(const Eigen::MatrixXi& F);

// Vertices lying within `tol` (Euclidean) of an earlier vertex; tol = 0 counts exact copies.
int duplicate_vertex_count(const Eigen::MatrixXd& V, double tol = 0.0);
// Faces with a repeated vertex index, or with area <= rel_eps * (bounding box diagonal)^2.
int degenerate_face_count(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, double rel_eps = 1e-14);

// Enclosed volume by the divergence theorem: positive for a closed, outward (counter-clockwise)
// oriented surface, negative when it is inside out. Meaningful only when is_closed(F).
double signed_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);
// is_closed(F) with positive signed volume: seen from outside, only front faces are ever visible.
bool is_closed_outward(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// Vertices joined by an edge of any element (triangles or tets: every pair within a row), as a symmetric
// adjacency list over num_vertices, each list sorted without duplicates.
std::vector<std::vector<int>> vertex_neighbours(const Eigen::MatrixXi& elements, int num_vertices);

// Tet meshes: triangles on exactly one tet, oriented outward for positively oriented tets.
Eigen::MatrixXi tet_boundary_faces(const Eigen::MatrixXi& T);
// Those faces as a surface compacted to the vertices they use (in order of first use); `to_tet` maps
// each surface vertex back to its tet vertex.
TriMesh tet_boundary_surface(const TetMesh& tets, Eigen::VectorXi* to_tet = nullptr);
// Tets with signed volume <= 0.
int non_positive_tet_count(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T);
// Sum of tet volumes (signed).
double tet_mesh_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T);

}  // namespace dfm
