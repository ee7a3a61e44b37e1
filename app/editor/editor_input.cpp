// Viewport input: camera gestures, keyboard shortcuts and the rigging/posing tools. Every edit is a
// Document call; drags are wrapped in gestures so one drag is one undo step.
#include <imgui.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>

#include "app/editor/camera_sync.h"
#include "app/editor/editor.h"
#include "core/view/picking.h"

namespace dfm::editor {
namespace {

Eigen::Vector4f rgba(float r, float g, float b, float a = 1) { return {r, g, b, a}; }

// A handle the Select tool can grab: which kind of rig element and its index there.
struct Grab {
  enum Kind { None, Handle, Joint } kind = None;
  int index = -1;
};

// Points, cage vertices and regions by their glyph; joints; then bones by their segment.
Grab pick_rig(const view::Camera& cam, const SceneView& view, const Rig& rig, const Eigen::Vector2d& m) {
  const int np = num_point_handles(rig), nb = rig.skeleton.num_bones();
  int best = view::pick_projected_point(cam, view.handle_positions(), m, 9);
  if (best >= np && best < np + nb) best = -1;  // a bone's row is its first joint: pick bones by segment
  if (best >= 0) return {Grab::Handle, best};
  const int j = view::pick_projected_point(cam, view.joint_positions(), m, 7);
  if (j >= 0) return {Grab::Joint, j};
  if (nb == 0) return {};
  std::vector<std::pair<int, int>> segs;
  for (const Bone& b : rig.skeleton.bones) segs.emplace_back(b.a, b.b);
  const int b = view::pick_projected_segment(cam, view.joint_positions(), segs, m, 6);
  return b >= 0 ? Grab{Grab::Handle, np + b} : Grab{};
}

}  // namespace

Eigen::Vector2d Editor::mouse_in_viewport() const {
  const ImVec2 m = ImGui::GetIO().MousePos;
  return {m.x - viewport_.x, m.y - viewport_.y};
}

void Editor::handle_shortcuts() {
  ImGuiIO& io = ImGui::GetIO();
  if (io.WantTextInput) return;
  const bool ctrl = io.KeyCtrl, shift = io.KeyShift;
  auto pressed = [](int key) { return ImGui::IsKeyPressed(key, false); };
  try {
    if (ctrl && pressed(GLFW_KEY_Z)) {
      run_ui_command({shift ? "redo" : "undo"});
      return;
    }
    if (ctrl && pressed(GLFW_KEY_Y)) {
      run_ui_command({"redo"});
      return;
    }
    if (ctrl && pressed(GLFW_KEY_S)) {
      if (doc_.path().empty()) files_.show(FilePanel::Mode::Save, "Save scene as", "save-scene", "scene.scene.json");
      else save_scene_as(doc_.path());
      return;
    }
    if (ctrl && pressed(GLFW_KEY_O)) return files_.show(FilePanel::Mode::Open, "Open", "open");
    if (ctrl) return;
    if (io.WantCaptureKeyboard) return;
    if (pressed(GLFW_KEY_F)) frame_selection();
    if (pressed(GLFW_KEY_HOME)) frame_all();
    if (pressed(GLFW_KEY_1) || pressed(GLFW_KEY_KP_1)) view::set_view_preset(cam_, view::ViewPreset::Front);
    if (pressed(GLFW_KEY_3) || pressed(GLFW_KEY_KP_3)) view::set_view_preset(cam_, view::ViewPreset::Right);
    if (pressed(GLFW_KEY_7) || pressed(GLFW_KEY_KP_7)) view::set_view_preset(cam_, view::ViewPreset::Top);
    if (pressed(GLFW_KEY_5) || pressed(GLFW_KEY_KP_5)) cam_.orthographic = !cam_.orthographic;
    if (pressed(GLFW_KEY_Z) && !shift) wireframe_ = !wireframe_;
    if (pressed(GLFW_KEY_Q)) tool_ = Tool::Select;
    if (pressed(GLFW_KEY_P)) tool_ = Tool::PlacePoint;
    if (pressed(GLFW_KEY_B)) tool_ = Tool::DrawBone;
    if (pressed(GLFW_KEY_V)) tool_ = Tool::Paint;
    if (pressed(GLFW_KEY_U)) tool_ = Tool::Sculpt;
    if (pressed(GLFW_KEY_G)) tool_ = Tool::Pose, gizmo_rotate_ = false;
    if (pressed(GLFW_KEY_R)) tool_ = Tool::Pose, gizmo_rotate_ = true;
    if (pressed(GLFW_KEY_K)) run_ui_command({"set-key"});
    if (pressed(GLFW_KEY_SPACE)) playing_ = !playing_;
    if (pressed(GLFW_KEY_ESCAPE)) bone_tool_.cancel(), pair_tool_.cancel();
    if ((pressed(GLFW_KEY_ENTER) || pressed(GLFW_KEY_KP_ENTER)) && tool_ == Tool::DrawBone) finish_bone_chain();
    if ((pressed(GLFW_KEY_DELETE) || pressed(GLFW_KEY_X)) && !doc_.selection().handles.empty())
      run_ui_command(command_words("delete-handles", doc_.selection().handles));
    sync_camera_to_doc();
  } catch (const std::exception& e) {
    error_popup_ = e.what();
  }
}

void Editor::handle_camera_input() {
  ImGuiIO& io = ImGui::GetIO();
  const Eigen::Vector2d m = mouse_in_viewport();
  const bool over = viewport_hovered_;
  if (over && io.MouseWheel != 0.0f) {
    view::zoom_to_cursor(cam_, std::pow(0.85, io.MouseWheel), m);
    sync_camera_to_doc();
  }
  if (drag_ == Drag::None && !rig_drag_.dragging() && !pose_tool_.dragging() && !paint_tool_.painting() &&
      !sculpt_tool_.busy() && !space_time_tool_.dragging() && over) {
    if (ImGui::IsMouseClicked(ImGuiMouseButton_Middle) || (io.KeyAlt && ImGui::IsMouseClicked(ImGuiMouseButton_Left)))
      drag_ = (io.KeyShift ? Drag::Pan : Drag::Orbit), drag_last_ = m;
    else if (ImGui::IsMouseClicked(ImGuiMouseButton_Right) && !(tool_ == Tool::DrawBone && bone_tool_.active()))
      drag_ = Drag::Pan, drag_last_ = m;
  }
  if (drag_ == Drag::Orbit) {
    if (m != drag_last_) view::arcball_orbit(cam_, drag_last_, m);
    drag_last_ = m;
  } else if (drag_ == Drag::Pan) {
    view::pan(cam_, m - drag_last_);
    drag_last_ = m;
  }
  if ((drag_ == Drag::Orbit || drag_ == Drag::Pan) && !ImGui::IsMouseDown(ImGuiMouseButton_Left) &&
      !ImGui::IsMouseDown(ImGuiMouseButton_Middle) && !ImGui::IsMouseDown(ImGuiMouseButton_Right)) {
    drag_ = Drag::None;
    sync_camera_to_doc();
  }
}

void Editor::handle_viewport_input() {
  ImGuiIO& io = ImGui::GetIO();
  viewport_hovered_ = !io.WantCaptureMouse && viewport_.contains(io.MousePos.x, io.MousePos.y);
  handle_camera_input();
  if (drag_ == Drag::Orbit || drag_ == Drag::Pan) return;
  const bool clicked = viewport_hovered_ && ImGui::IsMouseClicked(ImGuiMouseButton_Left) && !io.KeyAlt;
  const bool down = ImGui::IsMouseDown(ImGuiMouseButton_Left);
  const bool released = ImGui::IsMouseReleased(ImGuiMouseButton_Left);
  try {
    switch (tool_) {
      case Tool::Select: tool_select(clicked, released); break;
      case Tool::PlacePoint: tool_place_point(clicked); break;
      case Tool::DrawBone: tool_draw_bone(clicked); break;
      case Tool::Paint: tool_paint(down, clicked, released); break;
      case Tool::Pose: tool_pose(clicked, released); break;
      case Tool::Pair: tool_pair(clicked); break;
      case Tool::Sculpt: tool_sculpt(down, clicked, released); break;
      case Tool::SpaceTime: tool_space_time(clicked, released); break;
    }
  } catch (const std::exception& e) {
    drag_ = Drag::None;
    rig_drag_.cancel(doc_);
    pose_tool_.cancel(doc_);
    paint_tool_.cancel(doc_);
    sculpt_tool_.cancel(doc_);
    space_time_tool_.cancel(doc_);
    error_popup_ = e.what();
  }
}

void Editor::tool_select(bool clicked, bool released) {
  const Eigen::Vector2d m = mouse_in_viewport();
  const Rig& rig = doc_.rig();
  if (clicked) {
    const Eigen::MatrixXd& P = view_->handle_positions();
    // Only what is drawn: not with Handles off, nor over a mesh the rig does not apply to.
    const bool rig_shown = show_handles_ && view_->overlay_opacity() >= kMinOverlayOpacity;
    const Grab g = rig_shown ? pick_rig(cam_, *view_, rig, m) : Grab{};
    const bool additive = ImGui::GetIO().KeyShift || ImGui::GetIO().KeyCtrl;
    if (g.kind == Grab::Handle) {
      select_handle(g.index, additive);
      // Handles move only in the rest pose (editing the rig); posing is the Pose tool's job.
      if (view_->display_is_rest()) rig_drag_.start_handle(doc_, g.index, P.row(g.index));
      weight_rows_.clear();
    } else if (g.kind == Grab::Joint) {
      Selection s = doc_.selection();
      s.joint = g.index;
      doc_.set_selection(s);
      if (view_->display_is_rest()) rig_drag_.start_joint(doc_, g.index, view_->joint_positions().row(g.index));
    } else {
      // Nothing grabbed: a click on the surface lists that vertex's weights; empty space orbits.
      const view::Ray ray = view::pixel_ray(cam_, m.x(), m.y());
      const view::SurfaceHit hit = view::pick_surface(ray, view_->display_vertices(), view_->display_faces());
      if (!additive) doc_.set_selection(Selection{});
      if (hit.hit()) {
        picked_vertex_ = hit.nearest_vertex;
        weight_rows_.clear();
      } else {
        drag_ = Drag::Orbit;
        drag_last_ = m;
      }
    }
    return;
  }
  rig_drag_.update(doc_, cam_, m, released);
}

void Editor::tool_pair(bool clicked) {
  if (pair_tool_.first()) view_->add_overlay_points({gl::overlay_vertex(*pair_tool_.first(), rgba(1, 0.62f, 0.2f))}, 12.0f);
  if (!clicked) return;
  const Eigen::Vector2d m = mouse_in_viewport();
  const view::SurfaceHit h = view::pick_surface(view::pixel_ray(cam_, m.x(), m.y()), view_->display_vertices(), view_->display_faces());
  const PairTool::Step s = pair_tool_.click(doc_, h.hit() ? std::optional<Eigen::Vector3d>(h.point) : std::nullopt);
  if (!s.command.empty()) run_ui_command(s.command);
  if (s.go_to) doc_.set_time(*s.go_to);
  if (!s.status.empty()) status(s.status);
}

void Editor::tool_space_time(bool clicked, bool released) {
  SpaceTimeTool::Input in;
  in.mouse = mouse_in_viewport();
  in.hovered = viewport_hovered_;
  in.clicked = clicked;
  in.released = released || !ImGui::IsMouseDown(ImGuiMouseButton_Left);
  in.new_region = ImGui::GetIO().KeyShift;
  in.retime = ImGui::GetIO().KeyCtrl;  // Alt is the camera's orbit
  in.t_slice = slice_axis_ == SliceAxis::T;
  const std::string s = space_time_tool_.update(doc_, *view_, cam_, in, [this](const CommandWords& w) { return run_ui_command(w); });
  if (!s.empty()) status(s);
}

void Editor::tool_place_point(bool clicked) {
  if (!clicked) return;
  const Eigen::Vector2d m = mouse_in_viewport();
  const view::Ray ray = view::pixel_ray(cam_, m.x(), m.y());
  Eigen::Vector3d p;
  bool ok = false;
  if (place_inside_) {
    ok = view::pick_inside_point(ray, view_->display_vertices(), view_->display_faces(), p);
  } else {
    const view::SurfaceHit h = view::pick_surface(ray, view_->display_vertices(), view_->display_faces());
    ok = h.hit();
    p = h.point;
  }
  if (!ok) return status("click on the surface to place a point handle");
  const int i = num_point_handles(doc_.rig());
  if (!run_ui_command(command_words("add-point", {p.x(), p.y(), p.z()}))) return;
  select_handle(i, false);
  status("placed point handle " + handle_name(doc_.rig(), i));
}

void Editor::tool_draw_bone(bool clicked) {
  const Eigen::Vector2d m = mouse_in_viewport();
  bone_tool_.draw_preview(*view_, cam_, {m, viewport_hovered_, clicked});
  if (viewport_hovered_ && ImGui::IsMouseClicked(ImGuiMouseButton_Right) && bone_tool_.active()) return finish_bone_chain();
  if (!clicked) return;
  const std::string why = bone_tool_.click(*view_, cam_, m);
  if (!why.empty()) status(why);
}

// The chain so far through add-bone (or add-bone-from its joint); a chain of one joint is dropped.
void Editor::finish_bone_chain() {
  const int before = doc_.rig().skeleton.num_bones();
  const CommandWords words = bone_tool_.finish();
  if (words.empty() || !run_ui_command(words)) return;
  select_handle(num_point_handles(doc_.rig()) + before, false);
  status("added " + std::to_string(doc_.rig().skeleton.num_bones() - before) + " bone(s)");
}

void Editor::tool_paint(bool down, bool clicked, bool released) {
  PaintTool::Input in;
  in.mouse = mouse_in_viewport();
  in.hovered = viewport_hovered_;
  in.down = down, in.clicked = clicked, in.released = released;
  in.erase = ImGui::GetIO().KeyCtrl || ImGui::GetIO().KeyShift;
  in.locked = weight_tools_.locked;
  paint_tool_.update(doc_, *view_, cam_, in, [this](const CommandWords& w) { return run_ui_command(w); });
}

void Editor::tool_sculpt(bool down, bool clicked, bool released) {
  SculptTool::Input in;
  in.mouse = mouse_in_viewport();
  in.hovered = viewport_hovered_;
  in.down = down, in.clicked = clicked, in.released = released;
  in.erase = ImGui::GetIO().KeyCtrl || ImGui::GetIO().KeyShift;
  sculpt_tool_.update(doc_, *view_, cam_, in, [this](const CommandWords& w) { return run_ui_command(w); });
}

void Editor::tool_pose(bool clicked, bool released) {
  PoseTool::Input in;
  in.mouse = mouse_in_viewport();
  in.clicked = clicked;
  in.released = released;
  in.rotate = gizmo_rotate_;
  in.rig_shown = show_handles_ && view_->overlay_opacity() >= kMinOverlayOpacity;
  if (pose_tool_.update(doc_, *view_, cam_, in)) return;
  if (clicked) tool_select(true, false);  // a click off the gizmo selects a handle to pose
  rig_drag_.cancel(doc_);                 // but posing never drags rest positions
}

}  // namespace dfm::editor
