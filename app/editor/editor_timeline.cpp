// The timeline under the viewport: transport (play / pause / loop), set and delete keys, key a mesh
// file, a ruler to scrub the animation manifold (drag), pose keys as diamonds and mesh keys as squares
// (drag to move, right-click to delete), and the sweep view (slice along x, y or z instead of time).
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/editor/editor.h"
#include "app/editor/theme.h"
#include "render/overlay_geometry.h"

namespace dfm::editor {

// Transport, keys, the in-between of the current interval, time (frame and seconds at the frame
// rate) and speed, the sweep axis and the key count: laid out in rows that wrap on a narrow window
// (ItemFlow), the timeline growing to hold them from the next frame on.
void Editor::draw_timeline_toolbar() {
  ItemFlow flow;
  flow.next(60);
  if (ImGui::Button(playing_ ? "Pause" : "Play", ImVec2(60, 0))) playing_ = !playing_;
  flow.next(ItemFlow::check_width("Loop"));
  ImGui::Checkbox("Loop", &loop_);
  flow.next(ItemFlow::button_width("Key (K)"));
  if (ImGui::Button("Key (K)")) doc_.set_key(doc_.time());
  flow.next(ItemFlow::button_width("Key mesh..."));
  if (ImGui::Button("Key mesh...")) {
    // The same file dialog as File > Open; the pick lands in Editor::draw_ui -> key_mesh_file.
    key_mesh_time_ = doc_.time();
    files_.show(FilePanel::Mode::Open, "Key mesh at " + format_time(key_mesh_time_, frame_rate_), "key-mesh");
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Key a whole mesh (any surface file, any connectivity) at the current time;\n"
                      "the animation passes through it (a transition joins other connectivities)");
  flow.next(ItemFlow::button_width("Delete key"));
  const int at = doc_.key_at(doc_.time());
  if (at < 0) ImGui::BeginDisabled();
  if (ImGui::Button("Delete key")) doc_.delete_key(at);
  if (at < 0) ImGui::EndDisabled();
  draw_inbetween_choice(flow);
  // Time as animation tools show it: a frame at the frame rate, and seconds.
  float frame = float(time_to_frame(doc_.time(), frame_rate_));
  const bool whole = std::abs(frame - std::round(frame)) < 0.05f;
  flow.next(96);
  ImGui::SetNextItemWidth(96);
  if (ImGui::DragFloat("##frame", &frame, 0.2f, 0.0f, 0.0f, whole ? "frame %.0f" : "frame %.1f"))
    doc_.set_time(std::max(0.0, double(frame) / frame_rate_));
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Current frame (drag or type; the ruler scrubs too)");
  char secs[32];
  std::snprintf(secs, sizeof secs, "%.3f s", display_value(doc_.time(), 3));
  flow.next(ImGui::CalcTextSize(secs).x);
  ImGui::AlignTextToFramePadding();
  ImGui::TextDisabled("%s", secs);
  flow.next(64);
  float fps = float(frame_rate_);
  ImGui::SetNextItemWidth(64);
  if (ImGui::DragFloat("##fps", &fps, 0.1f, 1.0f, 240.0f, "%.0f fps", ImGuiSliderFlags_AlwaysClamp)) frame_rate_ = fps;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Frame rate: frames a second of animation time");
  flow.next(56);
  float speed = float(play_speed_);
  ImGui::SetNextItemWidth(56);
  if (ImGui::DragFloat("##speed", &speed, 0.01f, 0.05f, 8.0f, "x%.2f")) play_speed_ = speed;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Playback speed");
  const char* axes[] = {"t", "x", "y", "z"};
  int sweep = slice_axis_ == SliceAxis::T ? 0 : static_cast<int>(slice_axis_) + 1;
  const float combo_w = 44;
  flow.next(combo_w + ImGui::GetStyle().ItemInnerSpacing.x + ImGui::CalcTextSize("Slice").x);
  ImGui::SetNextItemWidth(combo_w);
  if (ImGui::Combo("Slice", &sweep, axes, 4)) slice_axis_ = sweep == 0 ? SliceAxis::T : static_cast<SliceAxis>(sweep - 1);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("t: the animation at a time; x, y, z: the sweep through time along that axis");
  if (slice_axis_ != SliceAxis::T) {
    flow.next(120);
    float sv = float(sweep_value_);
    ImGui::SetNextItemWidth(120);
    if (ImGui::SliderFloat("##sweep", &sv, 0.0f, 1.0f, "%.2f")) sweep_value_ = sv;
  }
  char keys[32];
  std::snprintf(keys, sizeof keys, "%d key%s", int(doc_.keys().size()), doc_.keys().size() == 1 ? "" : "s");
  flow.next(ImGui::CalcTextSize(keys).x);
  ImGui::AlignTextToFramePadding();
  ImGui::TextDisabled("%s", keys);
  // Room for the toolbar's rows and a ruler of at least 56 px (applied by the next frame's layout).
  const ImGuiStyle& st = ImGui::GetStyle();
  timeline_h_ = flow.rows() * ImGui::GetFrameHeightWithSpacing() + 2 * st.WindowPadding.y + 56 * ImGui::GetIO().FontGlobalScale;
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
  // Ticks on whole frames (1, 2 or 5 times a power of ten), labelled with the frame number, about
  // one per 60 px.
  const double frames = std::max(1e-9, (t1 - t0) * frame_rate_);
  const double fstep = std::max(1.0, gl::nice_spacing(frames, std::max(2, int(w / 60))));
  for (double f = std::ceil(t0 * frame_rate_ / fstep) * fstep; f <= t1 * frame_rate_ + 1e-6; f += fstep) {
    const float x = x_of(f / frame_rate_);
    dl->AddLine(ImVec2(x, p0.y), ImVec2(x, p0.y + 8), IM_COL32(110, 114, 122, 255));
    char lab[16];
    std::snprintf(lab, sizeof lab, "%.0f", f);
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
      const double nt = std::max(0.0, std::round(t_of(x) * frame_rate_) / frame_rate_);  // snap to whole frames
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
    const std::string next_join =
        hover_key + 1 < int(doc_.keys().size()) ? interval_join_label(interval_join(doc_, hover_key)) : "(the last key)";
    if (k.is_mesh())
      ImGui::SetTooltip("mesh key %d at %s: %s\n%d vertices, %d triangles\nto the next key: %s\n"
                        "(drag to move, right-click to delete)",
                        hover_key, format_time(k.time, frame_rate_).c_str(),
                        std::filesystem::path(k.mesh_path).filename().string().c_str(), k.mesh.num_vertices(),
                        k.mesh.num_faces(), next_join.c_str());
    else
      ImGui::SetTooltip("key %d at %s\nto the next key: %s\n(drag to move, right-click to delete)", hover_key,
                        format_time(k.time, frame_rate_).c_str(), next_join.c_str());
  }
}

// The in-between of the key interval holding the current time (one undo step per change); a
// transition (the keys' meshes differ) has no choice: it says so instead.
void Editor::draw_inbetween_choice(ItemFlow& flow) {
  const int k = interval_at(doc_, doc_.time());
  const int last = static_cast<int>(doc_.keys().size()) - 1;
  const IntervalJoin join = k >= 0 && k < last ? interval_join(doc_, k) : IntervalJoin::Handles;
  if (k >= 0 && join == IntervalJoin::Transition) {
    const char* text = interval_join_label(join);
    flow.next(ImGui::CalcTextSize(text).x);
    ImGui::AlignTextToFramePadding();
    ImGui::TextColored(ImVec4(0.45f, 0.80f, 0.78f, 1.0f), "%s", text);  // the mesh keys' teal
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("These two keys have different meshes: the animation passes from one to the other by a\n"
                        "transition (Southern 2008), and the rig's handles do not apply to its in-betweens.");
    return;
  }
  const char* names[] = {"handles", "ARAP", "linear"};
  int m = k >= 0 ? static_cast<int>(doc_.keys()[k].inbetween) : 0;
  flow.next(86);
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
