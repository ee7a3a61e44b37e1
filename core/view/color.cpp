#include "core/view/color.h"

#include <cmath>

namespace dfm::view {

Eigen::Vector3d hsv_to_rgb(double h_deg, double s, double v) {
  double h = std::fmod(h_deg, 360.0);
  if (h < 0) h += 360.0;
  h /= 60.0;
  const int i = static_cast<int>(h) % 6;
  const double f = h - std::floor(h);
  const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  switch (i) {
    case 0: return {v, t, p};
    case 1: return {q, v, p};
    case 2: return {p, v, t};
    case 3: return {p, q, v};
    case 4: return {t, p, v};
    default: return {v, p, q};
  }
}

Eigen::Vector3f display_to_linear(const Eigen::Vector3f& c) {
  const Eigen::Vector3d d = c.cast<double>();
  return Eigen::Vector3d(std::pow(d.x(), kDisplayGamma), std::pow(d.y(), kDisplayGamma), std::pow(d.z(), kDisplayGamma))
      .cast<float>();
}

Eigen::Vector3f linear_to_display(const Eigen::Vector3f& c) {
  const Eigen::Vector3d d = c.cast<double>();
  const double g = 1.0 / kDisplayGamma;
  return Eigen::Vector3d(std::pow(d.x(), g), std::pow(d.y(), g), std::pow(d.z(), g)).cast<float>();
}

double golden_hue(int index, double skip_lo, double skip_hi) {
  const double band = skip_hi - skip_lo;
  return std::fmod(skip_hi + std::fmod(0.08 + 0.618033988749895 * index, 1.0) * (360.0 - band), 360.0);
}

}  // namespace dfm::view
