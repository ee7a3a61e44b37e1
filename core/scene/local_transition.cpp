#include "core/scene/local_transition.h"

#include <cmath>
#include <string>

#include "core/scene/brush.h"
#include "core/util/error.h"

namespace dfm {

int transition_interval(const Document& doc, double t) {
  const std::vector<SceneKey>& keys = doc.keys();
  if (keys.size() < 2) throw Error("a local transition needs two keys (the document has " + std::to_string(keys.size()) + ")");
  if (!std::isfinite(t)) throw Error("the time is not finite");
  if (t < keys.front().time - 1e-9 || t > keys.back().time + 1e-9)
    throw Error("time " + std::to_string(t) + " is outside the keys (" + std::to_string(keys.front().time) + " to " +
                std::to_string(keys.back().time) + ")");
  int k = 0;
  while (k + 2 < static_cast<int>(keys.size()) && keys[k + 1].time <= t + 1e-9) ++k;
  const SceneKey &a = keys[k], &b = keys[k + 1];
  if (!a.is_mesh() || !b.is_mesh())
    throw Error("a local transition runs between two mesh keys; the interval at time " + std::to_string(t) + " (keys at " +
                std::to_string(a.time) + " and " + std::to_string(b.time) + ") has a pose key");
  if (a.mesh.V.rows() != b.mesh.V.rows() || a.mesh.F != b.mesh.F)
    throw Error("the keys at " + std::to_string(a.time) + " and " + std::to_string(b.time) +
                " have different meshes: a local transition needs one connectivity");
  return k;
}

Eigen::VectorXd transition_offsets(const Document& doc, int index) {
  const SceneKey& k = doc.keys().at(static_cast<size_t>(index));
  const Eigen::Index n = k.mesh.V.rows();
  return k.transition_to_next.size() == n ? k.transition_to_next : Eigen::VectorXd::Zero(n);
}

TransitionDab transition_dab(const Document& doc, int index, double value, const Eigen::Vector3d& center, double radius,
                             double falloff) {
  if (!(value > -1 && value < 1)) throw Error("a transition offset must lie in (-1, 1), got " + std::to_string(value));
  if (!(radius > 0)) throw Error("radius must be > 0");
  if (!(falloff >= 0 && falloff <= 1)) throw Error("falloff must be in [0, 1]");
  if (!center.allFinite()) throw Error("the dab's centre is not finite");
  const Eigen::MatrixXd& V = doc.keys().at(static_cast<size_t>(index)).mesh.V;
  const Eigen::VectorXd cur = transition_offsets(doc, index);
  TransitionDab dab;
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    const double f = brush_weight((V.row(v).transpose() - center).norm(), radius, falloff);
    if (f <= 0) continue;
    dab.vertices.push_back(static_cast<int>(v));
    dab.values.push_back(f >= 1 ? value : cur[v] + f * (value - cur[v]));
  }
  if (dab.vertices.empty()) throw Error("no vertex of the key at " + std::to_string(doc.keys()[index].time) + " within " +
                                        std::to_string(radius) + " of the point");
  return dab;
}

}  // namespace dfm
