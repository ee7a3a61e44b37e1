#pragma once
// Red-green refinement of a triangle list (Bank, Sherman and Weiser 1983): the marked ("red")
// triangles split 1:4 at their edges' middles; a triangle with two split edges turns red too (repeated
// until none does), and one with a single split edge is bisected ("green"), so the result has no hanging
// vertex. Orientation is kept. Used by space-time refinement (core/anim/manifold_refine.h).
#include <array>
#include <vector>

#include <Eigen/Core>

namespace dfm {

struct RedGreenRefinement {
  Eigen::MatrixXi F;                       // the refined triangles
  std::vector<std::array<int, 2>> middles;  // new vertex num_vertices + i is the middle of edge middles[i]
};

// F: #F x 3 over vertices 0..num_vertices-1; red: #F flags. Throws dfm::Error for a size mismatch or an
// index out of range.
RedGreenRefinement red_green_refine(const Eigen::MatrixXi& F, int num_vertices, std::vector<char> red);

// Positions for the refined list: V's rows followed by each middle's edge midpoint.
Eigen::MatrixXd append_middles(const Eigen::MatrixXd& V, const std::vector<std::array<int, 2>>& middles);

}  // namespace dfm
