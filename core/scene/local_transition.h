#pragma once
// Local transitions on a document's keys (issue 37; Alexa 2002, 4.3): per-vertex transition-state
// offsets painted on an interval between two mesh keys of one connectivity, so one region arrives at
// the next key early (offset > 0) or late (< 0). The in-betweens read them (key_surfaces.cpp through
// differential_blend.h); the brush and the script's transition-state go through transition_dab.
#include <vector>

#include <Eigen/Core>

#include "core/scene/document.h"

namespace dfm {

// The interval (its first key's index) holding time t, checked for a local transition: both keys mesh
// keys with one triangle list. Throws dfm::Error saying what is missing.
int transition_interval(const Document& doc, double t);

struct TransitionDab {
  std::vector<int> vertices;   // those the dab reaches, in index order
  std::vector<double> values;  // their new offsets
};

// One dab on interval `index`'s offsets: each vertex of the interval's first key within `radius` of
// `center` moves toward `value` by brush_weight (brush.h: all the way inside (1 - falloff) * radius).
// Throws dfm::Error for a value outside (-1, 1), a radius <= 0, a falloff outside [0, 1] or a centre
// with no vertex in reach.
TransitionDab transition_dab(const Document& doc, int index, double value, const Eigen::Vector3d& center, double radius,
                             double falloff = 0);

// The offsets of interval `index` as the in-betweens use them: the key's, or zeros (#V of the key).
Eigen::VectorXd transition_offsets(const Document& doc, int index);

}  // namespace dfm
