#pragma once
// The Sculpt tool (issue 37): shape keys made in the editor. Three modes, each a brush or a drag whose
// every step is a script line run by the caller (SCRIPT.md), so a script of those lines repeats it:
//  - Region: brush the free region (sculpt-region; Ctrl/Shift erases); the rest of the surface is fixed.
//  - Handle: a click picks the handle, the free region's vertices within the handle radius of the
//    clicked point (sculpt-handle); dragging moves it in the view plane (sculpt-move per frame).
//  - Transition: on the interval at the current time between two mesh keys of one connectivity, brush
//    where the next key arrives early or late (transition-state, one undo step per stroke).
// The Tools panel holds the radii, the C1/C2 order, "Key this shape" (sculpt-key) and "Discard". The
// session itself lives in the document (Document::sculpt); the view shows its result.
#include <functional>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "app/editor/scene_view.h"
#include "core/scene/command.h"
#include "core/scene/document.h"
#include "core/view/camera.h"

namespace dfm::editor {

enum class SculptMode { Region, Handle, Transition };

class SculptTool {
 public:
  struct Input {
    Eigen::Vector2d mouse = Eigen::Vector2d::Zero();  // viewport pixels
    bool hovered = false;
    bool down = false, clicked = false, released = false;
    bool erase = false;  // Ctrl or Shift held
  };
  // Runs a line as a UI command; false when it failed (the caller has said why).
  using Run = std::function<bool(const CommandWords& words)>;
  // Draws the brush circle and the region overlay, and turns strokes and drags into lines.
  void update(Document& doc, SceneView& view, const view::Camera& cam, const Input& in, const Run& run);
  void draw_options(const Document& doc, const Run& run);
  void set_mode(SculptMode m) { mode_ = m; }
  void set_brush(double radius, double handle_radius, double falloff, double arrive) {
    radius_ = radius, handle_radius_ = handle_radius, falloff_ = falloff, arrive_ = arrive;
  }
  bool busy() const { return stroke_ || drag_.has_value(); }
  void cancel(Document& doc);

  // The line of a transition dab at `hit` on the shown frame: the point on the interval's first key
  // with the same face and barycentric weights when the frame has the keys' triangles, else `point`
  // itself. Empty when the current time has no interval for a local transition (`why` says so).
  static CommandWords transition_line(const Document& doc, const Eigen::MatrixXi& shown_faces, int face,
                                      const Eigen::Vector3d& bary, const Eigen::Vector3d& point, double radius,
                                      double value, double falloff, std::string* why = nullptr);

 private:
  SculptMode mode_ = SculptMode::Region;
  double radius_ = 0.08;          // region and transition brush: fraction of the bounding-box diagonal
  double handle_radius_ = 0.04;   // the handle's reach, the same units
  double falloff_ = 0.5;          // transition brush only (the region is in or out)
  double arrive_ = 0.5;           // transition offset: > 0 early, < 0 late
  bool stroke_ = false;
  std::optional<Eigen::Vector3d> drag_;  // the handle drag's last point in the view plane
};

}  // namespace dfm::editor
