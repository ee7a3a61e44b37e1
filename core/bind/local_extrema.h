#pragma once
// Spurious local extrema of weight functions on a vertex graph (Jacobson 2013, 5.3: a weight should
// have its maxima and minima only on the handles). Plateau-aware: vertices of exactly equal value joined
// by edges form one plateau; a plateau with no fixed (handle) vertex whose every outside neighbour is
// lower is a local maximum, every one higher a local minimum.
#include <vector>

#include <Eigen/Core>

namespace dfm {

struct LocalExtrema {
  int maxima = 0, minima = 0;            // over all columns
  std::vector<int> maxima_per_column, minima_per_column;
};

// neighbours: symmetric adjacency over W's rows; fixed: per row, on a handle (empty = none).
LocalExtrema count_local_extrema(const std::vector<std::vector<int>>& neighbours, const Eigen::MatrixXd& W,
                                 const std::vector<char>& fixed);

}  // namespace dfm
