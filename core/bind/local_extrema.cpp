#include "core/bind/local_extrema.h"

#include <algorithm>
#include <string>

#include "core/util/error.h"

namespace dfm {

LocalExtrema count_local_extrema(const std::vector<std::vector<int>>& nb, const Eigen::MatrixXd& W,
                                 const std::vector<char>& fixed) {
  const int n = static_cast<int>(W.rows());
  if (static_cast<int>(nb.size()) != n || (!fixed.empty() && static_cast<int>(fixed.size()) != n))
    throw Error("local extrema: " + std::to_string(nb.size()) + " neighbour lists and " +
                std::to_string(fixed.size()) + " handle flags for " + std::to_string(n) + " vertices");
  LocalExtrema out;
  std::vector<int> plateau(n), stack;
  for (int j = 0; j < W.cols(); ++j) {
    int maxima = 0, minima = 0;
    std::fill(plateau.begin(), plateau.end(), -1);
    for (int s = 0; s < n; ++s) {
      if (plateau[s] >= 0) continue;
      const double v = W(s, j);
      bool on_handle = false, higher = false, lower = false;
      plateau[s] = s;
      stack.assign(1, s);
      while (!stack.empty()) {
        const int i = stack.back();
        stack.pop_back();
        on_handle = on_handle || (!fixed.empty() && fixed[i]);
        for (int k : nb[i]) {
          const double w = W(k, j);
          if (w == v) {
            if (plateau[k] < 0) plateau[k] = s, stack.push_back(k);
          } else {
            (w > v ? higher : lower) = true;
          }
        }
      }
      if (on_handle) continue;
      maxima += !higher && lower;
      minima += !lower && higher;
    }
    out.maxima_per_column.push_back(maxima);
    out.minima_per_column.push_back(minima);
    out.maxima += maxima;
    out.minima += minima;
  }
  return out;
}

}  // namespace dfm
