#pragma once
// The Pose tool (G: move, R: rotate): the gizmo on the active handle, drawn and picked from one
// GizmoShape (gizmo.h), and its drag, one undo step per drag through the document's translate_handle
// and rotate_handle; on a bone also its twist ring (R) and stretch handle (G), through
// set_bone_twist_stretch. Owns its drag state; the editor hands it the frame's input.
#include <optional>

#include <Eigen/Core>

#include "app/editor/gizmo.h"
#include "app/editor/scene_view.h"
#include "core/scene/document.h"
#include "core/view/camera.h"

namespace dfm::editor {

class PoseTool {
 public:
  struct Input {
    Eigen::Vector2d mouse = Eigen::Vector2d::Zero();  // viewport pixels
    bool clicked = false, released = false;
    bool rotate = false;     // the Rotate tool (else Move); cage vertices only move
    bool rig_shown = false;  // handles drawn (no gizmo on a handle that is not)
  };
  // Draws the gizmo and runs its drag. False when a click missed the gizmo (or there is none): the
  // editor then treats it as a selection click.
  bool update(Document& doc, SceneView& view, const view::Camera& cam, const Input& in);
  bool dragging() const { return part_ != GizmoPart::None; }
  // Ends a drag cut short (an error in an edit): closes its undo step.
  void cancel(Document& doc);
  // The gizmo on the active handle as drawn this frame (none: has_shape() is false).
  bool has_shape() const { return has_shape_; }
  const GizmoShape& shape() const { return shape_; }

 private:
  void drag(Document& doc, const view::Camera& cam, int handle, const Input& in);
  // A bone's twist ring or stretch handle: the document's twist or stretch (one undo step a drag).
  void drag_twist_stretch(Document& doc, const view::Camera& cam, int bone, const Input& in);

  GizmoPart part_ = GizmoPart::None;  // the part being dragged
  Eigen::Vector2d last_ = Eigen::Vector2d::Zero();
  GizmoShape shape_;
  bool has_shape_ = false;
};

}  // namespace dfm::editor
