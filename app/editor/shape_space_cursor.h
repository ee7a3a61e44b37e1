#pragma once
// The shape the Shape space panel shows at its pad cursor (Alexa 2002, 5.5.1: Eq. 5.31's chain of
// morphs at the cursor's weights). A linear space's shape is synthesized at once (microseconds); an
// ARAP space's goes to a worker (ShapeSpaceJob) once the cursor is released, the linear blend at the
// cursor standing in until the shape for the cursor arrives. A newer cursor or cancel() supersedes
// the request: a shape for an older cursor is never shown once a newer one is wanted. No GL, no
// Document: the space is built from copies of the keys (core/scene/shape_space_keys.h).
#include <memory>
#include <string>

#include <Eigen/Core>

#include "app/editor/shape_space_job.h"
#include "core/anim/shape_space.h"

namespace dfm::editor {

class CursorShape {
 public:
  // Brings the shape to coordinates x of `space` (null: nothing to show); `dragging`: the cursor is
  // moving (ARAP is not asked for until it stops). A different space than the last call's starts
  // afresh. Returns true when vertices() changed (upload them).
  bool update(const std::shared_ptr<ShapeSpace>& space, const Eigen::VectorXd& x, bool dragging);
  // Drops the ARAP request for the cursor (shown: the linear stand-in); not asked for again until the
  // cursor moves or retry().
  void cancel();
  void retry();
  // Stops asking for ARAP (the panel is closed): asked for again by the next update().
  void pause();

  const Eigen::MatrixXd& vertices() const { return V_; }  // empty: none
  const Eigen::VectorXd& weights() const { return x_; }   // of vertices()
  // vertices() are the space's own synthesis at x (the ARAP one in an ARAP space, not the stand-in).
  bool final_at(const Eigen::VectorXd& x) const;
  bool is_final() const { return final_; }
  bool waiting() const { return job_.waiting(); }   // an ARAP request is wanted and not collected
  bool running() const { return job_.running(); }   // the worker runs one (maybe superseded)
  bool cancelled() const { return cancelled_; }
  double elapsed_seconds() const { return job_.elapsed_seconds(); }
  double synth_ms() const { return ms_; }           // the last final shape's synthesis time
  const std::string& error() const { return error_; }
  // Blocks until the worker is idle (tests; the editor draws frames instead).
  bool wait_idle(double timeout_s) const { return job_.wait_idle(timeout_s); }

 private:
  void reset();

  ShapeSpaceJob job_;
  std::shared_ptr<ShapeSpace> space_;  // of the shape and the request
  Eigen::MatrixXd V_;
  Eigen::VectorXd x_;
  bool final_ = false;
  double ms_ = 0;
  std::string error_;
  Eigen::VectorXd requested_;  // the last ARAP request's coordinates (empty: none since the cursor moved)
  bool cancelled_ = false;
};

}  // namespace dfm::editor
