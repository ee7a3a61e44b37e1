#pragma once
// The Select tool's drag of the rig in its rest pose: a point handle, a cage vertex or a joint follows
// the cursor on the plane through it that faces the camera, one undo step per drag (the document's
// gesture around move_point, move_cage_vertex, move_joint). Owns its drag state; the editor starts it
// on a grab and hands it the frame's cursor.
#include <Eigen/Core>

#include "core/scene/document.h"
#include "core/view/camera.h"

namespace dfm::editor {

class RigDrag {
 public:
  // Starts dragging handle h (a point or cage vertex; other kinds do not move) or joint j, now at p.
  // Opens the drag's undo step.
  void start_handle(Document& doc, int h, const Eigen::Vector3d& p);
  void start_joint(Document& doc, int j, const Eigen::Vector3d& p);
  bool dragging() const { return handle_ >= 0 || joint_ >= 0; }
  // Moves what is dragged under the cursor; released ends the drag (closes the undo step).
  void update(Document& doc, const view::Camera& cam, const Eigen::Vector2d& mouse, bool released);
  // Ends a drag cut short (an error in an edit, or the Pose tool taking over): closes its undo step.
  void cancel(Document& doc);

 private:
  void move_to(Document& doc, const Eigen::Vector3d& q);

  Eigen::Vector3d point_ = Eigen::Vector3d::Zero();  // where the dragged element is (world)
  int handle_ = -1;
  int joint_ = -1;
};

}  // namespace dfm::editor
