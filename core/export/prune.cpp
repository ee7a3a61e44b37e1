#include "core/export/prune.h"

#include <cmath>
#include <string>

#include "core/util/error.h"

namespace dfm {

Influences prune_for_export(const Eigen::MatrixXd& W, int k) {
  if (k < 1) throw Error("influence pruning: k must be at least 1, got " + std::to_string(k));
  if (W.cols() < 1) throw Error("influence pruning: weight matrix has no columns");
  if (!W.allFinite()) throw Error("influence pruning: weights contain a non-finite value");
  Influences inf = top_influences(W.cwiseMax(0.0), k, true);
  for (int v = 0; v < inf.num_vertices(); ++v) {
    if (inf.weight.row(v).sum() <= 0) {
      int best = 0;
      for (int h = 1; h < W.cols(); ++h)
        if (std::abs(W(v, h)) > std::abs(W(v, best))) best = h;
      inf.weight.row(v).setZero();
      inf.index.row(v).setZero();
      inf.weight(v, 0) = 1.0;
      inf.index(v, 0) = best;
    }
    for (int j = 0; j < inf.k(); ++j)
      if (inf.weight(v, j) <= 0) inf.weight(v, j) = 0, inf.index(v, j) = 0;
  }
  return inf;
}

}  // namespace dfm
