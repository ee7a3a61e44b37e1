// The timeline under the viewport: transport (play / pause / loop), set and delete keys, key a mesh
// file, the in-between, time, speed and the sweep view (slice along x, y or z instead of time) above
// the ruler (timeline_ruler.h: scrub, keys).
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/editor/editor.h"
#include "app/editor/theme.h"
#include "core/anim/inbetween_method.h"

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
  if (ImGui::Button("Key (K)")) run_ui_command({"set-key"});
  flow.next(ItemFlow::button_width("Key mesh..."));
  if (ImGui::Button("Key mesh...")) {
    // The same file dialog as File > Open; the pick runs `key-mesh FILE T` at the time pressed.
    files_.show(FilePanel::Mode::Open, "Key mesh at " + format_time(doc_.time(), frame_rate_), "key-mesh", "",
                {CommandArg(doc_.time()).word});
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Key a whole mesh (any surface file, any connectivity) at the current time;\n"
                      "the animation passes through it (a transition joins other connectivities)");
  flow.next(ItemFlow::button_width("Delete key"));
  const int at = doc_.key_at(doc_.time());
  if (at < 0) ImGui::BeginDisabled();
  if (ImGui::Button("Delete key")) run_ui_command(command_words("delete-key", {doc_.keys()[at].time}));
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
  draw_timeline_toolbar();
  if (tool_ == Tool::SpaceTime) timeline_ruler_.set_band(space_time_tool_.window());
  else timeline_ruler_.set_band(std::nullopt);
  timeline_ruler_.draw(doc_, frame_rate_, error_popup_);
  if (tool_ == Tool::SpaceTime && timeline_ruler_.band()) {  // an edge dragged on the ruler
    const auto [t0, t1] = *timeline_ruler_.band();
    space_time_tool_.set_window(t0, t1);
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
  if (ImGui::Combo("##inbetween", &m, names, 3))
    run_ui_command(command_words("set-inbetween", {doc_.keys()[k].time, inbetween_method_name(static_cast<InbetweenMethod>(m))}));
  if (k < 0) ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("In-between of the key interval at the current time:\n"
                      "handles: the handle transforms are interpolated and skinned\n"
                      "ARAP: the two keyed meshes interpolated as rigidly as possible (Alexa 2002, 4.4)\n"
                      "linear: the vertices blended linearly\n"
                      "(ARAP and linear need one connectivity; a transition joins other meshes)");
}

}  // namespace dfm::editor
