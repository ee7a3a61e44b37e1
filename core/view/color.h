#pragma once
// Colour formulas the viewport and the panels share: HSV to RGB, the display gamma (2.2) both ways, and
// the golden-ratio hue sequence that gives every handle its own colour.
#include <Eigen/Core>

namespace dfm::view {

constexpr double kDisplayGamma = 2.2;

// h in degrees (any value, wrapped to [0, 360)), s and v in [0, 1]; RGB in [0, 1].
Eigen::Vector3d hsv_to_rgb(double h_deg, double s, double v);
// A display (gamma-encoded) colour to linear, and back: c^2.2 and c^(1/2.2) per channel.
Eigen::Vector3f display_to_linear(const Eigen::Vector3f& c);
Eigen::Vector3f linear_to_display(const Eigen::Vector3f& c);

// The index-th hue (degrees) of the golden-ratio sequence, spread over the circle outside the band
// [skip_lo, skip_hi] (degrees, skip_lo <= skip_hi; an empty band skips nothing): well separated for
// any count, and never inside the band.
double golden_hue(int index, double skip_lo, double skip_hi);

}  // namespace dfm::view
