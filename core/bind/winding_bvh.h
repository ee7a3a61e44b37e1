#pragma once
// Hierarchical generalized winding numbers (Barill et al. 2018, "Fast Winding Numbers for Soups and
// Clouds"): a bounding-volume tree over the triangles; a node far from the query point (distance >
// beta * its radius) is replaced by a second-order Taylor expansion of its dipole field, near nodes are
// opened and leaves summed exactly with solid angles. Cost ~O(log #F) per query instead of O(#F).
#include <vector>

#include <Eigen/Core>

namespace dfm {

struct WindingTree {
  struct Node {
    Eigen::Vector3d center;  // area-weighted centroid of its triangles (expansion point)
    double radius = 0;       // max distance from center to any of its triangles' corners
    double area = 0;         // total triangle area (bounds the truncation error)
    Eigen::Vector3d N;       // sum of area vectors a_t n_t (zeroth order)
    Eigen::Matrix3d M;       // sum (a_t n_t) (centroid_t - center)^T (first order)
    Eigen::Matrix3d H[3];    // H[i] = sum (a_t n_t)_i * int_t d d^T / a_t (second order)
    int begin = 0, end = 0;  // triangle range (in tri order)
    int left = -1, right = -1;
  };
  std::vector<Node> nodes;              // nodes[0] is the root
  std::vector<Eigen::Vector3d> a, b, c;  // triangle corners in tree order
  int leaf_size = 8;
};

WindingTree build_winding_tree(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int leaf_size = 8);

// A node is expanded only when the query is farther than beta * its radius and the estimated
// truncation error, area * radius^3 / (4 pi distance^5) (the size of the dropped third-order term),
// is below node_tolerance. The defaults keep |tree - direct| below 1e-4 on the test meshes.
struct WindingAccuracy {
  double beta = 2.0;
  double node_tolerance = 2e-5;
};
double winding_number(const WindingTree& tree, const Eigen::Vector3d& p, const WindingAccuracy& acc = {});
Eigen::VectorXd winding_numbers(const WindingTree& tree, const Eigen::MatrixXd& P, const WindingAccuracy& acc = {},
                                int threads = 0);

}  // namespace dfm
