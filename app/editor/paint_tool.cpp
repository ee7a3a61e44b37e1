#include "app/editor/paint_tool.h"

#include <imgui.h>

#include <algorithm>

#include "core/scene/brush.h"
#include "core/view/picking.h"
#include "render/overlay_geometry.h"

namespace dfm::editor {

void PaintTool::update(Document& doc, SceneView& view, const view::Camera& cam, const Input& in, const Run& run) {
  const Eigen::MatrixXd& V = view.display_vertices();
  const view::SurfaceHit hit = in.hovered || painting_
                                   ? view::pick_surface(view::pixel_ray(cam, in.mouse.x(), in.mouse.y()), V, view.display_faces())
                                   : view::SurfaceHit{};
  const double radius = radius_ * std::max(1e-9, view.surface_bounds().diagonal().norm());
  Eigen::Vector3d center = hit.point;
  if (hit.hit()) {
    const Eigen::MatrixXi& F = view.display_faces();
    const Eigen::Vector3d a = V.row(F(hit.face, 0)), b = V.row(F(hit.face, 1)), c = V.row(F(hit.face, 2));
    const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
    const Eigen::Vector4f col = in.erase ? Eigen::Vector4f(1, 0.35f, 0.3f, 1) : Eigen::Vector4f(1, 1, 1, 0.9f);
    const Eigen::Vector3d lift = center + 1e-3 * radius * normal;
    view.add_overlay_lines(gl::circle_lines(lift, normal, radius, col, 64), 2.0f);
    if (falloff_ < 0.99)  // inner circle where the falloff starts
      view.add_overlay_lines(gl::circle_lines(lift, normal, radius * (1 - falloff_),
                                              Eigen::Vector4f(col.x(), col.y(), col.z(), 0.35f), 48), 1.0f);
  }
  const bool weights = target_ == PaintTarget::Weights;
  if (in.clicked && hit.hit() && (!weights || (doc.has_weights() && !doc.selection().handles.empty() && run))) {
    painting_ = true;
    doc.begin_gesture();
    if (target_ == PaintTarget::Region && (region_ < 0 || region_ >= int(doc.rig().regions.size())))
      region_ = doc.add_region();
  }
  if (painting_ && in.down && hit.hit() && weights) {
    const view::Ray ray = view::pixel_ray(cam, in.mouse.x(), in.mouse.y());
    if (!run(weight_dab_line(doc, center, radius, ray.direction, in))) cancel(doc);
  } else if (painting_ && in.down && hit.hit()) {
    const Brush brush{radius, strength_, falloff_, in.erase ? BrushMode::Erase : BrushMode::Add};
    const Eigen::VectorXd& mask = doc.mask();
    const BrushDab dab = brush_dab(V, mask.size() == V.rows() ? mask : Eigen::VectorXd(), center, brush);
    if (!dab.vertices.empty()) {
      if (target_ == PaintTarget::Mask) doc.paint_mask(dab.vertices, dab.values);
      else doc.paint_region(region_, dab.vertices, in.erase);
    }
  }
  if (in.released) cancel(doc);
}

CommandWords PaintTool::weight_dab_line(const Document& doc, const Eigen::Vector3d& center, double radius,
                                        const Eigen::Vector3d& view, const Input& in) const {
  static const char* const kModes[] = {"add", "subtract", "mix", "smooth"};
  WeightPaintMode mode = weight_mode_;
  if (in.erase && mode == WeightPaintMode::Add) mode = WeightPaintMode::Subtract;
  else if (in.erase && mode == WeightPaintMode::Subtract) mode = WeightPaintMode::Add;
  CommandWords w = command_words("paint-weights", {doc.selection().handles.front(), kModes[static_cast<int>(mode)],
                                                   center.x(), center.y(), center.z(), radius, strength_});
  if (mode == WeightPaintMode::Mix) w.push_back(CommandArg(weight_value_).word);
  w.push_back("falloff=" + CommandArg(falloff_).word);
  if (front_only_) {
    const Eigen::Vector3d d = view.normalized();
    w.push_back("front=" + CommandArg(d.x()).word + "," + CommandArg(d.y()).word + "," + CommandArg(d.z()).word);
  }
  if (mirror_x_) w.push_back("mirror");
  if (!in.locked.empty()) {
    std::string l = "locked=";
    for (size_t i = 0; i < in.locked.size(); ++i) l += (i ? "," : "") + std::to_string(in.locked[i]);
    w.push_back(l);
  }
  return w;
}

void PaintTool::cancel(Document& doc) {
  if (!painting_) return;
  doc.end_gesture();
  painting_ = false;
}

void PaintTool::draw_options(Document& doc) {
  int target = static_cast<int>(target_);
  ImGui::RadioButton("Mask", &target, 0);
  ImGui::SameLine();
  ImGui::RadioButton("Region", &target, 1);
  ImGui::SameLine();
  ImGui::RadioButton("Weights", &target, 2);
  target_ = static_cast<PaintTarget>(target);
  float r = float(radius_), s = float(strength_), f = float(falloff_);
  ImGui::SliderFloat("Radius", &r, 0.005f, 0.4f, "%.3f");
  ImGui::SliderFloat("Strength", &s, 0.0f, 1.0f, "%.3f", ImGuiSliderFlags_AlwaysClamp);
  ImGui::SliderFloat("Falloff", &f, 0.0f, 1.0f, "%.3f", ImGuiSliderFlags_AlwaysClamp);
  radius_ = r, strength_ = s, falloff_ = f;
  if (target_ == PaintTarget::Weights) draw_weight_options(doc);
  if (target_ == PaintTarget::Region) {
    if (ImGui::Button("New region")) region_ = doc.add_region();
    ImGui::SameLine();
    ImGui::TextDisabled("painting region %d", region_);
  }
}

void PaintTool::draw_weight_options(const Document& doc) {
  int mode = static_cast<int>(weight_mode_);
  ImGui::Combo("Mode", &mode, "Add\0Subtract\0Mix\0Smooth\0");
  weight_mode_ = static_cast<WeightPaintMode>(mode);
  if (weight_mode_ == WeightPaintMode::Mix) {
    float v = float(weight_value_);
    ImGui::SliderFloat("Value", &v, 0.0f, 1.0f, "%.3f", ImGuiSliderFlags_AlwaysClamp);
    weight_value_ = v;
  }
  ImGui::Checkbox("Front faces only", &front_only_);
  ImGui::SameLine();
  ImGui::Checkbox("X mirror", &mirror_x_);
  ImGui::PushTextWrapPos(0.0f);
  ImGui::BeginDisabled();
  if (!doc.has_weights()) ImGui::TextWrapped("bind first: there are no weights to paint");
  else if (doc.selection().handles.empty()) ImGui::TextWrapped("select a handle to paint its weights");
  else ImGui::TextWrapped("painting %s; Ctrl swaps Add and Subtract; locked handles (Weights panel) are kept",
                          handle_name(doc.rig(), doc.selection().handles.front()).c_str());
  ImGui::EndDisabled();
  ImGui::PopTextWrapPos();
}

}  // namespace dfm::editor
