#include "core/bind/weight_normalize.h"

#include <algorithm>
#include <string>

#include "core/util/error.h"

namespace dfm {

std::vector<bool> locked_flags(const std::vector<int>& locked, int num_handles) {
  std::vector<bool> f(num_handles, false);
  for (int h : locked) {
    if (h < 0 || h >= num_handles)
      throw Error("no handle " + std::to_string(h) + " to lock (there are " + std::to_string(num_handles) + ")");
    f[h] = true;
  }
  return f;
}

Eigen::MatrixXd normalize_locked(const Eigen::MatrixXd& W, const std::vector<int>& locked,
                                 const std::vector<bool>& fixed, NormalizeReport* report) {
  if (!fixed.empty() && fixed.size() != static_cast<size_t>(W.rows()))
    throw Error("fixed-row flags: " + std::to_string(fixed.size()) + " for " + std::to_string(W.rows()) + " rows");
  const std::vector<bool> lock = locked_flags(locked, static_cast<int>(W.cols()));
  NormalizeReport rep;
  Eigen::MatrixXd out = W;
  for (int i = 0; i < W.rows(); ++i) {
    if (!fixed.empty() && fixed[i]) continue;
    double L = 0, U = 0;
    for (int j = 0; j < W.cols(); ++j) lock[j] ? L += W(i, j) : U += std::max(0.0, W(i, j));
    if (L >= 1) {
      if (L > 1 + 1e-12) ++rep.rows_locked_over_one;
      for (int j = 0; j < W.cols(); ++j)
        if (!lock[j]) out(i, j) = 0;
      continue;
    }
    if (!(U > 0)) {
      ++rep.rows_without_free_weight;
      continue;
    }
    const double scale = (1 - L) / U;
    for (int j = 0; j < W.cols(); ++j)
      if (!lock[j]) out(i, j) = std::max(0.0, W(i, j)) * scale;
    if (out.row(i) != W.row(i)) ++rep.rows_scaled;
  }
  if (report) *report = rep;
  return out;
}

}  // namespace dfm
