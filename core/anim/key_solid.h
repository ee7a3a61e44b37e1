#pragma once
// Which faces of a Delaunay tetrahedralization lie in the closed solid bounded by a key surface that
// conforms to it (every surface triangle is a face). Used to strip 4-simplices (Southern 2008, 8.5):
// a face is in the solid exactly when it is a face of an inside tetrahedron.
#include <array>
#include <string>
#include <unordered_set>
#include <vector>

#include <Eigen/Core>

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
  // tets: the tetrahedralization (#T x 4, indices into one point set) of the convex hull of the key's
  // points; surface: the key's outward triangles in the same indices. Inside/outside by a flood fill
  // from the hull that flips across surface triangles. Throws dfm::Error naming `what` when a surface
  // triangle is not a face of tets (`missing` receives their rows, if given, before the throw) or
  // the fill is inconsistent.
  KeySolid(const std::vector<std::array<int, 4>>& tets, const Eigen::MatrixXi& surface, const std::string& what,
           std::vector<int>* missing = nullptr);
  // True when the face (1 to 4 vertices) lies in the closed solid. A single vertex always does.
  bool contains(const int* vertices, int count) const;
  // True when the triangle is one of the key surface's triangles.
  bool on_surface(const int* vertices) const { return surface_.count(simplex_key(vertices, 3)) > 0; }
  int num_inside_tets() const { return inside_tets_; }

 private:
  std::unordered_set<SimplexKey, SimplexKeyHash> inside_;  // edges, triangles and tets of inside tets
  std::unordered_set<SimplexKey, SimplexKeyHash> surface_;
  int inside_tets_ = 0;
};

}  // namespace dfm
