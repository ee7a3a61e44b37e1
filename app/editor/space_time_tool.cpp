#include "app/editor/space_time_tool.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "core/anim/manifold_laplacian.h"
#include "core/scene/key_surfaces.h"
#include "core/view/picking.h"
#include "render/overlay_geometry.h"

namespace dfm::editor {

void SpaceTimeTool::follow_document(const Document& doc) {
  const std::vector<SpaceTimeEdit>& edits = doc.space_time_edits();
  if (edits.size() == seen_edits_ || drag_) return;
  seen_edits_ = edits.size();
  if (edits.empty()) return;
  const SpaceTimeEdit& e = edits.back();
  t0_ = e.region.t0, t1_ = e.region.t1;
  weights_ = e.weights, time_scale_ = e.time_scale, volume_ = e.preserve_volume;
}

CommandWords SpaceTimeTool::region_line(const Eigen::Vector3d& p, double diagonal) const {
  const double r = radius_ * std::max(1e-9, diagonal);
  CommandWords w = command_words("edit-region", {p.x(), p.y(), p.z(), r, t0_, t1_});
  // Only what differs from the defaults: a default region's line stays as before.
  if (weights_ != LaplacianWeights::Reciprocal) w.push_back(std::string("weights=") + laplacian_weights_name(weights_));
  if (time_scale_ != 1.0) w.push_back("time-scale=" + CommandArg(time_scale_).word);
  if (volume_) w.push_back("volume");
  return w;
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
    for (const Eigen::Vector3d& d : e.region.dabs)
      view.add_overlay_lines(gl::circle_lines(d, facing, e.region.radius, col, 64), 2.0f);
    view.add_overlay_points({gl::overlay_vertex(e.region.center, Eigen::Vector4f(0.75f, 0.45f, 1, 1))}, 8.0f);
    if (e.move != Eigen::Vector3d::Zero())
      view.add_overlay_points({gl::overlay_vertex(e.handle.point + e.move, Eigen::Vector4f(0.3f, 0.9f, 1, 1))}, 12.0f);
  }
  if (drag_) return update_drag(doc, cam, in);
  if (brushing_) {
    const std::string s = update_stroke(doc, view, cam, in, run);
    if (brushing_ || !in.clicked) return s;  // a press whose release was missed ends the stroke and counts
  }
  if (!in.clicked || !in.hovered) return "";
  if (!in.t_slice) return "the Space-time tool edits in the t-slice view (set the sweep to t)";
  const view::SurfaceHit hit =
      view::pick_surface(view::pixel_ray(cam, in.mouse.x(), in.mouse.y()), view.display_vertices(), view.display_faces());
  if (!hit.hit()) return "click on the surface";
  const Eigen::Vector3d p = hit.point;
  if (in.new_region || edits.empty()) {
    doc.begin_gesture();
    brushing_ = run(region_line(p, view.surface_bounds().diagonal().norm()));
    if (!brushing_) doc.end_gesture();
    return "";
  }
  doc.begin_gesture();
  if (!run(command_words("edit-drag", {p.x(), p.y(), p.z(), 0.0, 0.0, 0.0}))) {
    doc.end_gesture();
    return "";
  }
  const int index = static_cast<int>(doc.space_time_edits().size()) - 1;
  const SpaceTimeEdit& e = doc.space_time_edits()[index];
  Drag d{index, p, e.move};
  if (in.retime) {
    // The edit's replay factored once here (the manifold before it rebuilt, as edit-drag's checks do),
    // so each frame can ask whether the replay takes the value before the document gets it.
    try {
      d.trial = std::make_shared<const SpaceTimeRetimeTrial>(manifold_before_edit(doc, index), e);
    } catch (const std::exception& err) {
      doc.end_gesture();
      return std::string("cannot retime this edit: ") + err.what();
    }
    d.press_x = in.mouse.x();
    d.retime0 = e.retime;
  }
  drag_ = std::move(d);
  return "";
}

std::string SpaceTimeTool::update_stroke(Document& doc, SceneView& view, const view::Camera& cam, const Input& in,
                                         const Run& run) {
  if (doc.space_time_edits().empty()) {  // undone under the stroke
    doc.end_gesture();
    brushing_ = false;
    return "";
  }
  const EditRegionSpec& r = doc.space_time_edits().back().region;
  if (in.released || in.clicked) {
    doc.end_gesture();
    brushing_ = false;
    char buf[120];
    std::snprintf(buf, sizeof buf, "space-time region: %d ball(s) of radius %.3g", static_cast<int>(r.dabs.size()) + 1, r.radius);
    return buf;
  }
  const view::SurfaceHit hit =
      view::pick_surface(view::pixel_ray(cam, in.mouse.x(), in.mouse.y()), view.display_vertices(), view.display_faces());
  if (!hit.hit()) return "";
  // A new dab once the stroke has left the last one by half a radius.
  const Eigen::Vector3d last = r.dabs.empty() ? r.center : r.dabs.back();
  if ((hit.point - last).norm() > 0.5 * r.radius) run(command_words("edit-brush", {hit.point.x(), hit.point.y(), hit.point.z()}));
  return "";
}

std::string SpaceTimeTool::update_drag(Document& doc, const view::Camera& cam, const Input& in) {
  SpaceTimeEdit e = doc.space_time_edits().at(drag_->index);
  char buf[320];
  if (in.released) {
    doc.end_gesture();
    const Drag d = std::move(*drag_);
    drag_.reset();
    if (d.trial) {
      std::snprintf(buf, sizeof buf, "space-time retime by %.3g s (now %.3g)", e.retime - d.retime0, e.retime);
      return d.refusal.empty() ? std::string(buf) : std::string(buf) + "; further refused: " + d.refusal;
    }
    const Eigen::Vector3d m = e.move - d.move0;
    std::snprintf(buf, sizeof buf, "space-time drag by (%.3g, %.3g, %.3g)", m.x(), m.y(), m.z());
    return buf;
  }
  if (!drag_->trial) {
    e.move = drag_->move0 + (view::pixel_on_plane_through(cam, drag_->handle, in.mouse.x(), in.mouse.y()) - drag_->handle);
    doc.set_space_time_edit(drag_->index, e);  // merges into the drag's one undo step
    return "";
  }
  // In time: the viewport's width is the edit's window.
  const double want =
      drag_->retime0 + (in.mouse.x() - drag_->press_x) / std::max(1.0, cam.width) * (e.region.t1 - e.region.t0);
  if (want == e.retime || want == drag_->refused_at) return "";  // a still mouse tries nothing again
  const std::string why = drag_->trial->refusal(want);
  if (why.empty()) {
    e.retime = want;
    doc.set_space_time_edit(drag_->index, e);  // merges into the drag's one undo step
    drag_->refusal.clear();
    return "";
  }
  drag_->refused_at = want;
  if (why == drag_->refusal) return "";
  drag_->refusal = why;
  std::snprintf(buf, sizeof buf, "retime %.3g refused, keeping %.3g: ", want, e.retime);
  return buf + why;
}

void SpaceTimeTool::cancel(Document& doc) {
  if (drag_ || brushing_) doc.end_gesture();
  drag_.reset();
  brushing_ = false;
}

void SpaceTimeTool::draw_setup() {
  static const LaplacianWeights kAll[] = {LaplacianWeights::Equal, LaplacianWeights::Reciprocal,
                                          LaplacianWeights::PrimalBoundary, LaplacianWeights::Dual};
  static const char* kWhat =
      "The Laplacian's weights (Southern 2008, 4.6.1):\n"
      "equal: 1 / neighbours (distorts on irregular tetrahedra)\n"
      "reciprocal: 1 / 4D edge length (the default)\n"
      "primal-boundary: reciprocal, and at the first and last frames the least-|delta| weights (4.4.1)\n"
      "dual: the dual graph Laplacian, rows per tetrahedron, ghost tetrahedra at the boundary (4.4.2)";
  ImGui::Separator();
  ImGui::TextWrapped("The next region's setup:");
  // Narrower than the panel's other fields: "Time scale" is the longest label and must show.
  const float width =
      ImGui::GetContentRegionAvail().x - ImGui::CalcTextSize("Time scale").x - ImGui::GetStyle().ItemInnerSpacing.x;
  ImGui::SetNextItemWidth(width);
  if (ImGui::BeginCombo("Weights", laplacian_weights_name(weights_))) {
    for (LaplacianWeights w : kAll)
      if (ImGui::Selectable(laplacian_weights_name(w), w == weights_)) weights_ = w;
    ImGui::EndCombo();
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", kWhat);
  double s = time_scale_;
  ImGui::SetNextItemWidth(width);
  if (ImGui::InputDouble("Time scale", &s, 0, 0, "%.3g") && std::isfinite(s) && s > 0) time_scale_ = s;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("t's factor in the weights' edge lengths (> 0, default 1): larger keeps each frame's shape\n"
                      "stiffer against the time edges, so parts past the handle follow it");
  ImGui::Checkbox("Preserve volume", &volume_);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Each edited time layer keeps its enclosed volume (4.2.2)");
  ImGui::Separator();
}

void SpaceTimeTool::draw_options(const Document& doc, const Run& run) {
  default_window(doc);
  ImGui::TextWrapped("Shift-click the surface: a region there over the window; keep the button down and "
                     "move to brush more of it. Then drag a point in it: the motion follows over the window, "
                     "frames outside it stay. Ctrl-drag moves the point in time instead (the viewport's width "
                     "is the window).");
  float r = static_cast<float>(radius_);
  if (ImGui::SliderFloat("Radius", &r, 0.01f, 0.5f, "%.3f")) radius_ = r;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("The region's radius, a fraction of the surface's diagonal");
  ImGui::InputDouble("T0", &t0_, 0, 0, "%.3f");
  ImGui::InputDouble("T1", &t1_, 0, 0, "%.3f");
  if (ImGui::Button("Window = current time +- 1/4")) t0_ = t1_ = 0, default_window(doc);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Or drag the edges of the window's band on the timeline");
  draw_setup();
  const std::vector<SpaceTimeEdit>& edits = doc.space_time_edits();
  ImGui::Text("%d edit(s)", static_cast<int>(edits.size()));
  if (!edits.empty()) {
    const SpaceTimeEdit& e = edits.back();
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
    ImGui::TextWrapped("last: r %.3g (%d ball%s) over [%.3g, %.3g], move (%.3g, %.3g, %.3g) at t %.3g, retime %.3g; %s weights, "
                       "time scale %.3g%s%s",
                       e.region.radius, static_cast<int>(e.region.dabs.size()) + 1, e.region.dabs.empty() ? "" : "s",
                       e.region.t0, e.region.t1, e.move.x(), e.move.y(), e.move.z(), e.handle.time,
                       e.retime, laplacian_weights_name(e.weights), e.time_scale,
                       e.preserve_volume ? ", volume kept" : "", e.refine ? ", refined" : "");
    ImGui::PopStyleColor();
    const bool moved = e.move != Eigen::Vector3d::Zero() || e.retime != 0 ||
                       e.rotation.coeffs() != Eigen::Quaterniond::Identity().coeffs();
    ImGui::BeginDisabled(!moved || e.refine);
    if (ImGui::Button("Refine stretched")) run({"edit-refine"});
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
      ImGui::SetTooltip("Southern 4.5.1: the layer triangles the last edit stretched past twice the mean edge\n"
                        "length, and two rings round them, split 1:4 in every layer; the edit is made again on\n"
                        "the finer mesh. A new drag of the edit goes back to the unrefined mesh.");
    ImGui::SameLine();
    if (ImGui::Button("Clear edits")) run({"edit-clear"});
  }
}

}  // namespace dfm::editor
