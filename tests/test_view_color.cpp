// core/view/color: HSV, display gamma and the handles' golden-ratio hues against references written here.
#include <algorithm>
#include <cmath>

#include <catch2/catch.hpp>

#include "core/view/color.h"

using namespace dfm;

namespace {
// The textbook inverse (max/min/chroma), independent of the sector switch under test.
double hue_of(const Eigen::Vector3d& c) {
  const double mx = c.maxCoeff(), mn = c.minCoeff(), d = mx - mn;
  if (d <= 0) return -1;
  double h = mx == c.x() ? std::fmod((c.y() - c.z()) / d, 6.0) : mx == c.y() ? (c.z() - c.x()) / d + 2 : (c.x() - c.y()) / d + 4;
  h *= 60;
  return h < 0 ? h + 360 : h;
}
}  // namespace

TEST_CASE("hsv_to_rgb: primaries, and hue, saturation and value read back by the textbook inverse", "[view][color]") {
  REQUIRE((view::hsv_to_rgb(0, 1, 1) - Eigen::Vector3d(1, 0, 0)).norm() < 1e-12);
  REQUIRE((view::hsv_to_rgb(120, 1, 1) - Eigen::Vector3d(0, 1, 0)).norm() < 1e-12);
  REQUIRE((view::hsv_to_rgb(240, 1, 1) - Eigen::Vector3d(0, 0, 1)).norm() < 1e-12);
  REQUIRE((view::hsv_to_rgb(60, 1, 0.5) - Eigen::Vector3d(0.5, 0.5, 0)).norm() < 1e-12);
  REQUIRE((view::hsv_to_rgb(-120, 1, 1) - view::hsv_to_rgb(240, 1, 1)).norm() < 1e-12);  // wraps
  for (double h = 0.5; h < 360; h += 7.3) {
    for (double s : {0.2, 0.62, 1.0}) {
      const Eigen::Vector3d c = view::hsv_to_rgb(h, s, 0.92);
      INFO("h " << h << " s " << s);
      REQUIRE(c.maxCoeff() == Approx(0.92));            // value
      REQUIRE(c.minCoeff() == Approx(0.92 * (1 - s)));  // saturation
      REQUIRE(hue_of(c) == Approx(h).margin(1e-9));
    }
  }
}

TEST_CASE("display gamma: c^2.2 one way, c^(1/2.2) back", "[view][color]") {
  const Eigen::Vector3f c(0.0f, 0.5f, 1.0f);
  const Eigen::Vector3f lin = view::display_to_linear(c);
  REQUIRE(lin.x() == 0.0f);
  REQUIRE(lin.y() == Approx(0.217637640824031));  // 0.5^2.2
  REQUIRE(lin.z() == 1.0f);
  for (float x = 0.05f; x < 1.0f; x += 0.05f) {
    const Eigen::Vector3f back = view::linear_to_display(view::display_to_linear(Eigen::Vector3f::Constant(x)));
    REQUIRE(back.x() == Approx(x).epsilon(1e-6));
    REQUIRE(view::display_to_linear(Eigen::Vector3f::Constant(x)).x() < x);  // darker in linear
  }
}

TEST_CASE("golden_hue: never inside the skipped band, neighbours far apart, an empty band skips nothing", "[view][color]") {
  for (int i = 0; i < 1000; ++i) {
    const double h = view::golden_hue(i, 10, 70);
    INFO("index " << i << " hue " << h);
    REQUIRE(h >= 0);
    REQUIRE(h < 360);
    REQUIRE((h < 10 || h >= 70));
    if (i > 0) {
      const double d = std::abs(h - view::golden_hue(i - 1, 10, 70));
      REQUIRE(std::min(d, 360 - d) > 60);  // golden steps: about 0.38 of the circle apart
    }
  }
  // No band: the plain sequence 360 * frac(0.08 + i / phi).
  for (int i = 0; i < 50; ++i) {
    const double x = 0.08 + 0.618033988749895 * i;
    REQUIRE(view::golden_hue(i, 0, 0) == Approx(360 * (x - std::floor(x))).margin(1e-9));
  }
}
