#include "core/bind/weight_smooth.h"

#include <string>

#include <Eigen/Sparse>

#include "core/bind/surface_laplacian.h"
#include "core/bind/weight_normalize.h"
#include "core/util/error.h"

namespace dfm {

Eigen::MatrixXd smooth_weights(const Eigen::MatrixXd& W, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                               const std::vector<int>& locked, const std::vector<bool>& fixed,
                               const SmoothOptions& opts) {
  if (opts.iterations < 0 || opts.iterations > 1000)
    throw Error("smooth: iterations must be in 0..1000 (got " + std::to_string(opts.iterations) + ")");
  if (!(opts.factor > 0 && opts.factor <= 1)) throw Error("smooth: factor must be in (0, 1]");
  if (W.rows() != V.rows())
    throw Error("weights have " + std::to_string(W.rows()) + " rows for " + std::to_string(V.rows()) + " vertices");
  if (!fixed.empty() && fixed.size() != static_cast<size_t>(W.rows()))
    throw Error("fixed-row flags: " + std::to_string(fixed.size()) + " for " + std::to_string(W.rows()) + " rows");
  const std::vector<bool> lock = locked_flags(locked, static_cast<int>(W.cols()));
  const int nv = static_cast<int>(V.rows());
  const Eigen::SparseMatrix<double> K = opts.cotangent ? surface_cotangent_stiffness(V, F) : uniform_stiffness(nv, F);
  // The step is W - factor D^-1 K W on the free rows and unlocked columns (D = diag K).
  Eigen::VectorXd step = Eigen::VectorXd::Zero(nv);
  for (int i = 0; i < nv; ++i) {
    const double d = K.coeff(i, i);
    if (d > 0 && (fixed.empty() || !fixed[i])) step(i) = opts.factor / d;
  }
  std::vector<int> unlocked;
  for (int j = 0; j < W.cols(); ++j)
    if (!lock[j]) unlocked.push_back(j);
  Eigen::MatrixXd out = W;
  for (int it = 0; it < opts.iterations; ++it) {
    for (int j : unlocked) {
      const Eigen::VectorXd g = K * out.col(j);
      out.col(j) -= step.cwiseProduct(g);
    }
    out = normalize_locked(out, locked, fixed);
  }
  return out;
}

}  // namespace dfm
