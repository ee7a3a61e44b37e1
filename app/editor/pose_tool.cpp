#include "app/editor/pose_tool.h"

#include <algorithm>

namespace dfm::editor {

namespace {

// The bone as shown (its joints in the view, posed) with its rest length; none when the view has no
// joints for it.
std::optional<GizmoBone> shown_bone(const Document& doc, const SceneView& view, int bone) {
  const Skeleton& sk = doc.rig().skeleton;
  const Eigen::MatrixXd& J = view.joint_positions();
  const Bone& b = sk.bones[bone];
  if (b.a >= J.rows() || b.b >= J.rows()) return std::nullopt;
  GizmoBone g;
  g.a = J.row(b.a).transpose();
  g.b = J.row(b.b).transpose();
  g.rest_length = (sk.joints.row(b.b) - sk.joints.row(b.a)).norm();
  return g;
}

}  // namespace

void PoseTool::drag_twist_stretch(Document& doc, const view::Camera& cam, int bone, const Input& in) {
  BoneTwistStretch ts = twist_stretch_of(doc.pose_params(), bone);
  if (part_ == GizmoPart::TwistRing) ts.twist += gizmo_twist(cam, shape_, last_, in.mouse);
  else ts.stretch = std::max(0.05, ts.stretch + gizmo_stretch(cam, shape_, last_, in.mouse));
  doc.set_bone_twist_stretch(bone, ts);
  last_ = in.mouse;
}

bool PoseTool::update(Document& doc, SceneView& view, const view::Camera& cam, const Input& in) {
  const auto& sel = doc.selection().handles;
  const Eigen::MatrixXd& P = view.handle_positions();
  has_shape_ = false;
  if (sel.empty() || sel.front() >= P.rows() || !in.rig_shown) {
    cancel(doc);
    return false;
  }
  const int h = sel.front();
  const HandleRef r = handle_ref(doc.rig(), h);
  const bool rotate = in.rotate && r.kind != HandleKind::CageVertex;
  const std::optional<GizmoBone> bone = r.kind == HandleKind::Bone ? shown_bone(doc, view, r.index) : std::nullopt;
  shape_ = gizmo_shape(cam, P.row(h).transpose(), rotate, {}, bone ? &*bone : nullptr);
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
  if (in.mouse != last_ && (part_ == GizmoPart::TwistRing || part_ == GizmoPart::Stretch)) {
    drag_twist_stretch(doc, cam, handle_ref(doc.rig(), handle).index, in);
  } else if (in.mouse != last_) {
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
