#pragma once
// Which faces of a key's Delaunay tetrahedralization lie in the closed solid the key surface bounds,
// for stripping 4-simplices (Southern 2008, 8.5): a face is in the solid exactly when it is a face of
// an inside tetrahedron. Where every surface triangle is a face of the tetrahedra, inside is exact (a
// flood fill that flips across the surface); otherwise the generalized winding number of the surface
// at each tetrahedron's centroid decides (Jacobson 2013, ch. 8), which stays right where the surface
// could not be made fully conforming and a tetrahedron crosses it.
#include <array>
#include <unordered_set>
#include <vector>

#include <Eigen/Core>

#include "core/anim/manifold.h"
#include "core/mesh/mesh.h"

namespace dfm {

struct SimplexKeyHash {
  size_t operator()(const std::array<int, 4>& k) const {
    size_t h = 0;
    for (int v : k) h = h * 0x9E3779B97F4A7C15ull + static_cast<size_t>(v) + 0x7F4A7C15u;
    return h;
  }
};

// A face given by its sorted vertex indices, unused trailing entries -1.
using SimplexKey = std::array<int, 4>;
SimplexKey simplex_key(const int* vertices, int count);

class KeySolid {
 public:
  // tets: the key's tetrahedra (indices into P, whose first 3 columns are positions); surface: the
  // key's closed, outward surface; surface_in_P: its triangles in P's indices.
  KeySolid(const std::vector<std::array<int, 4>>& tets, const MatrixX4dRow& P, const TriMesh& surface,
           const Eigen::MatrixXi& surface_in_P);
  bool exact() const { return exact_; }
  // True when the face (1 to 4 vertices) lies in the closed solid. A single vertex always does (every
  // key point is on its surface).
  bool contains(const int* vertices, int count) const;
  int num_inside_tets() const { return inside_tets_; }

 private:
  std::unordered_set<SimplexKey, SimplexKeyHash> inside_;  // edges, triangles and tets of inside tets
  int inside_tets_ = 0;
  bool exact_ = false;
};

}  // namespace dfm
