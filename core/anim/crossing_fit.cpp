#include "core/anim/crossing_fit.h"

#include <algorithm>
#include <cmath>

#include "core/util/error.h"

namespace dfm {

double hermite_root(double fa, double fb, double da, double db) {
  const double slope = fb - fa;
  da = std::clamp(da, 0.0, 3 * slope);
  db = std::clamp(db, 0.0, 3 * slope);
  // Coefficients of c0 + c1 x + c2 x^2 + c3 x^3.
  const double c0 = fa, c1 = da, c2 = 3 * slope - 2 * da - db, c3 = da + db - 2 * slope;
  // Newton's steps from the linear root, kept inside the bracket by bisection.
  double lo = 0, hi = 1, x = -fa / slope;
  for (int it = 0; it < 60 && hi - lo > 1e-12; ++it) {
    const double value = c0 + x * (c1 + x * (c2 + x * c3));
    if (value == 0) return x;
    (value < 0 ? lo : hi) = x;
    const double next = x - value / (c1 + x * (2 * c2 + 3 * x * c3));
    if (std::abs(next - x) < 1e-14) return x;
    x = next > lo && next < hi ? next : (lo + hi) / 2;
  }
  return x;
}

std::vector<std::array<int, 2>> tet_edges(const MatrixX4iRow& T) {
  std::vector<std::array<int, 2>> e;
  e.reserve(6 * static_cast<size_t>(T.rows()));
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) e.push_back({std::min(T(t, i), T(t, j)), std::max(T(t, i), T(t, j))});
  std::sort(e.begin(), e.end());
  e.erase(std::unique(e.begin(), e.end()), e.end());
  return e;
}

Eigen::VectorXd fit_crossings(const Eigen::MatrixXd& X, const std::vector<std::array<int, 2>>& edges,
                              const Eigen::VectorXd& f, const Eigen::MatrixXd& G) {
  const Eigen::Index n = f.size();
  if (X.rows() != n || G.rows() != n || X.cols() != 3 || G.cols() != 3)
    throw Error("fit_crossings: one point, value and gradient per row needed");
  Eigen::VectorXd num = Eigen::VectorXd::Zero(n), den = Eigen::VectorXd::Zero(n);
  for (const auto& [p, q] : edges) {
    if (p < 0 || q < 0 || p >= n || q >= n) throw Error("fit_crossings: an edge's point is out of range");
    if ((f[p] < 0) == (f[q] < 0)) continue;
    const int a = f[p] < 0 ? p : q, b = f[p] < 0 ? q : p;  // a negative, b positive
    const Eigen::Vector3d e = (X.row(b) - X.row(a)).transpose();
    const double r = hermite_root(f[a], f[b], G.row(a).dot(e), G.row(b).dot(e));
    num[a] -= (1 - r) * r * f[b], den[a] += (1 - r) * (1 - r);
    num[b] -= r * (1 - r) * f[a], den[b] += r * r;
  }
  Eigen::VectorXd v = f;
  for (Eigen::Index i = 0; i < n; ++i)
    if (den[i] > 0) v[i] = 0.5 * (f[i] + num[i] / den[i]);
  return v;
}

}  // namespace dfm
