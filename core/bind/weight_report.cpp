#include "core/bind/weight_report.h"

#include <cmath>

#include "core/util/error.h"

namespace dfm {

std::vector<ZeroWeightHandle> zero_weight_report(const Eigen::MatrixXd& W, const Rig& rig, double threshold) {
  if (W.cols() != num_handles(rig))
    throw Error("weights have " + std::to_string(W.cols()) + " columns for " + std::to_string(num_handles(rig)) + " handles");
  if (!std::isfinite(threshold)) throw Error("weight report: the threshold is not finite");
  std::vector<ZeroWeightHandle> out;
  for (int h = 0; h < W.cols(); ++h) {
    const double m = W.rows() ? W.col(h).maxCoeff() : 0.0;
    if (m < threshold) out.push_back({h, handle_name(rig, h), m});
  }
  return out;
}

}  // namespace dfm
