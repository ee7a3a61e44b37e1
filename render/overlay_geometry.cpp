#include "render/overlay_geometry.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace dfm::gl {

double nice_spacing(double extent, int lines) {
  if (!(extent > 0) || lines <= 0) return 1.0;
  const double raw = extent / lines;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10.0 * p;
}

std::vector<OverlayVertex> grid_lines(double cx, double cz, double height, double half_extent,
                                      double spacing) {
  std::vector<OverlayVertex> out;
  if (!(spacing > 0) || !(half_extent > 0)) return out;
  // Snap to the spacing so lines stay put when the centre moves.
  const long i0 = static_cast<long>(std::floor((cx - half_extent) / spacing));
  const long i1 = static_cast<long>(std::ceil((cx + half_extent) / spacing));
  const long j0 = static_cast<long>(std::floor((cz - half_extent) / spacing));
  const long j1 = static_cast<long>(std::ceil((cz + half_extent) / spacing));
  auto fade = [&](double x, double z) {
    const double r = std::hypot(x - cx, z - cz) / (half_extent * 1.05);
    return static_cast<float>(std::clamp(1.0 - r * r, 0.0, 1.0));
  };
  // Each line is split in segments so the fade follows the distance from the centre.
  auto add_line = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, Eigen::Vector4f c) {
    const int n = 16;
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d p = a + (b - a) * (double(k) / n), q = a + (b - a) * (double(k + 1) / n);
      Eigen::Vector4f cp = c, cq = c;
      cp[3] *= fade(p.x(), p.z());
      cq[3] *= fade(q.x(), q.z());
      if (cp[3] <= 0 && cq[3] <= 0) continue;
      out.push_back(overlay_vertex(p, cp));
      out.push_back(overlay_vertex(q, cq));
    }
  };
  const Eigen::Vector4f minor(0.55f, 0.57f, 0.62f, 0.22f), major(0.62f, 0.64f, 0.70f, 0.45f);
  const Eigen::Vector4f x_axis(0.85f, 0.30f, 0.30f, 0.8f), z_axis(0.30f, 0.45f, 0.90f, 0.8f);
  for (long i = i0; i <= i1; ++i) {
    const double x = i * spacing;
    add_line({x, height, j0 * spacing}, {x, height, j1 * spacing}, i == 0 ? z_axis : (i % 5 == 0 ? major : minor));
  }
  for (long j = j0; j <= j1; ++j) {
    const double z = j * spacing;
    add_line({i0 * spacing, height, z}, {i1 * spacing, height, z}, j == 0 ? x_axis : (j % 5 == 0 ? major : minor));
  }
  return out;
}

std::vector<OverlayVertex> circle_lines(const Eigen::Vector3d& center, const Eigen::Vector3d& normal,
                                        double radius, const Eigen::Vector4f& color, int segments) {
  const Eigen::Vector3d n = normal.normalized();
  const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
  std::vector<OverlayVertex> out;
  for (int k = 0; k < segments; ++k) {
    const double a = 2 * M_PI * k / segments, b = 2 * M_PI * (k + 1) / segments;
    out.push_back(overlay_vertex(center + radius * (std::cos(a) * u + std::sin(a) * v), color));
    out.push_back(overlay_vertex(center + radius * (std::cos(b) * u + std::sin(b) * v), color));
  }
  return out;
}

}  // namespace dfm::gl
