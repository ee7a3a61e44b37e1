// Document commands of the weight tools (document.h; the tools themselves are core/bind/weight_*.h).
// Each reads the current weights, runs the tool with the bind's constrained rows kept, and stores the
// result as one undo step of the weights part.
#include "core/scene/document.h"

#include <string>

#include "core/bind/weight_mirror.h"
#include "core/mesh/mesh_info.h"
#include "core/scene/document_parts.h"
#include "core/scene/weight_brush.h"
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

struct Document::PaintCache {
  std::uint64_t revision = 0;
  WeightPaintSurface surface;
  std::vector<bool> fixed;  // the bind's constrained rows
  std::vector<int> mirror;  // per handle, its mirror across x = 0
};

int Document::paint_weights(int handle, const Eigen::Vector3d& center, const WeightBrush& brush,
                            const std::vector<int>& locked, bool mirror_x) {
  require_weights(*this, "paint weights");
  document_detail::check_finite(center, "the dab's centre");
  if (!paint_cache_ || paint_cache_->revision != surface_rig_revision_) {
    auto c = std::make_shared<PaintCache>();
    c->revision = surface_rig_revision_;
    c->surface = weight_paint_surface(s_.surface.V, s_.surface.F);
    c->fixed = constrained_rows(*this);
    const double tol = MirrorOptions().tolerance * bounding_box(s_.surface.V).diagonal().norm();
    c->mirror = mirror_handles(s_.rig, s_.surface.V, Eigen::Vector3d::UnitX(), 0, tol);
    paint_cache_ = std::move(c);
  }
  const PaintCache& c = *paint_cache_;
  const std::vector<bool> lock = locked_flags(locked, num_handles());
  const WeightDab first = weight_dab(s_.weights, c.surface, handle, center, brush, lock, c.fixed);
  WeightDab second;
  if (mirror_x) {
    // The mirrored dab reads the weights after the first (they meet where the dab crosses x = 0):
    // the first is applied for the read and taken back, so the undo step saves what was there.
    WeightDab before = first;
    for (size_t i = 0; i < first.rows.size(); ++i) before.values.row(static_cast<Eigen::Index>(i)) = s_.weights.row(first.rows[i]);
    apply_weight_dab(s_.weights, first);
    WeightBrush b = brush;
    b.facing.x() = -b.facing.x();
    try {
      second = weight_dab(s_.weights, c.surface, c.mirror[handle], Eigen::Vector3d(-center.x(), center.y(), center.z()), b,
                          lock, c.fixed);
    } catch (...) {
      apply_weight_dab(s_.weights, before);
      throw;
    }
    apply_weight_dab(s_.weights, before);
  }
  const int changed = static_cast<int>(first.rows.size() + second.rows.size());
  if (changed == 0) return 0;
  execute("paint weights", kWeights, "paint weights", [&](SceneData& s) {
    apply_weight_dab(s.weights, first);
    apply_weight_dab(s.weights, second);
  });
  return changed;
}

}  // namespace dfm
