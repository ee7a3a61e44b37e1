#include "core/scene/brush.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/util/error.h"

namespace dfm {

double brush_weight(double distance, double radius, double falloff) {
  if (distance > radius) return 0.0;
  const double inner = (1.0 - falloff) * radius;
  if (distance <= inner) return 1.0;
  const double u = (distance - inner) / std::max(1e-12, radius - inner);
  return 1.0 - u * u * (3 - 2 * u);
}

BrushDab brush_dab(const Eigen::MatrixXd& V, const Eigen::VectorXd& current, const Eigen::Vector3d& center,
                   const Brush& brush) {
  if (!(brush.radius > 0)) throw Error("brush radius must be > 0");
  if (!(brush.strength >= 0 && brush.strength <= 1)) throw Error("brush strength must be in [0, 1]");
  if (!(brush.falloff >= 0 && brush.falloff <= 1)) throw Error("brush falloff must be in [0, 1]");
  if (current.size() != 0 && current.size() != V.rows())
    throw Error("brush: the mask has " + std::to_string(current.size()) + " values for " + std::to_string(V.rows()) +
                " vertices");
  BrushDab dab;
  for (int v = 0; v < V.rows(); ++v) {
    const double f = brush_weight((V.row(v).transpose() - center).norm(), brush.radius, brush.falloff);
    if (f <= 0) continue;
    const double cur = current.size() ? current[v] : 0.0;
    double value = 0;
    switch (brush.mode) {
      case BrushMode::Set: value = f >= 1 ? brush.strength : cur + f * (brush.strength - cur); break;
      case BrushMode::Add: value = cur + 0.25 * brush.strength * f; break;
      case BrushMode::Erase: value = cur - 0.25 * brush.strength * f; break;
    }
    dab.vertices.push_back(v);
    dab.values.push_back(std::clamp(value, 0.0, 1.0));
  }
  return dab;
}

}  // namespace dfm
