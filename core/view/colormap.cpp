#include "core/view/colormap.h"

#include <algorithm>
#include <cstdio>

namespace dfm::view {
namespace {

// Degree-5 polynomial coefficients, lowest first, per channel.
constexpr double kTurbo[3][6] = {
    {0.13572138, 4.61539260, -42.66032258, 132.13108234, -152.94239396, 59.28637943},
    {0.09140261, 2.19418839, 4.84296658, -14.18503333, 4.27729857, 2.82956604},
    {0.10667330, 12.64194608, -60.58204836, 110.36276771, -89.90310912, 27.34824973},
};

}  // namespace

Eigen::Vector3d turbo(double x) {
  x = std::clamp(x, 0.0, 1.0);
  Eigen::Vector3d c;
  for (int ch = 0; ch < 3; ++ch) {
    double v = 0;
    for (int k = 5; k >= 0; --k) v = v * x + kTurbo[ch][k];  // Horner
    c[ch] = v;
  }
  return c;
}

std::vector<std::string> turbo_shader_defines() {
  std::vector<std::string> out;
  const char* names[3] = {"TURBO_R", "TURBO_G", "TURBO_B"};
  char buf[160];
  for (int ch = 0; ch < 3; ++ch) {
    const double* k = kTurbo[ch];
    std::snprintf(buf, sizeof buf, "%s vec4(%.8f, %.8f, %.8f, %.8f)", names[ch], k[0], k[1], k[2], k[3]);
    out.push_back(buf);
    std::snprintf(buf, sizeof buf, "%s2 vec2(%.8f, %.8f)", names[ch], k[4], k[5]);
    out.push_back(buf);
  }
  return out;
}

}  // namespace dfm::view
