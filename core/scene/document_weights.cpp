// Document commands of the weight tools (document.h; the tools themselves are core/bind/weight_*.h).
// Each reads the current weights, runs the tool with the bind's constrained rows kept, and stores the
// result as one undo step of the weights part.
#include "core/scene/document.h"

#include <string>

#include "core/scene/document_parts.h"
#include "core/util/error.h"

namespace dfm {
namespace {

void require_weights(const Document& doc, const char* tool) {
  if (!doc.has_weights())
    throw Error(std::string(tool) + " needs weights: " + (doc.weights_note().empty() ? "not bound" : doc.weights_note()) +
                " (bind first)");
}

std::vector<bool> constrained_rows(const Document& doc) {
  return surface_weight_constraints(doc.surface().V, doc.rig()).mask(doc.surface().num_vertices());
}

}  // namespace

void Document::store_weights(const std::string& name, Eigen::MatrixXd W) {
  if (W == s_.weights) return;  // nothing changed: no undo step
  execute(name, kWeights, "", [&](SceneData& s) { s.weights = std::move(W); });
}

LimitReport Document::weights_limit(const LimitOptions& opts) {
  require_weights(*this, "limit influences");
  LimitReport rep;
  Eigen::MatrixXd W = limit_influences(s_.weights, s_.surface.V, s_.surface.F, constrained_rows(*this), opts, &rep);
  store_weights("limit weights to " + std::to_string(opts.k), std::move(W));
  return rep;
}

NormalizeReport Document::weights_normalize(const std::vector<int>& locked) {
  require_weights(*this, "normalize");
  NormalizeReport rep;
  Eigen::MatrixXd W = normalize_locked(s_.weights, locked, constrained_rows(*this), &rep);
  store_weights("normalize weights", std::move(W));
  return rep;
}

void Document::weights_smooth(const SmoothOptions& opts, const std::vector<int>& locked) {
  require_weights(*this, "smooth");
  Eigen::MatrixXd W = smooth_weights(s_.weights, s_.surface.V, s_.surface.F, locked, constrained_rows(*this), opts);
  store_weights("smooth weights", std::move(W));
}

MirrorReport Document::weights_mirror(const MirrorOptions& opts) {
  require_weights(*this, "mirror");
  MirrorReport rep;
  Eigen::MatrixXd W = mirror_weights(s_.weights, s_.surface.V, s_.surface.F, s_.rig, constrained_rows(*this), opts, &rep);
  store_weights("mirror weights", std::move(W));
  return rep;
}

std::vector<ZeroWeightHandle> Document::weights_report(double threshold) const {
  if (!has_weights()) return {};
  return zero_weight_report(s_.weights, s_.rig, threshold);
}

}  // namespace dfm
