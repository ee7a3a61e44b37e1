#pragma once
// The Space-time tool (issue 35; Southern 2008 ch. 4): edits the animation manifold itself. Shift-click
// (or the first click) on the surface at the current time sets an edit's region centre, with the
// radius and the time window from the Tools panel (an edit-region line); holding the button and moving
// brushes more of the region (an edit-brush line each half radius, the stroke one undo step); then press on the surface
// near it and drag: that point is the handle, moved in the view plane, and the region follows
// smoothly in space and over the window. The press is an edit-drag line (the same checks a script
// gets), each frame of the drag sets the edit's move in the document (the manifold builder replays it
// onto the region's rows from the editor it cached), the whole drag one undo step. A Ctrl-drag (Alt
// orbits) retimes instead: the handle moves in time, the viewport's width the edit's window, and a
// value the replay refuses (manifold_retime.h) is not set: the last accepted one stays, the refusal
// is the status line. The panel's weights, time scale and volume are the next region's setup.
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "app/editor/scene_view.h"
#include "core/scene/command.h"
#include "core/scene/document.h"
#include "core/view/camera.h"

namespace dfm::editor {

class SpaceTimeTool {
 public:
  struct Input {
    Eigen::Vector2d mouse = Eigen::Vector2d::Zero();  // viewport pixels
    bool hovered = false, clicked = false, released = false;
    bool new_region = false;  // Shift held: the click starts a new region
    bool retime = false;      // Ctrl held: the press starts a drag in time
    bool t_slice = true;      // the view shows a t-slice (the region's ball is drawn only there)
  };
  using Run = std::function<bool(const CommandWords& words)>;  // a line as a UI command; false: failed
  // Draws the region and handle and runs the click or drag. Returns a status line ("" for none).
  std::string update(Document& doc, SceneView& view, const view::Camera& cam, const Input& in, const Run& run);
  // The Tools panel: radius (a fraction of the surface's diagonal), window T0 T1, the setup, the edits, Clear.
  void draw_options(const Document& doc, const Run& run);
  void set_region(double radius_fraction, double t0, double t1) { radius_ = radius_fraction, t0_ = t0, t1_ = t1; }
  // The next region's setup (edit-region's weights=, time-scale=, volume).
  void set_setup(LaplacianWeights weights, double time_scale, bool preserve_volume) {
    weights_ = weights, time_scale_ = time_scale, volume_ = preserve_volume;
  }
  // The edit-region line a click at p makes: the panel's radius (times the surface's diagonal), window and setup.
  CommandWords region_line(const Eigen::Vector3d& p, double diagonal) const;
  // The window the timeline draws as a band (and whose edges it drags: set_window).
  std::pair<double, double> window() const { return {t0_, t1_}; }
  void set_window(double t0, double t1) { t0_ = t0, t1_ = t1; }
  bool dragging() const { return drag_.has_value() || brushing_; }
  void cancel(Document& doc);  // ends a drag or stroke cut short (its undo step stays as far as it got)

 private:
  struct Drag {
    int index = 0;
    Eigen::Vector3d handle, move0;  // the grabbed point and the edit's move when grabbed
    // A retime drag: the press's x, the edit's retime then, its replay to try values on, the last refusal.
    double press_x = 0, retime0 = 0;
    double refused_at = std::numeric_limits<double>::quiet_NaN();  // the last value refused
    std::shared_ptr<const SpaceTimeRetimeTrial> trial;  // null: a drag in space
    std::string refusal;
  };
  std::string update_stroke(Document& doc, SceneView& view, const view::Camera& cam, const Input& in, const Run& run);
  std::string update_drag(Document& doc, const view::Camera& cam, const Input& in);
  void draw_setup();  // the Tools panel's weights, time scale and volume
  // The window when the fields hold none yet: the middle half of the keys' span.
  void default_window(const Document& doc);
  // Adopts the window of an edit made elsewhere (a script's edit-region, undo), once per change.
  void follow_document(const Document& doc);
  double radius_ = 0.12;
  size_t seen_edits_ = 0;
  double t0_ = 0, t1_ = 0;
  LaplacianWeights weights_ = LaplacianWeights::Reciprocal;
  double time_scale_ = 1.0;
  bool volume_ = false;
  std::optional<Drag> drag_;
  bool brushing_ = false;  // a Shift stroke: each step on the surface brushes more of the new region
};

}  // namespace dfm::editor
