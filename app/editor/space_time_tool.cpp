#include "app/editor/space_time_tool.h"

#include <algorithm>
#include <cstdio>

#include <imgui.h>

#include "core/view/picking.h"
#include "render/overlay_geometry.h"

namespace dfm::editor {

void SpaceTimeTool::follow_document(const Document& doc) {
  const std::vector<SpaceTimeEdit>& edits = doc.space_time_edits();
  if (edits.size() == seen_edits_ || drag_) return;
  seen_edits_ = edits.size();
  if (!edits.empty()) t0_ = edits.back().region.t0, t1_ = edits.back().region.t1;
}

void SpaceTimeTool::default_window(const Document& doc) {
  if (t0_ < t1_ || doc.keys().size() < 2) return;
  const double a = doc.keys().front().time, b = doc.keys().back().time, q = 0.25 * (b - a);
  t0_ = std::clamp(doc.time() - q, a, b);
  t1_ = std::clamp(doc.time() + q, a, b);
  if (!(t0_ < t1_)) t0_ = a, t1_ = b;
}

std::string SpaceTimeTool::update(Document& doc, SceneView& view, const view::Camera& cam, const Input& in, const Run& run) {
  follow_document(doc);
  default_window(doc);
  const std::vector<SpaceTimeEdit>& edits = doc.space_time_edits();
  const Eigen::Vector3d facing = -view::camera_forward(cam);
  if (!edits.empty() && in.t_slice) {  // the current edit: its ball (a circle facing the camera) and its handle
    const SpaceTimeEdit& e = edits.back();
    const bool in_window = doc.time() >= e.region.t0 && doc.time() <= e.region.t1;
    const Eigen::Vector4f col = in_window ? Eigen::Vector4f(0.75f, 0.45f, 1, 0.9f) : Eigen::Vector4f(0.6f, 0.6f, 0.6f, 0.5f);
    view.add_overlay_lines(gl::circle_lines(e.region.center, facing, e.region.radius, col, 64), 2.0f);
    view.add_overlay_points({gl::overlay_vertex(e.region.center, Eigen::Vector4f(0.75f, 0.45f, 1, 1))}, 8.0f);
    if (e.move != Eigen::Vector3d::Zero())
      view.add_overlay_points({gl::overlay_vertex(e.handle.point + e.move, Eigen::Vector4f(0.3f, 0.9f, 1, 1))}, 12.0f);
  }
  if (drag_) {
    if (in.released) {
      doc.end_gesture();
      const Drag d = *drag_;
      drag_.reset();
      const Eigen::Vector3d m = doc.space_time_edits()[d.index].move - d.move0;
      char buf[160];
      std::snprintf(buf, sizeof buf, "space-time drag by (%.3g, %.3g, %.3g)", m.x(), m.y(), m.z());
      return buf;
    }
    SpaceTimeEdit e = doc.space_time_edits().at(drag_->index);
    e.move = drag_->move0 + (view::pixel_on_plane_through(cam, drag_->handle, in.mouse.x(), in.mouse.y()) - drag_->handle);
    doc.set_space_time_edit(drag_->index, e);  // merges into the drag's one undo step
    return "";
  }
  if (!in.clicked || !in.hovered) return "";
  if (!in.t_slice) return "the Space-time tool edits in the t-slice view (set the sweep to t)";
  const view::SurfaceHit hit =
      view::pick_surface(view::pixel_ray(cam, in.mouse.x(), in.mouse.y()), view.display_vertices(), view.display_faces());
  if (!hit.hit()) return "click on the surface";
  const Eigen::Vector3d p = hit.point;
  if (in.new_region || edits.empty()) {
    const double r = radius_ * std::max(1e-9, view.surface_bounds().diagonal().norm());
    run(command_words("edit-region", {p.x(), p.y(), p.z(), r, t0_, t1_}));
    return "";
  }
  doc.begin_gesture();
  if (!run(command_words("edit-drag", {p.x(), p.y(), p.z(), 0.0, 0.0, 0.0}))) {
    doc.end_gesture();
    return "";
  }
  const int index = static_cast<int>(doc.space_time_edits().size()) - 1;
  drag_ = Drag{index, p, doc.space_time_edits()[index].move};
  return "";
}

void SpaceTimeTool::cancel(Document& doc) {
  if (drag_) doc.end_gesture();
  drag_.reset();
}

void SpaceTimeTool::draw_options(const Document& doc, const Run& run) {
  default_window(doc);
  ImGui::TextWrapped("Shift-click the surface: a region there over the window. Then drag a point in it: "
                     "the motion follows over the window, frames outside it stay.");
  float r = static_cast<float>(radius_);
  if (ImGui::SliderFloat("Radius", &r, 0.01f, 0.5f, "%.3f")) radius_ = r;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("The region's radius, a fraction of the surface's diagonal");
  ImGui::InputDouble("T0", &t0_, 0, 0, "%.3f");
  ImGui::InputDouble("T1", &t1_, 0, 0, "%.3f");
  if (ImGui::Button("Window = current time +- 1/4")) t0_ = t1_ = 0, default_window(doc);
  const std::vector<SpaceTimeEdit>& edits = doc.space_time_edits();
  ImGui::Text("%d edit(s)", static_cast<int>(edits.size()));
  if (!edits.empty()) {
    const SpaceTimeEdit& e = edits.back();
    ImGui::TextDisabled("last: r %.3g over [%.3g, %.3g], move (%.3g, %.3g, %.3g) at t %.3g", e.region.radius, e.region.t0,
                        e.region.t1, e.move.x(), e.move.y(), e.move.z(), e.handle.time);
    if (ImGui::Button("Clear edits")) run({"edit-clear"});
  }
}

}  // namespace dfm::editor
