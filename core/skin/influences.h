#pragma once
// Per-vertex influences: the k handles with the largest weights (sorted, largest first) and their
// weights. The GPU keeps k = 4 or 8 per vertex; the CPU reference keeps all of them.
#include <Eigen/Core>

namespace dfm {

struct Influences {
  Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> index;      // #V x k handle indices
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> weight;  // #V x k
  int k() const { return static_cast<int>(index.cols()); }
  int num_vertices() const { return static_cast<int>(index.rows()); }
};

// W: #V x #handles. Keeps the k largest weights per vertex (ties: lower handle first); with
// renormalize, the kept weights are scaled to sum to one (a vertex whose kept weights sum to <= 0 is
// left as is). When k > #handles the extra slots hold handle 0 with weight 0. Throws dfm::Error for k < 1.
Influences top_influences(const Eigen::MatrixXd& W, int k, bool renormalize = true);
// Every weight, sorted, unchanged: the exact reference.
Influences all_influences(const Eigen::MatrixXd& W);
// Back to a dense #V x num_handles matrix.
Eigen::MatrixXd influences_to_dense(const Influences& inf, int num_handles);
// Per-vertex, per-handle data (#V x #handles) gathered into influence order (#V x k).
Eigen::MatrixXd gather_by_influence(const Influences& inf, const Eigen::MatrixXd& per_handle);

}  // namespace dfm
