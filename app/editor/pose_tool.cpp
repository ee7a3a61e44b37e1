#include "app/editor/pose_tool.h"

namespace dfm::editor {

bool PoseTool::update(Document& doc, SceneView& view, const view::Camera& cam, const Input& in) {
  const auto& sel = doc.selection().handles;
  const Eigen::MatrixXd& P = view.handle_positions();
  has_shape_ = false;
  if (sel.empty() || sel.front() >= P.rows() || !in.rig_shown) {
    cancel(doc);
    return false;
  }
  const int h = sel.front();
  const bool rotate = in.rotate && handle_ref(doc.rig(), h).kind != HandleKind::CageVertex;
  shape_ = gizmo_shape(cam, P.row(h).transpose(), rotate);
  has_shape_ = true;
  const GizmoPart hover = dragging() ? part_ : gizmo_hit(cam, shape_, in.mouse);
  view.add_overlay_lines(gizmo_lines(shape_, hover), 3.0f);
  if (in.clicked) {
    if (hover == GizmoPart::None) return false;
    part_ = hover;
    last_ = in.mouse;
    doc.begin_gesture();
    return true;
  }
  if (dragging()) drag(doc, cam, h, in);
  return true;
}

void PoseTool::drag(Document& doc, const view::Camera& cam, int handle, const Input& in) {
  if (in.mouse != last_) {
    if (shape_.rotate) {
      const Eigen::Quaterniond q = gizmo_rotation(cam, shape_.origin, part_, last_, in.mouse);
      if (q.angularDistance(Eigen::Quaterniond::Identity()) > 1e-9) doc.rotate_handle(handle, q);
    } else {
      const Eigen::Vector3d d = gizmo_translation(cam, shape_.origin, part_, last_, in.mouse);
      if (d.norm() > 0) doc.translate_handle(handle, d);
    }
    last_ = in.mouse;
  }
  if (in.released) cancel(doc);
}

void PoseTool::cancel(Document& doc) {
  if (!dragging()) return;
  doc.end_gesture();
  part_ = GizmoPart::None;
}

}  // namespace dfm::editor
