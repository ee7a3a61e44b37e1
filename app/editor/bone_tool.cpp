#include "app/editor/bone_tool.h"

#include "core/view/picking.h"
#include "render/overlay_geometry.h"

namespace dfm::editor {

namespace {
const Eigen::Vector4f kChain(1, 0.75f, 0.3f, 1), kRubberBand(1, 1, 1, 0.6f);
}  // namespace

std::string BoneTool::click(SceneView& view, const view::Camera& cam, const Eigen::Vector2d& m) {
  if (joints_.empty()) {
    const int j = view::pick_projected_point(cam, view.joint_positions(), m, 8);
    if (j >= 0) {
      parent_ = j;
      joints_.push_back(view.joint_positions().row(j));
      return "";
    }
    parent_ = -1;
  }
  Eigen::Vector3d p;
  if (!view::pick_inside_point(view::pixel_ray(cam, m.x(), m.y()), view.display_vertices(), view.display_faces(), p)) {
    if (joints_.empty()) return "click inside the surface to start a bone chain";
    p = view::pixel_on_plane_through(cam, joints_.back(), m.x(), m.y());  // off the surface: the last joint's depth
  }
  joints_.push_back(p);
  return "";
}

void BoneTool::draw_preview(SceneView& view, const view::Camera& cam, const Input& in) const {
  if (joints_.empty()) return;
  std::vector<gl::OverlayVertex> l, pts;
  for (size_t i = 1; i < joints_.size(); ++i) {
    l.push_back(gl::overlay_vertex(joints_[i - 1], kChain));
    l.push_back(gl::overlay_vertex(joints_[i], kChain));
  }
  if (in.hovered) {
    l.push_back(gl::overlay_vertex(joints_.back(), kRubberBand));
    const Eigen::Vector3d end = view::pixel_on_plane_through(cam, joints_.back(), in.mouse.x(), in.mouse.y());
    l.push_back(gl::overlay_vertex(end, kRubberBand));
  }
  view.add_overlay_lines(l, 3.0f);
  for (const auto& j : joints_) pts.push_back(gl::overlay_vertex(j, kChain));
  view.add_overlay_points(pts, 10.0f);
}

CommandWords BoneTool::finish() {
  CommandWords w;
  if (joints_.size() >= 2) {
    // From a joint: the words name it and the new joints only (the first is the joint itself).
    w = parent_ >= 0 ? command_words("add-bone-from", {parent_}) : command_words("add-bone");
    for (size_t i = parent_ >= 0 ? 1 : 0; i < joints_.size(); ++i)
      for (int c = 0; c < 3; ++c) w.push_back(CommandArg(joints_[i][c]).word);
  }
  cancel();
  return w;
}

}  // namespace dfm::editor
