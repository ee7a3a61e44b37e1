// The ImGui panels: menu bar, tools + outliner (left), view / bind / weights / transform (right),
// the viewport HUD and the popups. Panels read the Document and issue its commands.
#include <imgui.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "app/editor/editor.h"
#include "core/bind/weight_difference.h"
#include "app/editor/theme.h"

#include "core/anim/slice.h"
#include "core/mesh/io.h"
#include "core/scene/command.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/view/color.h"
#include "core/view/colormap.h"

namespace dfm::editor {
namespace {

void help_marker(const char* text) {
  ImGui::SameLine();
  ImGui::TextDisabled("(?)");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}

bool tool_button(const char* label, bool active, const char* tip, float w) {
  if (active) ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyle().Colors[ImGuiCol_HeaderActive]);
  const bool pressed = ImGui::Button(label, ImVec2(w, 0));
  if (active) ImGui::PopStyleColor();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tip);
  return pressed;
}

ImU32 to_u32(const Eigen::Vector3f& linear) {
  const Eigen::Vector3f c = view::linear_to_display(linear);
  return ImGui::GetColorU32(ImVec4(c.x(), c.y(), c.z(), 1.0f));
}

// The rig's handles as tree nodes by type, each drawn by row(h) (h: its number, what scripts take).
void outliner_tree(const Rig& rig, const std::function<void(int)>& row) {
  int h = 0;
  const int np = num_point_handles(rig), nb = rig.skeleton.num_bones();
  ImGui::SetNextItemOpen(true, ImGuiCond_Once);
  if (ImGui::TreeNode("points", "Points (%d)", np)) {
    for (int i = 0; i < np; ++i) row(h + i);
    ImGui::TreePop();
  }
  h += np;
  ImGui::SetNextItemOpen(true, ImGuiCond_Once);
  if (ImGui::TreeNode("bones", "Bones (%d)", nb)) {
    // Indent children under parents to show the hierarchy.
    for (int i : bones_topological_order(rig.skeleton)) {
      int depth = 0;
      for (int p = rig.skeleton.bones[i].parent; p >= 0 && depth < 16; p = rig.skeleton.bones[p].parent) ++depth;
      if (depth) ImGui::Indent(8.0f * depth);
      row(h + i);
      if (depth) ImGui::Unindent(8.0f * depth);
    }
    ImGui::TreePop();
  }
  h += nb;
  if (ImGui::TreeNode("cages", "Cages (%d)", int(rig.cages.size()))) {
    for (const Cage& c : rig.cages) {
      if (ImGui::TreeNode(c.name.empty() ? "cage" : c.name.c_str())) {
        for (int v = 0; v < c.mesh.num_vertices(); ++v) row(h + v);
        ImGui::TreePop();
      }
      h += c.mesh.num_vertices();
    }
    ImGui::TreePop();
  } else {
    h += num_cage_vertices(rig);
  }
  if (ImGui::TreeNode("regions", "Regions (%d)", int(rig.regions.size()))) {
    for (size_t r = 0; r < rig.regions.size(); ++r) row(h + int(r));
    ImGui::TreePop();
  }
}

}  // namespace

// A menu item or button of a table command is enabled when the command's poll allows it.
bool Editor::available(const char* command) const { return command_unavailable(command, doc_).empty(); }

PanelLayout Editor::panel_layout() const {
  int w = 0, h = 0;
  glfwGetWindowSize(window_, &w, &h);
  const float scale = ImGui::GetIO().FontGlobalScale;
  // Before the first frame ImGui has no font size yet: the default font's menu bar height.
  const float top = std::max(ImGui::GetFrameHeight(), 21.0f * scale);
  return layout_panels(w, h, top, timeline_h_, scale);
}

void Editor::draw_ui() {
  draw_menu_bar();
  const PanelLayout l = panel_layout();
  const ImGuiWindowFlags fixed = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoBringToFrontOnFocus;
  auto place = [](const Rect& r) {
    ImGui::SetNextWindowPos(ImVec2(float(r.x), float(r.y)));
    ImGui::SetNextWindowSize(ImVec2(float(r.w), float(r.h)));
  };
  place(l.left);
  ImGui::Begin("##left", nullptr, fixed);
  draw_left_panel();
  ImGui::End();

  place(l.right);
  ImGui::Begin("##right", nullptr, fixed);
  draw_right_panel();
  ImGui::End();

  place(l.timeline);
  ImGui::Begin("##timeline", nullptr, fixed | ImGuiWindowFlags_NoScrollbar);
  draw_timeline();
  ImGui::End();

  viewport_ = l.viewport;
  draw_viewport_hud();

  if (files_.draw()) {  // the chosen file completes its command's line
    const CommandWords words = files_.command_line();
    if (words[0] == "open") open_any(words[1]);  // asks first when the document has unsaved changes
    else if (words[0] == "transfer-weights" && words.size() == 2 && file_extension(words[1]) != "json")
      files_.show(FilePanel::Mode::Open, "Weights of " + words[1] + " (.dmat)", "transfer-weights", "", {}, {words[1]});
    else run_ui_command(words);
  }
  draw_quit_prompt();
  draw_error_popup();
  draw_export_report();
}

void Editor::draw_menu_bar() {
  if (!ImGui::BeginMainMenuBar()) return;
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("Open...", "Ctrl+O")) files_.show(FilePanel::Mode::Open, "Open", "open");
    if (ImGui::BeginMenu("Open recent", !files_.recent().empty())) {
      for (const auto& r : files_.recent())
        if (ImGui::MenuItem(r.c_str())) open_any(r);
      ImGui::EndMenu();
    }
    if (ImGui::MenuItem("Replace surface...", nullptr, false, available("replace-surface")))
      files_.show(FilePanel::Mode::Open, "Replace surface (the rig stays)", "replace-surface");
    if (ImGui::MenuItem("Load skeleton (.tgf)...")) files_.show(FilePanel::Mode::Open, "Load skeleton", "load-skeleton");
    if (ImGui::MenuItem("Load cage...")) files_.show(FilePanel::Mode::Open, "Load cage", "load-cage");
    ImGui::Separator();
    if (ImGui::MenuItem("Save scene", "Ctrl+S")) {
      if (doc_.path().empty()) files_.show(FilePanel::Mode::Save, "Save scene as", "save-scene", "scene.scene.json");
      else save_scene_as(doc_.path());
    }
    if (ImGui::MenuItem("Save scene as...")) files_.show(FilePanel::Mode::Save, "Save scene as", "save-scene", "scene.scene.json");
    if (ImGui::MenuItem("Save posed mesh...", nullptr, false, available("save-posed")))
      files_.show(FilePanel::Mode::Save, "Save posed mesh", "save-posed", "posed.obj");
    if (ImGui::MenuItem("Save all frames...", nullptr, false, available("save-frames")))
      files_.show(FilePanel::Mode::Save, "Save frames (name####.obj)", "save-frames", "frame.obj");
    if (ImGui::MenuItem("Save screenshot...")) files_.show(FilePanel::Mode::Save, "Save screenshot", "screenshot", "screenshot.png");
    if (ImGui::BeginMenu("Export glTF", available("export-gltf"))) {
      // glTF stores 4 joints per set: 8 keeps more of the bind's weights at twice the attribute size.
      for (int k : {4, 8}) {
        const std::string label = std::to_string(k) + " influences per vertex (.glb)...";
        if (ImGui::MenuItem(label.c_str()))
          files_.show(FilePanel::Mode::Save, "Export glTF (" + std::to_string(k) + " influences)", "export-gltf", "scene.glb",
                      {std::to_string(k)});
      }
      ImGui::EndMenu();
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", "Ctrl+Q")) request_quit();
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Edit")) {
    const std::string u = "Undo " + doc_.undo_name(), r = "Redo " + doc_.redo_name();
    if (ImGui::MenuItem(u.c_str(), "Ctrl+Z", false, available("undo"))) run_ui_command({"undo"});
    if (ImGui::MenuItem(r.c_str(), "Ctrl+Shift+Z", false, available("redo"))) run_ui_command({"redo"});
    ImGui::Separator();
    if (ImGui::MenuItem("Delete selected", "Del", false, !doc_.selection().handles.empty()))
      run_ui_command(command_words("delete-handles", doc_.selection().handles));
    if (ImGui::MenuItem("Reset pose")) run_ui_command({"reset-pose"});
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    if (ImGui::MenuItem("Frame selection", "F")) frame_selection();
    if (ImGui::MenuItem("Frame all", "Home")) frame_all();
    ImGui::MenuItem("Orthographic", "5", &cam_.orthographic);
    ImGui::MenuItem("Wireframe", "Z", &wireframe_);
    ImGui::MenuItem("Grid", nullptr, &show_grid_);
    ImGui::MenuItem("Handles", nullptr, &show_handles_);
    ImGui::Separator();
    for (auto p : {view::ViewPreset::Front, view::ViewPreset::Back, view::ViewPreset::Left, view::ViewPreset::Right,
                   view::ViewPreset::Top, view::ViewPreset::Bottom, view::ViewPreset::Iso})
      if (ImGui::MenuItem(view::view_preset_name(p))) view::set_view_preset(cam_, p), sync_camera_to_doc();
    ImGui::EndMenu();
  }
  // Document name and dirty flag on the right of the bar.
  std::string title = doc_.title();
  if (doc_.dirty()) title += "  *";
  ImGui::SameLine(ImGui::GetWindowWidth() - ImGui::CalcTextSize(title.c_str()).x - 16);
  ImGui::TextDisabled("%s", title.c_str());
  ImGui::EndMainMenuBar();
}

void Editor::draw_left_panel() {
  draw_tools_panel();
  ImGui::Spacing();
  draw_outliner();
}

void Editor::draw_tools_panel() {
  ImGui::TextDisabled("TOOLS");
  const float w = (ImGui::GetContentRegionAvail().x - ImGui::GetStyle().ItemSpacing.x) * 0.5f;
  if (tool_button("Select  Q", tool_ == Tool::Select, "Select handles; drag points, joints and cage vertices (rest pose)", w)) tool_ = Tool::Select;
  ImGui::SameLine();
  if (tool_button("Point  P", tool_ == Tool::PlacePoint, "Click the surface to place a point handle", w)) tool_ = Tool::PlacePoint;
  if (tool_button("Bones  B", tool_ == Tool::DrawBone, "Click joints of a chain; right-click or Enter finishes; start on a joint to branch", w)) tool_ = Tool::DrawBone;
  ImGui::SameLine();
  if (tool_button("Paint  V", tool_ == Tool::Paint, "Paint the shape-preservation mask or a region; Ctrl/Shift erases", w)) tool_ = Tool::Paint;
  if (tool_button("Move  G", tool_ == Tool::Pose && !gizmo_rotate_, "Pose: translate along axes / planes", w)) tool_ = Tool::Pose, gizmo_rotate_ = false;
  ImGui::SameLine();
  if (tool_button("Rotate  R", tool_ == Tool::Pose && gizmo_rotate_, "Pose: rotate with the ring (view axis) or the trackball inside it", w)) tool_ = Tool::Pose, gizmo_rotate_ = true;
  if (tool_button("Pair", tool_ == Tool::Pair, "Pick a point on a key and its partner on the next: a transition sends one to the other", w)) {
    tool_ = Tool::Pair;
    pair_tool_.cancel();
  }
  ImGui::SameLine();
  if (tool_button("Sculpt  U", tool_ == Tool::Sculpt, "Shape keys: brush a free region, drag a handle inside it (C1 or C2), key the shape; or paint a local transition between two mesh keys", w))
    tool_ = Tool::Sculpt;
  if (tool_button("Space-time", tool_ == Tool::SpaceTime, "Drag the animation itself: a region over a time window follows a handle (Southern ch. 4)", w))
    tool_ = Tool::SpaceTime;

  ImGui::Separator();
  switch (tool_) {
    case Tool::PlacePoint:
      ImGui::Checkbox("Inside the volume", &place_inside_);
      help_marker("On: halfway between where the cursor ray enters and leaves the surface. Off: on the surface.");
      break;
    case Tool::DrawBone:
      ImGui::TextWrapped("%d joint(s) in the chain. Right-click / Enter: finish, Esc: cancel.", bone_tool_.joints());
      break;
    case Tool::Paint: {
      paint_tool_.draw_options(doc_);  // paint_tool.h
      if (weight_view_ != WeightView::Mask && ImGui::Button("Show mask")) weight_view_ = WeightView::Mask;
      break;
    }
    case Tool::Pose:
      ImGui::TextWrapped("Select a handle, then drag the gizmo. Method: %s", skin_method_name(doc_.method()));
      if (ImGui::Button("Reset pose")) run_ui_command({"reset-pose"});
      break;
    case Tool::Pair:
      ImGui::TextWrapped("%s", pair_tool_.hint(doc_).c_str());
      if (ImGui::Button("Clear pairs")) run_ui_command({"clear-pairs"});
      break;
    case Tool::Sculpt:
      sculpt_tool_.draw_options(doc_, [this](const CommandWords& w) { return run_ui_command(w); });  // sculpt_tool.h
      break;
    case Tool::SpaceTime:
      space_time_tool_.draw_options(doc_, [this](const CommandWords& w) { return run_ui_command(w); });
      break;
    case Tool::Select:
      ImGui::TextWrapped("Click to select (Shift: add). Drag handles before binding. Click the surface to list a vertex's weights.");
      break;
  }
}

void Editor::draw_outliner() {
  ImGui::TextDisabled("OUTLINER");
  const Rig& rig = doc_.rig();
  const auto& sel = doc_.selection().handles;
  ImGui::BeginChild("outliner", ImVec2(0, 0), true, ImGuiWindowFlags_HorizontalScrollbar);
  const bool fast = doc_.posing().fast;
  const std::vector<HandleConstraint> states = doc_.handle_states();
  auto row = [&](int h) {
    const bool is_sel = std::find(sel.begin(), sel.end(), h) != sel.end();
    ImGui::PushID(h);
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const float sz = ImGui::GetTextLineHeight();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const Eigen::Vector4f sel_body = selection_style().body, sel_line = selection_style().outline;
    // The swatch is the handle's viewport colour; selected, the viewport's selection look (body, outline).
    dl->AddRectFilled(ImVec2(p.x, p.y + 2), ImVec2(p.x + sz - 4, p.y + sz - 2),
                      is_sel ? ImGui::GetColorU32(ImVec4(sel_body.x(), sel_body.y(), sel_body.z(), 1)) : to_u32(handle_color(h)),
                      2.0f);
    if (is_sel)
      dl->AddRect(ImVec2(p.x - 1, p.y + 1), ImVec2(p.x + sz - 3, p.y + sz - 1),
                  ImGui::GetColorU32(ImVec4(sel_line.x(), sel_line.y(), sel_line.z(), 1)), 2.0f, 0, 1.5f);
    // FAST's state as the viewport marks it: a dark centre pinned, a white one free.
    const HandleConstraint state = fast ? states[h] : HandleConstraint::Position;
    if (state != HandleConstraint::Position)
      dl->AddCircleFilled(ImVec2(p.x + 0.5f * (sz - 4), p.y + 0.5f * sz), 0.18f * sz,
                          state == HandleConstraint::Fixed ? IM_COL32(20, 20, 26, 255) : IM_COL32(255, 255, 255, 255));
    ImGui::Dummy(ImVec2(sz - 2, sz));
    ImGui::SameLine();
    // Number (what scripts take), name and, where the row has room, FAST's state in words.
    std::string label = outliner_label(doc_, h, true);
    if (ImGui::CalcTextSize(label.c_str()).x > ImGui::GetContentRegionAvail().x) label = outliner_label(doc_, h, false);
    if (ImGui::Selectable(label.c_str(), is_sel)) select_handle(h, ImGui::GetIO().KeyShift || ImGui::GetIO().KeyCtrl);
    if (fast && ImGui::IsItemHovered())
      ImGui::SetTooltip("%s: %s (FAST)", outliner_label(doc_, h, false).c_str(), constraint_state_name(state));
    if (ImGui::BeginPopupContextItem("ctx")) {
      static char buf[128];
      if (ImGui::IsWindowAppearing()) std::snprintf(buf, sizeof buf, "%s", handle_name(rig, h).c_str());
      ImGui::SetNextItemWidth(180);
      if (ImGui::InputText("Name", buf, sizeof buf, ImGuiInputTextFlags_EnterReturnsTrue)) {
        run_ui_command(command_words("rename-handle", {h, std::string(buf)}));
        ImGui::CloseCurrentPopup();
      }
      if (ImGui::MenuItem("Delete")) run_ui_command(command_words("delete-handles", std::vector<int>{h}));
      ImGui::EndPopup();
    }
    ImGui::PopID();
  };
  outliner_tree(rig, row);
  if (!sel.empty()) {
    ImGui::Separator();
    if (ImGui::Button("Delete selected")) run_ui_command(command_words("delete-handles", sel));
    if (sel.size() == 2 && handle_ref(rig, sel[0]).kind == HandleKind::Point &&
        handle_ref(rig, sel[1]).kind == HandleKind::Point) {
      ImGui::SameLine();
      if (ImGui::Button("Pseudo-edge")) run_ui_command(command_words("pseudo-edge", {sel[0], sel[1]}));
    }
  }
  ImGui::EndChild();
}

namespace {
constexpr const char* kSections[] = {"view", "bind", "weights", "transform", "posing"};
}  // namespace

void Editor::draw_right_panel() {
  // --ui panels=...: the sections it names open, the others closed (once).
  auto header = [&](const char* label, int index) {
    if (open_sections_ >= 0) ImGui::SetNextItemOpen((open_sections_ >> index) & 1, ImGuiCond_Always);
    return ImGui::CollapsingHeader(label, ImGuiTreeNodeFlags_DefaultOpen);
  };
  if (header("View", 0)) draw_view_section();
  if (header("Bind", 1)) draw_bind_section();
  if (header("Weights", 2)) draw_weights_section();
  if (header("Transform", 3)) draw_transform_section();
  if (header("Posing", 4)) draw_posing_section();
  open_sections_ = -1;
  draw_shape_space_section();  // its own header (closed by default)
}

bool Editor::panel_ui_option(const std::string& key, const std::string& value) {
  if (key != "panels") return false;
  int mask = 0;
  for (size_t pos = 0; pos <= value.size();) {
    size_t end = value.find(':', pos);
    if (end == std::string::npos) end = value.size();
    const std::string name = value.substr(pos, end - pos);
    pos = end + 1;
    if (name.empty()) continue;
    const auto it = std::find(std::begin(kSections), std::end(kSections), name);
    if (it == std::end(kSections))
      throw Error("--ui: panels takes view, bind, weights, transform and posing joined by ':', got '" + name + "'");
    mask |= 1 << int(it - std::begin(kSections));
  }
  open_sections_ = mask;
  return true;
}

void Editor::draw_view_section() {
  bool persp = !cam_.orthographic;
  if (ImGui::RadioButton("Perspective", persp)) cam_.orthographic = false;
  ImGui::SameLine();
  if (ImGui::RadioButton("Ortho", !persp)) cam_.orthographic = true;
  ItemFlow flow;
  for (auto [label, value] : {std::pair<const char*, bool*>{"Wireframe", &wireframe_}, {"Grid", &show_grid_},
                              {"Handles", &show_handles_}}) {
    flow.next(ItemFlow::check_width(label));
    ImGui::Checkbox(label, value);
  }
  const float bw = (ImGui::GetContentRegionAvail().x - 3 * ImGui::GetStyle().ItemSpacing.x) / 4;
  int i = 0;
  for (auto p : {view::ViewPreset::Front, view::ViewPreset::Right, view::ViewPreset::Top, view::ViewPreset::Iso}) {
    if (i++) ImGui::SameLine();
    if (ImGui::Button(view::view_preset_name(p), ImVec2(bw, 0))) view::set_view_preset(cam_, p), sync_camera_to_doc();
  }
  if (ImGui::Button("Frame all", ImVec2(2 * bw + ImGui::GetStyle().ItemSpacing.x, 0))) frame_all();
  ImGui::SameLine();
  if (ImGui::Button("Frame selection", ImVec2(-1, 0))) frame_selection();
}

void Editor::draw_bind_section() {
  if (bind_.running()) {
    const BindProgress p = bind_.progress();
    char overlay[96];
    std::snprintf(overlay, sizeof overlay, "%s  %.0f%%", p.stage.c_str(), 100.0 * p.fraction);
    ImGui::ProgressBar(float(p.fraction), ImVec2(-1, 0), overlay);
    ImGui::TextDisabled("%.1f s, UI %.0f ms max", bind_.elapsed_seconds(), bind_tally_.max_ms);
    ImGui::SameLine();
    if (ImGui::Button(bind_.cancel_requested() ? "Cancelling..." : "Cancel", ImVec2(-1, 0))) bind_.cancel();
    return;
  }
  bool monotone = doc_.bind_settings().monotone;
  if (ImGui::Checkbox("Monotone weights", &monotone))  // one undo step; takes effect at the next bind
    run_ui_command({"bind-monotone", monotone ? "on" : "off"});
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("No local maxima or minima away from the handles (Jacobson 2013, ch. 5); slower bind");
  int additional = doc_.bind_settings().additional_weights;
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.4f);
  if (ImGui::InputInt("Additional weights", &additional, 1, 5) && additional >= 0 && additional <= kMaxAdditionalWeights)
    run_ui_command({"bind-additional", std::to_string(additional)});  // one undo step; at the next bind
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Extra weight functions whose transformations FAST solves (Jacobson 2013, 7.3.3):\n"
                      "more freedom where fully constrained handles pinch. Takes effect at the next bind.");
  const bool can = available("bind");
  if (!can) ImGui::BeginDisabled();
  if (ImGui::Button(doc_.has_weights() ? "Rebind" : "Bind", ImVec2(-1, 28))) run_ui_command({"bind"});  // the worker
  if (!can) ImGui::EndDisabled();
  if (doc_.has_weights()) {
    const BindStats& s = doc_.bind_stats();
    text_disabled_wrapped("%d handles, %d tets, %.2f s", doc_.num_handles(), s.tets, s.seconds);
    for (const auto& n : s.notes) ImGui::TextWrapped("- %s", n.c_str());
    if (bind_tally_.frames > 0)
      text_disabled_wrapped("UI while binding: %d frames, max %.0f ms", bind_tally_.frames, bind_tally_.max_ms);
  } else {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.95f, 0.75f, 0.35f, 1));
    ImGui::TextWrapped("%s", doc_.weights_note().c_str());
    ImGui::PopStyleColor();
  }
  int m = static_cast<int>(doc_.method());
  const char* methods[] = {"LBS", "DQS", "Stretch/twist bones (LBS)", "Stretch/twist bones (DQS)"};
  ImGui::SetNextItemWidth(-1);
  if (ImGui::Combo("##method", &m, methods, 4)) run_ui_command({"set-method", skin_method_name(static_cast<SkinMethod>(m))});
}

// The difference view's legend: against what, and how far the weights moved (mean and largest).
void Editor::draw_weight_difference_note() {
  const Eigen::MatrixXd& R = doc_.replaced_weights();
  if (!doc_.has_weights() || R.rows() != doc_.weights().rows() || R.cols() != doc_.weights().cols()) {
    text_disabled_wrapped("bind again to compare the new weights with those the bind replaces");
    return;
  }
  const int h = doc_.selection().handles.empty() ? -1 : doc_.selection().handles.front();
  const Eigen::VectorXd d = weight_difference(doc_.weights(), R, h);
  if (h < 0)
    text_disabled_wrapped("share of each vertex's weight the last bind moved to other handles (select a handle "
                          "for its own)");
  else
    ImGui::TextDisabled("%s: |new - replaced|", handle_name(doc_.rig(), h).c_str());
  ImGui::Text("mean %.3f, largest %.3f", d.mean(), d.maxCoeff());
}

void Editor::draw_weights_section() {
  int v = static_cast<int>(weight_view_);
  ItemFlow flow;
  int i = 0;
  for (const char* label : {"Off", "Selected", "All", "Mask", "Difference"}) {
    flow.next(ItemFlow::check_width(label));
    ImGui::RadioButton(label, &v, i++);
  }
  weight_view_ = static_cast<WeightView>(v);
  if (weight_view_ == WeightView::Difference) draw_weight_difference_note();
  if (weight_view_ == WeightView::Selected || weight_view_ == WeightView::Difference) {
    // Colour bar legend for the turbo map.
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const float w = ImGui::GetContentRegionAvail().x;
    ImDrawList* dl = ImGui::GetWindowDrawList();
    for (int i = 0; i < 32; ++i) {
      const float x0 = p.x + w * i / 32, x1 = p.x + w * (i + 1) / 32;
      const float t = (i + 0.5f) / 32;
      const Eigen::Vector3d c = view::turbo(t);  // the shader's colour map (core/view/colormap.h)
      const float r = float(c.x()), g = float(c.y()), b = float(c.z());
      dl->AddRectFilled(ImVec2(x0, p.y), ImVec2(x1 + 1, p.y + 8), ImGui::GetColorU32(ImVec4(r, g, b, 1)));
    }
    ImGui::Dummy(ImVec2(w, 10));
    ImGui::TextDisabled("0");
    ImGui::SameLine(w - 8);
    ImGui::TextDisabled("1");
    if (weight_view_ == WeightView::Selected && doc_.selection().handles.empty())
      text_disabled_wrapped("select a handle to see its weights");
  }
  if (picked_vertex_ >= 0 && picked_vertex_ < doc_.surface().num_vertices()) {
    ImGui::Text("Vertex %d", picked_vertex_);
    if (!doc_.has_weights()) {
      ImGui::TextDisabled("not bound");
    } else {
      const Eigen::MatrixXd& W = doc_.weights();
      std::vector<std::pair<double, int>> w;
      for (int j = 0; j < W.cols(); ++j) w.emplace_back(W(picked_vertex_, j), j);
      std::sort(w.rbegin(), w.rend());
      if (ImGui::BeginTable("vw", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
        for (size_t k = 0; k < std::min<size_t>(8, w.size()); ++k) {
          if (w[k].first < 1e-4 && k > 0) break;
          ImGui::TableNextRow();
          ImGui::TableNextColumn();
          ImGui::TextUnformatted(handle_name(doc_.rig(), w[k].second).c_str());
          ImGui::TableNextColumn();
          ImGui::Text("%.4f", w[k].first);
        }
        ImGui::EndTable();
      }
    }
  }
  if (ImGui::TreeNodeEx("Weight tools", ImGuiTreeNodeFlags_DefaultOpen)) {
    draw_weight_tools_section();
    ImGui::TreePop();
  }
}

// fps: frames drawn per second where they follow one another (a frame after an idle wait counts as
// its own drawing time: the rate the editor can draw); ms: the mean time to draw one (frame_pacing.h).
std::string Editor::hud_text() const {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%.0f fps  %.1f ms   %d verts  %d faces   %s%s", frame_stats_.fps(), frame_stats_.ms(),
                view_->display_vertex_count(), view_->display_face_count(),
                cam_.orthographic ? "ortho" : "persp", view_->showing_preview() ? (doc_.sculpt() ? "   sculpt" : "   shape space") : view_->display_is_rest() ? "   rest" : (view_->showing_slice() ? "   manifold slice" : "   posed"));
  return buf;
}

void Editor::draw_viewport_hud() {
  // Everything here stays inside the viewport: lines wrap at its width and are clipped to it.
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  const ImVec2 lo(float(viewport_.x), float(viewport_.y)), hi(float(viewport_.x + viewport_.w), float(viewport_.y + viewport_.h));
  dl->PushClipRect(lo, hi, false);
  ImFont* font = ImGui::GetFont();
  const float size = ImGui::GetFontSize(), wrap = std::max(40.0f, hi.x - lo.x - 20);
  float y = lo.y + 8;
  auto line = [&](float at_y, ImU32 color, const std::string& text) {
    dl->AddText(font, size, ImVec2(lo.x + 10, at_y), color, text.c_str(), nullptr, wrap);
    return ImGui::CalcTextSize(text.c_str(), nullptr, false, wrap).y;
  };
  // The picked pairs' numbers beside their points (scene_overlays.cpp draws the points).
  for (const ViewportLabel& l : pair_labels(doc_, cam_, view_->pair_placement(doc_)))
    dl->AddText(font, size, ImVec2(lo.x + float(l.x), lo.y + float(l.y) - size), IM_COL32(240, 226, 190, 255), l.text.c_str());
  y += line(y, IM_COL32(200, 204, 212, 220), hud_text()) + 4;
  if (!view_->last_error().empty()) y += line(y, IM_COL32(255, 150, 110, 255), view_->last_error()) + 4;
  // A transition builds on a worker: say so (the pose or rest shows until it lands).
  if (view_->manifold_building()) line(y, IM_COL32(140, 215, 240, 255), view_->manifold_progress());
  if (!status_.empty()) {
    const float h = ImGui::CalcTextSize(status_.c_str(), nullptr, false, wrap).y;
    line(hi.y - h - 8, status_error_ ? IM_COL32(255, 120, 110, 255) : IM_COL32(170, 176, 186, 220), status_);
  }
  dl->PopClipRect();
}

void Editor::draw_quit_prompt() {
  if (quit_prompt_) ImGui::OpenPopup("Unsaved changes");
  ImGui::SetNextWindowPos(ImGui::GetMainViewport()->GetCenter(), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (ImGui::BeginPopupModal("Unsaved changes", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("The scene has unsaved changes.");
    if (ImGui::Button("Save and quit")) {
      if (doc_.path().empty()) {
        files_.show(FilePanel::Mode::Save, "Save scene as", "save-scene", "scene.scene.json");
      } else {
        should_quit_ = save_scene_as(doc_.path());
      }
      quit_prompt_ = false;
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Quit without saving")) should_quit_ = true, quit_prompt_ = false, ImGui::CloseCurrentPopup();
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) quit_prompt_ = false, ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
}

namespace {

// A centred modal showing `text` while it is non-empty; OK clears it.
void message_popup(const char* title, std::string& text, float wrap) {
  if (!text.empty() && !ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
  ImGui::SetNextWindowPos(ImGui::GetMainViewport()->GetCenter(), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSizeConstraints(ImVec2(320, 0), ImVec2(wrap + 40, 400));
  if (ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::PushTextWrapPos(wrap);
    ImGui::TextUnformatted(text.c_str());
    ImGui::PopTextWrapPos();
    if (ImGui::Button("OK", ImVec2(120, 0))) text.clear(), ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
}

}  // namespace

void Editor::draw_error_popup() { message_popup("Error", error_popup_, 600); }

void Editor::draw_export_report() { message_popup("glTF export", export_report_, 640); }

}  // namespace dfm::editor
