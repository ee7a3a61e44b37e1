// The timeline under the viewport: transport (play / pause / loop), set and delete keys, key a mesh
// file, a ruler to scrub the animation manifold (drag), pose keys as diamonds and mesh keys as squares
// (drag to move, right-click to delete), and the sweep view (slice along x, y or z instead of time).
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/editor/editor.h"

namespace dfm::editor {

// Transport, keys, the in-between of the current interval, time and speed, and the sweep axis.
void Editor::draw_timeline_toolbar() {
  if (ImGui::Button(playing_ ? "Pause" : "Play", ImVec2(60, 0))) playing_ = !playing_;
  ImGui::SameLine();
  ImGui::Checkbox("Loop", &loop_);
  ImGui::SameLine();
  if (ImGui::Button("Key (K)")) doc_.set_key(doc_.time());
  ImGui::SameLine();
  if (ImGui::Button("Key mesh...")) {
    // The same file dialog as File > Open; the pick lands in Editor::draw_ui -> key_mesh_file.
    key_mesh_time_ = doc_.time();
    char title[64];
    std::snprintf(title, sizeof title, "Key mesh at t = %.3f", key_mesh_time_);
    files_.show(FilePanel::Mode::Open, title, "key-mesh");
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Key a whole mesh (any surface file, any connectivity) at the current time;\n"
                      "the animation passes through it (a transition joins other connectivities)");
  ImGui::SameLine();
  const int at = doc_.key_at(doc_.time());
  if (at < 0) ImGui::BeginDisabled();
  if (ImGui::Button("Delete key")) doc_.delete_key(at);
  if (at < 0) ImGui::EndDisabled();
  ImGui::SameLine();
  draw_inbetween_choice();
  ImGui::SameLine();
  float t = float(doc_.time());
  ImGui::SetNextItemWidth(70);
  if (ImGui::DragFloat("##time", &t, 0.01f, 0.0f, 0.0f, "t %.3f")) doc_.set_time(std::max(0.0f, t));
  ImGui::SameLine();
  float speed = float(play_speed_);
  ImGui::SetNextItemWidth(56);
  if (ImGui::DragFloat("##speed", &speed, 0.01f, 0.05f, 8.0f, "x%.2f")) play_speed_ = speed;
  ImGui::SameLine();
  ImGui::TextDisabled("|");
  ImGui::SameLine();
  const char* axes[] = {"t", "x", "y", "z"};
  int sweep = slice_axis_ == SliceAxis::T ? 0 : static_cast<int>(slice_axis_) + 1;
  ImGui::SetNextItemWidth(60);
  if (ImGui::Combo("Slice", &sweep, axes, 4)) slice_axis_ = sweep == 0 ? SliceAxis::T : static_cast<SliceAxis>(sweep - 1);
  if (slice_axis_ != SliceAxis::T) {
    ImGui::SameLine();
    float sv = float(sweep_value_);
    ImGui::SetNextItemWidth(120);
    if (ImGui::SliderFloat("##sweep", &sv, 0.0f, 1.0f, "%.2f")) sweep_value_ = sv;
  }
  ImGui::SameLine();
  ImGui::TextDisabled("%d key(s)", int(doc_.keys().size()));
}

void Editor::draw_timeline() {
  const auto& keys = doc_.keys();
  // Range: the keys' span padded, at least [0, 1].
  double t0 = 0, t1 = 1;
  if (!keys.empty()) {
    t0 = std::min(0.0, keys.front().time);
    t1 = std::max(1.0, keys.back().time);
  }
  t1 = std::max(t1, doc_.time());

  draw_timeline_toolbar();

  // Ruler.
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  const float w = ImGui::GetContentRegionAvail().x, h = std::max(30.0f, ImGui::GetContentRegionAvail().y);
  const float pad = 10;
  auto x_of = [&](double time) { return p0.x + pad + float((time - t0) / (t1 - t0)) * (w - 2 * pad); };
  auto t_of = [&](float x) { return t0 + (t1 - t0) * double(x - p0.x - pad) / double(w - 2 * pad); };
  dl->AddRectFilled(p0, ImVec2(p0.x + w, p0.y + h), IM_COL32(24, 25, 28, 255), 3.0f);
  double step = std::pow(10.0, std::floor(std::log10((t1 - t0) / 5.0)));
  for (double m : {2.0, 5.0})  // at most about ten labelled ticks
    if ((t1 - t0) / step > 10.0) step *= m == 2.0 ? 2.0 : 2.5;
  for (double s = std::ceil(t0 / step) * step; s <= t1 + 1e-9; s += step) {
    const float x = x_of(s);
    dl->AddLine(ImVec2(x, p0.y), ImVec2(x, p0.y + 8), IM_COL32(110, 114, 122, 255));
    char lab[16];
    std::snprintf(lab, sizeof lab, "%g", std::round(s / step) * step);
    dl->AddText(ImVec2(x + 3, p0.y + 1), IM_COL32(130, 134, 142, 255), lab);
  }
  if (keys.size() >= 2)  // the animated span
    dl->AddRectFilled(ImVec2(x_of(keys.front().time), p0.y + h - 10), ImVec2(x_of(keys.back().time), p0.y + h - 6),
                      IM_COL32(70, 110, 170, 200), 2.0f);
  ImGui::InvisibleButton("ruler", ImVec2(w, h), ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
  const bool hovered = ImGui::IsItemHovered();
  const float mx = ImGui::GetIO().MousePos.x, my = ImGui::GetIO().MousePos.y;
  const float ky = p0.y + h * 0.55f;
  int hover_key = -1;
  for (size_t i = 0; i < keys.size(); ++i)
    if (hovered && std::abs(mx - x_of(keys[i].time)) < 7 && std::abs(my - ky) < 10) hover_key = int(i);
  if (ImGui::IsItemClicked(ImGuiMouseButton_Left)) {
    if (hover_key >= 0) {
      drag_ = Drag::Key;
      drag_key_ = hover_key;
    } else {
      drag_ = Drag::Timeline;
    }
  }
  if (ImGui::IsItemClicked(ImGuiMouseButton_Right) && hover_key >= 0) doc_.delete_key(hover_key);
  if (drag_ == Drag::Timeline) {
    doc_.set_time(std::clamp(t_of(mx), 0.0, 1e9));
    if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) drag_ = Drag::None;
  }
  if (drag_ == Drag::Key) {
    const float x = std::clamp(mx, p0.x + pad, p0.x + w - pad);
    dl->AddLine(ImVec2(x, p0.y), ImVec2(x, p0.y + h), IM_COL32(255, 210, 90, 160));
    if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
      const double nt = std::max(0.0, std::round(t_of(x) * 100.0) / 100.0);  // snap to 0.01
      if (drag_key_ >= 0 && drag_key_ < int(keys.size()) && std::abs(nt - keys[drag_key_].time) > 1e-9) {
        try {
          doc_.move_key(drag_key_, nt);
        } catch (const std::exception& e) {
          error_popup_ = e.what();
        }
      }
      drag_ = Drag::None;
      drag_key_ = -1;
    }
  }
  // Intervals with an ARAP or linear in-between: a bar between their keys (green, grey).
  for (size_t i = 0; i + 1 < doc_.keys().size(); ++i) {
    const InbetweenMethod m = doc_.keys()[i].inbetween;
    if (m == InbetweenMethod::Handles) continue;
    const ImU32 c = m == InbetweenMethod::Arap ? IM_COL32(110, 200, 120, 200) : IM_COL32(150, 150, 150, 200);
    dl->AddLine(ImVec2(x_of(doc_.keys()[i].time), ky), ImVec2(x_of(doc_.keys()[i + 1].time), ky), c, 3.0f);
  }
  // Pose keys are amber diamonds, mesh keys teal squares.
  for (size_t i = 0; i < doc_.keys().size(); ++i) {
    const float x = x_of(doc_.keys()[i].time), r = 6;
    const bool hot = int(i) == hover_key || int(i) == drag_key_;
    if (doc_.keys()[i].is_mesh()) {
      const float q = r - 1;
      dl->AddRectFilled(ImVec2(x - q, ky - q), ImVec2(x + q, ky + q),
                        hot ? IM_COL32(150, 240, 235, 255) : IM_COL32(70, 195, 190, 255), 1.5f);
    } else {
      const ImU32 c = hot ? IM_COL32(255, 220, 110, 255) : IM_COL32(235, 180, 60, 255);
      dl->AddQuadFilled(ImVec2(x, ky - r), ImVec2(x + r, ky), ImVec2(x, ky + r), ImVec2(x - r, ky), c);
    }
  }
  const float xt = x_of(doc_.time());
  dl->AddLine(ImVec2(xt, p0.y), ImVec2(xt, p0.y + h), IM_COL32(90, 160, 255, 255), 2.0f);
  dl->AddTriangleFilled(ImVec2(xt - 5, p0.y), ImVec2(xt + 5, p0.y), ImVec2(xt, p0.y + 6), IM_COL32(90, 160, 255, 255));
  if (hover_key >= 0) {
    const SceneKey& k = doc_.keys()[hover_key];
    if (k.is_mesh())
      ImGui::SetTooltip("mesh key %d at t = %.3f: %s\n%d vertices, %d triangles\nin-between to the next key: %s\n"
                        "(drag to move, right-click to delete)",
                        hover_key, k.time, std::filesystem::path(k.mesh_path).filename().string().c_str(),
                        k.mesh.num_vertices(), k.mesh.num_faces(), inbetween_method_name(k.inbetween));
    else
      ImGui::SetTooltip("key %d at t = %.3f\nin-between to the next key: %s\n(drag to move, right-click to delete)",
                        hover_key, k.time, inbetween_method_name(k.inbetween));
  }
}

// The in-between of the key interval holding the current time (one undo step per change).
void Editor::draw_inbetween_choice() {
  const auto& keys = doc_.keys();
  int k = -1;
  for (size_t i = 0; i + 1 < keys.size(); ++i)
    if (keys[i].time <= doc_.time() + 1e-9) k = int(i);
  if (k >= 0 && doc_.time() > keys.back().time + 1e-9) k = -1;  // past the last key: no interval
  const char* names[] = {"handles", "ARAP", "linear"};
  int m = k >= 0 ? static_cast<int>(keys[k].inbetween) : 0;
  if (k < 0) ImGui::BeginDisabled();
  ImGui::SetNextItemWidth(86);
  if (ImGui::Combo("##inbetween", &m, names, 3)) doc_.set_key_inbetween(k, static_cast<InbetweenMethod>(m));
  if (k < 0) ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("In-between of the key interval at the current time:\n"
                      "handles: the handle transforms are interpolated and skinned\n"
                      "ARAP: the two keyed meshes interpolated as rigidly as possible (Alexa 2002, 4.4)\n"
                      "linear: the vertices blended linearly\n"
                      "(ARAP and linear need one connectivity; a transition joins other meshes)");
}

}  // namespace dfm::editor
