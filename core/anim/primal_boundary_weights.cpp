#include "core/anim/primal_boundary_weights.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "core/util/error.h"

namespace dfm {

Eigen::VectorXd project_shifted_simplex(const Eigen::VectorXd& y, double xi) {
  // w = xi + u, u on the simplex of mass 1 - k xi (Duchi et al. 2008's sort-based projection).
  const int k = static_cast<int>(y.size());
  const double mass = 1 - k * xi;
  Eigen::VectorXd z = y.array() - xi;
  std::vector<double> s(z.data(), z.data() + k);
  std::sort(s.begin(), s.end(), std::greater<double>());
  double cum = 0, theta = 0;
  for (int i = 0; i < k; ++i) {
    cum += s[i];
    const double t = (cum - mass) / (i + 1);
    if (s[i] - t > 0) theta = t;
  }
  return (z.array() - theta).max(0.0) + xi;
}

Eigen::VectorXd primal_boundary_weights(const Eigen::Vector4d& v, const Eigen::MatrixXd& N, const Eigen::VectorXd& w0,
                                        const PrimalWeightOptions& o) {
  const int k = static_cast<int>(N.rows());
  if (k == 0) throw Error("primal boundary weights: the vertex has no neighbours");
  if (!(o.xi >= 0 && o.xi * k < 1)) throw Error("primal boundary weights: xi must be in [0, 1 / #neighbours)");
  // With sum w = 1, v - sum w_j v_j = -sum w_j (v_j - v): edges relative to v keep Q well scaled.
  // f(w) = |E^T w|^2 + eps |w - w0|^2,  grad = 2 Q w + 2 eps (w - w0),  Q = E E^T (k x k).
  const Eigen::MatrixXd E = N.rowwise() - v.transpose();
  const Eigen::MatrixXd Q = E * E.transpose();
  const double eps = o.proximal * std::max(Q.trace() / k, 1e-300);
  const double L = 2 * (Q.trace() + eps);  // >= the gradient's Lipschitz constant
  Eigen::VectorXd w = project_shifted_simplex(w0, o.xi), y = w;
  double tk = 1;
  for (int it = 0; it < o.iterations; ++it) {
    const Eigen::VectorXd g = 2 * (Q * y) + 2 * eps * (y - w0);
    const Eigen::VectorXd next = project_shifted_simplex(y - g / L, o.xi);
    const double tn = 0.5 * (1 + std::sqrt(1 + 4 * tk * tk));
    y = next + ((tk - 1) / tn) * (next - w);
    w = next;
    tk = tn;
  }
  return w;
}

}  // namespace dfm
