#include "app/editor/shape_space_cursor.h"

#include <chrono>
#include <optional>
#include <utility>

namespace dfm::editor {

namespace {
bool same(const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return a.size() == b.size() && a == b; }
}  // namespace

bool CursorShape::final_at(const Eigen::VectorXd& x) const { return final_ && V_.rows() > 0 && same(x_, x); }

void CursorShape::reset() {
  job_.cancel();
  space_.reset();
  V_.resize(0, 3);
  x_.resize(0);
  final_ = false;
  error_.clear();
  requested_.resize(0);
  cancelled_ = false;
}

void CursorShape::cancel() {
  if (!job_.waiting()) return;
  job_.cancel();
  cancelled_ = true;  // requested_ stays: not posted again for this cursor
}

void CursorShape::retry() {
  requested_.resize(0);
  cancelled_ = false;
}

void CursorShape::pause() {
  if (job_.waiting()) job_.cancel(), requested_.resize(0);
}

bool CursorShape::update(const std::shared_ptr<ShapeSpace>& space, const Eigen::VectorXd& x, bool dragging) {
  if (space != space_ || !space) {
    const bool had = V_.rows() > 0;
    reset();
    space_ = space;
    if (!space) return had;
  }
  bool changed = false;
  if (std::optional<ShapeSpaceJob::Result> r = job_.take()) {  // the newest request's, once
    if (r->error.empty()) {
      V_ = std::move(r->V);
      x_ = requested_;
      final_ = true;
      ms_ = 1000.0 * r->seconds;
      error_.clear();
      changed = true;
    } else {
      error_ = r->error;  // requested_ stays: not asked for again until the cursor moves
    }
  }
  if (x.size() != space_->size()) return changed;
  const bool at_cursor = same(x_, x);
  if (space_->morph() == ShapeMorph::Arap && !same(requested_, x)) {
    job_.cancel();  // an older cursor's shape is no longer wanted
    requested_.resize(0);
    cancelled_ = false;
    if (!dragging) {
      requested_ = x;
      if (!(at_cursor && final_)) {
        job_.post([space = space_, x] { return space->synthesize(x); });
        error_.clear();
      }
    }
  }
  if (at_cursor) return changed;
  // The linear blend: a linear space's own shape, or the stand-in while ARAP runs.
  try {
    const auto t0 = std::chrono::steady_clock::now();
    V_ = synthesize_linear(space_->bases(), x);
    final_ = space_->morph() == ShapeMorph::Linear;
    if (final_) {
      ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      error_.clear();
    }
  } catch (const std::exception& e) {
    error_ = e.what();
    V_.resize(0, 3);
    final_ = false;
  }
  x_ = x;  // on an error too: not tried again every frame
  return true;
}

}  // namespace dfm::editor
