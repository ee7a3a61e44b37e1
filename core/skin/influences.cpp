#include "core/skin/influences.h"

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include "core/util/error.h"

namespace dfm {

Influences top_influences(const Eigen::MatrixXd& W, int k, bool renormalize) {
  if (k < 1) throw Error("number of influences must be at least 1, got " + std::to_string(k));
  const int n = static_cast<int>(W.rows()), h = static_cast<int>(W.cols());
  Influences inf;
  inf.index.setZero(n, k);
  inf.weight.setZero(n, k);
  const int keep = std::min(k, h);
  std::vector<int> order(h);
  for (int i = 0; i < n; ++i) {
    std::iota(order.begin(), order.end(), 0);
    std::partial_sort(order.begin(), order.begin() + keep, order.end(), [&](int a, int b) {
      return W(i, a) > W(i, b) || (W(i, a) == W(i, b) && a < b);
    });
    double sum = 0;
    for (int j = 0; j < keep; ++j) {
      inf.index(i, j) = order[j];
      inf.weight(i, j) = W(i, order[j]);
      sum += W(i, order[j]);
    }
    if (renormalize && sum > 0)
      for (int j = 0; j < keep; ++j) inf.weight(i, j) /= sum;
  }
  return inf;
}

Influences all_influences(const Eigen::MatrixXd& W) {
  return top_influences(W, std::max<int>(1, static_cast<int>(W.cols())), false);
}

Eigen::MatrixXd influences_to_dense(const Influences& inf, int num_handles) {
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(inf.num_vertices(), num_handles);
  for (int i = 0; i < inf.num_vertices(); ++i)
    for (int j = 0; j < inf.k(); ++j) {
      const int h = inf.index(i, j);
      if (h < 0 || h >= num_handles) throw Error("influence handle " + std::to_string(h) + " out of range");
      W(i, h) += inf.weight(i, j);
    }
  return W;
}

Eigen::MatrixXd gather_by_influence(const Influences& inf, const Eigen::MatrixXd& per_handle) {
  if (per_handle.rows() != inf.num_vertices())
    throw Error("per-handle data has " + std::to_string(per_handle.rows()) + " rows for " +
                std::to_string(inf.num_vertices()) + " vertices");
  Eigen::MatrixXd out(inf.num_vertices(), inf.k());
  for (int i = 0; i < inf.num_vertices(); ++i)
    for (int j = 0; j < inf.k(); ++j) {
      const int h = inf.index(i, j);
      if (h < 0 || h >= per_handle.cols()) throw Error("influence handle " + std::to_string(h) + " out of range");
      out(i, j) = per_handle(i, h);
    }
  return out;
}

SparseInfluences sparse_influences(const Influences& inf, const Eigen::MatrixXd& E) {
  const int n = inf.num_vertices(), k = inf.k();
  if (E.size() && (E.rows() != n || E.cols() != k))
    throw Error("sparse influences: endpoint weights are " + std::to_string(E.rows()) + " x " +
                std::to_string(E.cols()) + " for " + std::to_string(n) + " x " + std::to_string(k) + " influences");
  SparseInfluences s;
  s.offsets.reserve(static_cast<size_t>(n) + 1);
  s.offsets.push_back(0);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < k; ++j) {
      const double w = inf.weight(i, j);
      if (w == 0) continue;
      if (inf.index(i, j) < 0) throw Error("sparse influences: negative handle index at vertex " + std::to_string(i));
      s.handle.push_back(inf.index(i, j));
      s.weight.push_back(w);
      s.endpoint.push_back(E.size() ? E(i, j) : 0.0);
    }
    s.offsets.push_back(s.num_entries());
    s.max_row = std::max(s.max_row, s.offsets[i + 1] - s.offsets[i]);
  }
  return s;
}

}  // namespace dfm
