#include "app/editor/sculpt_tool.h"

#include <imgui.h>

#include <algorithm>

#include "core/scene/local_transition.h"
#include "core/util/error.h"
#include "core/view/picking.h"
#include "render/overlay_geometry.h"

namespace dfm::editor {

CommandWords SculptTool::transition_line(const Document& doc, const Eigen::MatrixXi& shown_faces, int face,
                                         const Eigen::Vector3d& bary, const Eigen::Vector3d& point, double radius,
                                         double value, double falloff, std::string* why) {
  int k = -1;
  try {
    k = transition_interval(doc, doc.time());
  } catch (const Error& e) {
    if (why) *why = e.what();
    return {};
  }
  const TriMesh& key = doc.keys()[k].mesh;
  Eigen::Vector3d c = point;
  // The shown frame is an in-between of the keys: the same spot on the first key, where the dab is measured.
  if (shown_faces.rows() == key.F.rows() && shown_faces == key.F && face >= 0 && face < key.F.rows()) {
    c.setZero();
    for (int j = 0; j < 3; ++j) c += bary[j] * key.V.row(key.F(face, j)).transpose();
  }
  return command_words("transition-state", {doc.time(), value, c.x(), c.y(), c.z(), radius, falloff});
}

void SculptTool::update(Document& doc, SceneView& view, const view::Camera& cam, const Input& in, const Run& run) {
  const double diag = std::max(1e-9, view.surface_bounds().diagonal().norm());

  // The handle drag: the point under the cursor on the view plane through where it started.
  if (drag_) {
    if (!in.down || in.released) {
      drag_.reset();
    } else {
      const Eigen::Vector3d p = view::pixel_on_plane_through(cam, *drag_, in.mouse.x(), in.mouse.y());
      const Eigen::Vector3d d = p - *drag_;
      if (d.squaredNorm() > 0) {
        if (!run(command_words("sculpt-move", {d.x(), d.y(), d.z()}))) return drag_.reset();
        drag_ = p;
      }
    }
    return;
  }

  const Eigen::MatrixXd& V = view.display_vertices();
  const Eigen::MatrixXi& F = view.display_faces();
  const view::SurfaceHit hit = in.hovered || stroke_ ? view::pick_surface(view::pixel_ray(cam, in.mouse.x(), in.mouse.y()), V, F)
                                                     : view::SurfaceHit{};
  const double radius = (mode_ == SculptMode::Handle ? handle_radius_ : radius_) * diag;
  if (hit.hit()) {
    const Eigen::Vector3d a = V.row(F(hit.face, 0)), b = V.row(F(hit.face, 1)), c = V.row(F(hit.face, 2));
    const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
    const Eigen::Vector4f col = in.erase && mode_ == SculptMode::Region ? Eigen::Vector4f(1, 0.35f, 0.3f, 1)
                                : mode_ == SculptMode::Handle ? Eigen::Vector4f(1, 0.62f, 0.2f, 1)
                                                              : Eigen::Vector4f(1, 1, 1, 0.9f);
    view.add_overlay_lines(gl::circle_lines(hit.point + 1e-3 * radius * normal, normal, radius, col, 64), 2.0f);
  }

  if (mode_ == SculptMode::Handle) {
    // A click on the region picks the handle there and starts its drag (off the region: the error says so).
    if (in.clicked && hit.hit() && run(command_words("sculpt-handle", {hit.point.x(), hit.point.y(), hit.point.z(), radius})))
      drag_ = hit.point;
    return;
  }

  if (in.clicked && hit.hit()) {
    stroke_ = true;
    doc.begin_gesture();  // a transition stroke is one undo step
  }
  if (stroke_ && in.down && hit.hit()) {
    CommandWords line;
    if (mode_ == SculptMode::Region) {
      line = command_words("sculpt-region", {hit.point.x(), hit.point.y(), hit.point.z(), radius});
      if (in.erase) line.push_back("erase");
    } else {
      line = transition_line(doc, F, hit.face, hit.bary, hit.point, radius, arrive_, falloff_);
    }
    if (line.empty() || !run(line)) cancel(doc);
  }
  if (in.released) cancel(doc);
}

void SculptTool::cancel(Document& doc) {
  drag_.reset();
  if (!stroke_) return;
  doc.end_gesture();
  stroke_ = false;
}

void SculptTool::draw_options(const Document& doc, const Run& run) {
  int mode = static_cast<int>(mode_);
  ImGui::RadioButton("Region", &mode, 0);
  ImGui::SameLine();
  ImGui::RadioButton("Handle", &mode, 1);
  ImGui::RadioButton("Local transition", &mode, 2);
  mode_ = static_cast<SculptMode>(mode);
  const SculptSession* s = doc.sculpt();
  ImGui::PushTextWrapPos(0.0f);
  if (mode_ == SculptMode::Transition) {
    float r = float(radius_), f = float(falloff_), a = float(arrive_);
    ImGui::SliderFloat("Radius", &r, 0.005f, 0.4f, "%.3f");
    ImGui::SliderFloat("Falloff", &f, 0.0f, 1.0f, "%.3f", ImGuiSliderFlags_AlwaysClamp);
    ImGui::SliderFloat("Arrives", &a, -0.9f, 0.9f, "%.2f", ImGuiSliderFlags_AlwaysClamp);
    radius_ = r, falloff_ = f, arrive_ = a;
    ImGui::TextDisabled("> 0: the next key arrives early there, < 0: late");
    std::string why;
    try {
      const int k = transition_interval(doc, doc.time());
      const Eigen::VectorXd& o = doc.keys()[k].transition_to_next;
      ImGui::TextDisabled("keys at %.2f -> %.2f: %d vertices painted", doc.keys()[k].time, doc.keys()[k + 1].time,
                          o.size() ? int((o.array() != 0).count()) : 0);
      if (ImGui::Button("Clear transition")) run({"clear-transition"});
    } catch (const Error& e) {
      ImGui::TextDisabled("%s", e.what());
    }
    ImGui::PopTextWrapPos();
    return;
  }
  float r = float(radius_), h = float(handle_radius_);
  ImGui::SliderFloat("Radius", &r, 0.005f, 0.4f, "%.3f");
  ImGui::SliderFloat("Handle r", &h, 0.005f, 0.2f, "%.3f");
  radius_ = r, handle_radius_ = h;
  int order = s ? s->order : 2;
  const int before = order;
  ImGui::RadioButton("Smooth (C1)", &order, 2);
  ImGui::RadioButton("Very smooth (C2)", &order, 3);
  if (order != before) run(command_words("sculpt-order", {order}));
  if (!s) {
    ImGui::TextDisabled("Brush the free region (the rest stays fixed; Ctrl erases), then in Handle mode click a handle inside it and drag.");
  } else {
    ImGui::TextDisabled("%d free vertices, handle %d, moved %.3f %.3f %.3f", s->region_count(), int(s->handle.size()),
                        s->move.x(), s->move.y(), s->move.z());
    if (doc.sculpt_factor_seconds() > 0) ImGui::TextDisabled("factored in %.0f ms", 1000 * doc.sculpt_factor_seconds());
  }
  ImGui::BeginDisabled(!s);
  if (ImGui::Button("Key this shape")) run({"sculpt-key"});
  ImGui::SameLine();
  if (ImGui::Button("Discard")) run({"sculpt-clear"});
  ImGui::EndDisabled();
  ImGui::PopTextWrapPos();
}

}  // namespace dfm::editor
