#pragma once
// The paint brush's kernel: what one dab does to the shape-preservation mask (or which vertices it
// adds to / removes from a region). The editor's Paint tool and the script's paint-mask / paint-dab
// call it, so a script reproduces a user's strokes exactly.
//
// A dab reaches the vertices within `radius` of its centre: full strength within (1 - falloff) * radius,
// then a smoothstep down to zero at the rim.
#include <vector>

#include <Eigen/Core>

namespace dfm {

enum class BrushMode {
  Set,    // value -> strength (blended toward it by the falloff)
  Add,    // value += strength / 4 (a stroke of several dabs builds up), clamped to [0, 1]
  Erase,  // value -= strength / 4, clamped to [0, 1]
};

struct Brush {
  double radius = 0;    // world units, > 0
  double strength = 1;  // [0, 1]
  double falloff = 0;   // [0, 1]: the outer fraction of the radius over which the dab fades out
  BrushMode mode = BrushMode::Set;
};

// The dab's weight at `distance` from its centre, in [0, 1].
double brush_weight(double distance, double radius, double falloff);

struct BrushDab {
  std::vector<int> vertices;   // those with a positive weight, in index order
  std::vector<double> values;  // their new mask values
};

// current: the mask on V's vertices (empty = all 0). Throws dfm::Error for a radius <= 0, a strength or
// falloff outside [0, 1], or a current mask of the wrong size.
BrushDab brush_dab(const Eigen::MatrixXd& V, const Eigen::VectorXd& current, const Eigen::Vector3d& center,
                   const Brush& brush);

}  // namespace dfm
