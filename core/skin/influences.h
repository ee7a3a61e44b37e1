#pragma once
// Per-vertex influences: handle indices and weights, sorted largest first. Either every weight (the
// exact reference, and what the GPU skins by default, as sparse rows) or the k largest (glTF's 4 or
// 8, `deform pose -k 4|8`).
#include <vector>

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

// Every nonzero influence in compressed sparse rows (the GPU skinning layout): row i is entries
// offsets[i] .. offsets[i + 1] - 1, in influence order (largest weight first, so entry offsets[i]
// is the DQS sign-fix pivot). Zero weights are dropped; a row may be empty.
struct SparseInfluences {
  std::vector<int> offsets;       // #V + 1, offsets[0] = 0
  std::vector<int> handle;        // one per entry
  std::vector<double> weight;     // one per entry
  std::vector<double> endpoint;   // one per entry: STBS endpoint weight (0 when none given)
  int max_row = 0;                // the most entries in one row
  int num_entries() const { return static_cast<int>(handle.size()); }
};

// E: #V x k endpoint weights in influence order, or empty (zeros). Throws dfm::Error on a size
// mismatch or a negative handle index.
SparseInfluences sparse_influences(const Influences& inf, const Eigen::MatrixXd& E = {});

}  // namespace dfm
