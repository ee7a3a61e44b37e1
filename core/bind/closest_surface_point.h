#pragma once
// Closest points on a triangle surface, as barycentric samples (a point's value is the blend of its
// triangle's three vertex values): the weight mirror reads the weights at each vertex's reflection.
#include <array>
#include <memory>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

namespace dfm {

struct SurfaceSample {
  std::array<int, 3> vertex{{-1, -1, -1}};  // -1 in vertex[0]: nothing within the search distance
  std::array<double, 3> weight{{0, 0, 0}};  // barycentric, >= 0, summing to 1; a coordinate below 1e-9
                                            // is snapped to 0 (a point on a vertex reads that vertex exactly)
  double distance = 0;
  bool found() const { return vertex[0] >= 0; }
};

// Closest point of triangle (a, b, c) to p as barycentric coordinates (Ericson, Real-Time Collision
// Detection, 5.1.5: the Voronoi regions of the vertices, edges and face).
Eigen::Vector3d closest_point_barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c);

// A uniform grid of the triangles' bounding boxes, with cells no smaller than max_distance, so a query
// visits at most 27 cells and finds the closest point exactly whenever it lies within max_distance.
class SurfaceLocator {
 public:
  SurfaceLocator(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, double max_distance);
  SurfaceSample closest(const Eigen::Vector3d& p) const;

 private:
  long long key(long long x, long long y, long long z) const;
  const Eigen::MatrixXd& V_;
  const Eigen::MatrixXi& F_;
  double max_distance_, cell_;
  Eigen::Vector3d origin_;
  std::unordered_map<long long, std::vector<int>> cells_;
};

// The same query by a bounding-volume tree of the triangles (CGAL's AABB tree): logarithmic at any
// distance, where the grid's cells grow with max_distance (weight transfer searches 5% of the
// diagonal). Queries may run on several threads at once. Of triangles equally near, the tree's choice.
class SurfaceTree {
 public:
  SurfaceTree(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, double max_distance);
  ~SurfaceTree();
  SurfaceSample closest(const Eigen::Vector3d& p) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dfm
