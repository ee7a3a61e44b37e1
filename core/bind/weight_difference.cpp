#include "core/bind/weight_difference.h"

#include <string>

#include "core/util/error.h"

namespace dfm {

Eigen::VectorXd weight_difference(const Eigen::MatrixXd& W, const Eigen::MatrixXd& R, int handle) {
  if (W.rows() != R.rows() || W.cols() != R.cols())
    throw Error("weight difference: weights are " + std::to_string(W.rows()) + " x " + std::to_string(W.cols()) +
                " and " + std::to_string(R.rows()) + " x " + std::to_string(R.cols()));
  if (handle >= W.cols()) throw Error("weight difference: no handle " + std::to_string(handle));
  if (handle >= 0) return (W.col(handle) - R.col(handle)).cwiseAbs();
  return 0.5 * (W - R).cwiseAbs().rowwise().sum();
}

}  // namespace dfm
