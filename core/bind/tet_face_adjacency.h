#pragma once
// The faces two tets share, for segmentations that couple neighbouring tets (Jacobson 2013, 8.5.1:
// N(i) in Eq. 8.8, a_ij in Eq. 8.10), and which of them lie on an input surface.
#include <vector>

#include <Eigen/Core>

#include "core/mesh/mesh.h"

namespace dfm {

struct TetFaceAdjacency {
  Eigen::MatrixXi tets;   // #A x 2: the two tets sharing a face (first < second)
  Eigen::MatrixXi faces;  // #A x 3: that face's vertices, ascending
  Eigen::VectorXd area;   // #A: its area
};

// Every face shared by exactly two tets. A face on three or more tets (not a valid tet mesh) couples
// none of them. Order: by face vertices.
TetFaceAdjacency tet_face_adjacency(const TetMesh& tets);

// Per shared face: 1 when it is one of F's triangles (#F x 3 tet-vertex indices, any order or
// orientation; rows with a negative index are skipped), else 0.
std::vector<char> shared_faces_on_surface(const TetFaceAdjacency& adj, const Eigen::MatrixXi& F);

}  // namespace dfm
