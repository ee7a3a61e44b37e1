#include "core/skin/endpoint_filter.h"

#include <algorithm>
#include <cmath>

#include "core/util/error.h"

namespace dfm {

namespace {

// The knots (0, 0), the filter's points, (1, 1), with their Fritsch-Carlson tangents: built once per
// filter, evaluated per weight.
struct Curve {
  std::vector<Eigen::Vector2d> k;
  std::vector<double> m;

  explicit Curve(const EndpointFilter& f) {
    k.reserve(f.size() + 2);
    k.emplace_back(0.0, 0.0);
    k.insert(k.end(), f.begin(), f.end());
    k.emplace_back(1.0, 1.0);
    const size_t n = k.size();
    std::vector<double> d(n - 1);  // secant slopes
    m.resize(n);
    for (size_t i = 0; i + 1 < n; ++i) d[i] = (k[i + 1].y() - k[i].y()) / (k[i + 1].x() - k[i].x());
    m[0] = d[0], m[n - 1] = d[n - 2];
    for (size_t i = 1; i + 1 < n; ++i) m[i] = d[i - 1] * d[i] <= 0 ? 0.0 : 0.5 * (d[i - 1] + d[i]);
    // Tangents limited so that each piece stays monotone.
    for (size_t i = 0; i + 1 < n; ++i) {
      if (d[i] == 0) {
        m[i] = m[i + 1] = 0;
        continue;
      }
      const double a = m[i] / d[i], b = m[i + 1] / d[i], s = a * a + b * b;
      if (s > 9) {
        const double t = 3 / std::sqrt(s);
        m[i] = t * a * d[i], m[i + 1] = t * b * d[i];
      }
    }
  }

  double operator()(double e) const {
    e = std::clamp(e, 0.0, 1.0);
    size_t i = 0;
    while (i + 2 < k.size() && e > k[i + 1].x()) ++i;
    const double h = k[i + 1].x() - k[i].x(), t = (e - k[i].x()) / h;
    const double h00 = (1 + 2 * t) * (1 - t) * (1 - t), h10 = t * (1 - t) * (1 - t), h01 = t * t * (3 - 2 * t),
                 h11 = t * t * (t - 1);
    return std::clamp(h00 * k[i].y() + h10 * h * m[i] + h01 * k[i + 1].y() + h11 * h * m[i + 1], 0.0, 1.0);
  }
};

}  // namespace

void check_endpoint_filter(const EndpointFilter& f, const std::string& what) {
  double x = 0, y = 0;
  for (size_t i = 0; i < f.size(); ++i) {
    const Eigen::Vector2d& p = f[i];
    const std::string at = what + ": point " + std::to_string(i + 1);
    if (!p.allFinite()) throw Error(at + " is not finite");
    if (!(p.x() > x && p.x() < 1)) throw Error(at + ": x must increase strictly inside (0, 1)");
    if (!(p.y() >= y && p.y() <= 1)) throw Error(at + ": y must not decrease and stay in [0, 1]");
    x = p.x(), y = p.y();
  }
}

double filter_endpoint(const EndpointFilter& f, double e) {
  return f.empty() ? std::clamp(e, 0.0, 1.0) : Curve(f)(e);
}

Eigen::MatrixXd filter_endpoints(const Eigen::MatrixXd& E, const std::vector<EndpointFilter>& filters) {
  Eigen::MatrixXd out = E;
  for (Eigen::Index b = 0; b < E.cols() && b < static_cast<Eigen::Index>(filters.size()); ++b) {
    if (filters[b].empty()) continue;
    const Curve curve(filters[b]);
    for (Eigen::Index i = 0; i < E.rows(); ++i) out(i, b) = curve(E(i, b));
  }
  return out;
}

}  // namespace dfm
