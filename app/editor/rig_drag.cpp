#include "app/editor/rig_drag.h"

#include "core/rig/rig.h"

namespace dfm::editor {

void RigDrag::start_handle(Document& doc, int h, const Eigen::Vector3d& p) {
  cancel(doc);
  const HandleKind k = handle_ref(doc.rig(), h).kind;
  if (k != HandleKind::Point && k != HandleKind::CageVertex) return;
  handle_ = h;
  point_ = p;
  doc.begin_gesture();
}

void RigDrag::start_joint(Document& doc, int j, const Eigen::Vector3d& p) {
  cancel(doc);
  joint_ = j;
  point_ = p;
  doc.begin_gesture();
}

void RigDrag::move_to(Document& doc, const Eigen::Vector3d& q) {
  if (joint_ >= 0) {
    doc.move_joint(joint_, q);
  } else {
    const HandleRef r = handle_ref(doc.rig(), handle_);
    if (r.kind == HandleKind::Point) doc.move_point(r.index, q);
    else if (r.kind == HandleKind::CageVertex) doc.move_cage_vertex(r.cage, r.index, q);
  }
  point_ = q;
}

void RigDrag::update(Document& doc, const view::Camera& cam, const Eigen::Vector2d& mouse, bool released) {
  if (!dragging()) return;
  const Eigen::Vector3d q = view::pixel_on_plane_through(cam, point_, mouse.x(), mouse.y());
  if ((q - point_).norm() > 0) move_to(doc, q);
  if (released) cancel(doc);
}

void RigDrag::cancel(Document& doc) {
  if (!dragging()) return;
  doc.end_gesture();
  handle_ = joint_ = -1;
}

}  // namespace dfm::editor
