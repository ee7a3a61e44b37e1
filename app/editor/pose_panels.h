#pragma once
// The right panel's Transform section (typed moves and rotations of the selected handle) and Posing
// section (FAST on or off, iterations, the selected handle's state, the IK chain, the last solve's
// timings) as one unit with the state they keep between frames: the typed rotation, the iteration
// slider while it is dragged, the last precompute and switch times. Every change is a document command.
#include <string>

#include "core/scene/document.h"

namespace dfm::editor {

class PosePanels {
 public:
  // `shown`: the pose on display (SceneView::shown_pose); `animated_at`: the time shown as text when
  // that is the animation's ("" when it is the document's pose); `drag_step`: world units a pixel of
  // dragging moves.
  void draw_transform(Document& doc, const Pose& shown, const std::string& animated_at, double drag_step);
  void draw_posing(Document& doc, double frame_rate);

 private:
  void draw_typed_values(Document& doc, int h, const Eigen::Affine3d& T, double drag_step);
  void draw_handle_state(Document& doc, int h);
  // The Dynamics switch, its settings and Simulate at the timeline's frame rate (dynamics_panel.cpp).
  void draw_dynamics(Document& doc, double frame_rate);
  void draw_dynamics_controls(Document& doc, double frame_rate);  // throws what a command threw
  void draw_twist_stretch(Document& doc, int bone);
  void draw_endpoint_filter(Document& doc, int bone);

  float rotate_deg_[3] = {0, 0, 0};  // "Apply rotation": degrees about world x, y, z
  int iterations_ = -1;              // the slider's value while it is dragged (-1: not yet shown)
  double precompute_s_ = 0, switch_s_ = 0;
  std::string dynamics_error_;  // why the last Simulate or dynamics setting failed  // the last FAST precompute and state switch
};

}  // namespace dfm::editor
