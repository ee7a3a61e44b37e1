// Viewport input: camera gestures, keyboard shortcuts and the rigging/posing tools. Every edit is a
// Document call; drags are wrapped in gestures so one drag is one undo step.
#include <imgui.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>

#include "app/editor/camera_sync.h"
#include "app/editor/editor.h"
#include "core/scene/brush.h"
#include "core/view/picking.h"

namespace dfm::editor {
namespace {

Eigen::Vector4f rgba(float r, float g, float b, float a = 1) { return {r, g, b, a}; }

// A handle the Select tool can grab: which kind of rig element and its index there.
struct Grab {
  enum Kind { None, Handle, Joint } kind = None;
  int index = -1;
};

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
      if (shift) doc_.redo(); else doc_.undo();
      return;
    }
    if (ctrl && pressed(GLFW_KEY_Y)) return doc_.redo();
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
    if (pressed(GLFW_KEY_G)) tool_ = Tool::Pose, gizmo_rotate_ = false;
    if (pressed(GLFW_KEY_R)) tool_ = Tool::Pose, gizmo_rotate_ = true;
    if (pressed(GLFW_KEY_K)) doc_.set_key(doc_.time());
    if (pressed(GLFW_KEY_SPACE)) playing_ = !playing_;
    if (pressed(GLFW_KEY_ESCAPE)) bone_chain_.clear();
    if ((pressed(GLFW_KEY_ENTER) || pressed(GLFW_KEY_KP_ENTER)) && tool_ == Tool::DrawBone && bone_chain_.size() >= 2) {
      const int first = doc_.add_bone_chain(bone_chain_, bone_chain_parent_);
      select_handle(num_point_handles(doc_.rig()) + first, false);
      bone_chain_.clear();
    }
    if ((pressed(GLFW_KEY_DELETE) || pressed(GLFW_KEY_X)) && !doc_.selection().handles.empty())
      doc_.delete_handles(doc_.selection().handles);
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
  if (drag_ == Drag::None && over) {
    if (ImGui::IsMouseClicked(ImGuiMouseButton_Middle) || (io.KeyAlt && ImGui::IsMouseClicked(ImGuiMouseButton_Left)))
      drag_ = (io.KeyShift ? Drag::Pan : Drag::Orbit), drag_last_ = m;
    else if (ImGui::IsMouseClicked(ImGuiMouseButton_Right) && !(tool_ == Tool::DrawBone && !bone_chain_.empty()))
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
  brush_visible_ = false;
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
    }
  } catch (const std::exception& e) {
    if (drag_ != Drag::None) doc_.end_gesture();
    drag_ = Drag::None;
    error_popup_ = e.what();
  }
}

void Editor::tool_select(bool clicked, bool released) {
  const Eigen::Vector2d m = mouse_in_viewport();
  const Rig& rig = doc_.rig();
  if (clicked) {
    const Eigen::MatrixXd& P = view_->handle_positions();
    const int np = num_point_handles(rig), nb = rig.skeleton.num_bones();
    Grab g;
    // Points, cage vertices and regions by their glyph; joints; then bones by their segment. Only what
    // is drawn: not with Handles off, nor over a mesh the rig does not apply to (overlays hidden).
    const bool rig_shown = show_handles_ && view_->overlay_opacity() >= kMinOverlayOpacity;
    int best = rig_shown ? view::pick_projected_point(cam_, P, m, 9) : -1;
    if (best >= np && best < np + nb) best = -1;  // a bone's row is its first joint: pick bones by segment
    if (best >= 0) g = {Grab::Handle, best};
    if (g.kind == Grab::None && rig_shown) {
      const int j = view::pick_projected_point(cam_, view_->joint_positions(), m, 7);
      if (j >= 0) g = {Grab::Joint, j};
    }
    if (g.kind == Grab::None && nb > 0 && rig_shown) {
      std::vector<std::pair<int, int>> segs;
      for (const Bone& b : rig.skeleton.bones) segs.emplace_back(b.a, b.b);
      const int b = view::pick_projected_segment(cam_, view_->joint_positions(), segs, m, 6);
      if (b >= 0) g = {Grab::Handle, np + b};
    }
    const bool additive = ImGui::GetIO().KeyShift || ImGui::GetIO().KeyCtrl;
    if (g.kind == Grab::Handle) {
      select_handle(g.index, additive);
      const HandleRef r = handle_ref(rig, g.index);
      // Handles move only in the rest pose (editing the rig); posing is the Pose tool's job.
      if (view_->display_is_rest() && (r.kind == HandleKind::Point || r.kind == HandleKind::CageVertex)) {
        drag_ = Drag::Handle;
        drag_handle_ = g.index;
        drag_point_ = P.row(g.index);
        doc_.begin_gesture();
      }
      weight_rows_.clear();
    } else if (g.kind == Grab::Joint) {
      Selection s = doc_.selection();
      s.joint = g.index;
      doc_.set_selection(s);
      if (view_->display_is_rest()) {
        drag_ = Drag::Handle;
        drag_handle_ = -1;
        drag_joint_ = g.index;
        drag_point_ = view_->joint_positions().row(g.index);
        doc_.begin_gesture();
      }
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
  if (drag_ == Drag::Handle) {
    // Move in the plane through the handle that faces the camera.
    view::Camera c = cam_;
    c.target = drag_point_;
    c.distance = (drag_point_ - view::camera_eye(cam_)).dot(view::camera_forward(cam_));
    if (c.distance > 1e-9 || cam_.orthographic) {
      if (cam_.orthographic) c.distance = cam_.distance;
      const Eigen::Vector3d p = view::pixel_on_target_plane(cam_.orthographic ? cam_ : c, m.x(), m.y());
      Eigen::Vector3d q = p;
      if (cam_.orthographic) q = p + (drag_point_ - p).dot(view::camera_forward(cam_)) * view::camera_forward(cam_);
      if ((q - drag_point_).norm() > 0) {
        if (drag_joint_ >= 0) {
          doc_.move_joint(drag_joint_, q);
        } else {
          const HandleRef r = handle_ref(rig, drag_handle_);
          if (r.kind == HandleKind::Point) doc_.move_point(r.index, q);
          else if (r.kind == HandleKind::CageVertex) doc_.move_cage_vertex(r.cage, r.index, q);
        }
        drag_point_ = q;
      }
    }
    if (released) {
      doc_.end_gesture();
      drag_ = Drag::None;
      drag_joint_ = drag_handle_ = -1;
    }
  }
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
  const int i = doc_.add_point(p);
  select_handle(i, false);
  status("placed point handle " + handle_name(doc_.rig(), i));
}

void Editor::tool_draw_bone(bool clicked) {
  const Eigen::Vector2d m = mouse_in_viewport();
  // Preview of the chain so far and a rubber band to the cursor.
  if (!bone_chain_.empty()) {
    std::vector<gl::OverlayVertex> l;
    for (size_t i = 1; i < bone_chain_.size(); ++i) {
      l.push_back(gl::overlay_vertex(bone_chain_[i - 1], rgba(1, 0.75f, 0.3f)));
      l.push_back(gl::overlay_vertex(bone_chain_[i], rgba(1, 0.75f, 0.3f)));
    }
    if (viewport_hovered_) {
      view::Camera c = cam_;
      c.target = bone_chain_.back();
      l.push_back(gl::overlay_vertex(bone_chain_.back(), rgba(1, 1, 1, 0.6f)));
      l.push_back(gl::overlay_vertex(view::pixel_on_target_plane(c, m.x(), m.y()), rgba(1, 1, 1, 0.6f)));
    }
    view_->add_overlay_lines(l, 3.0f);
    std::vector<gl::OverlayVertex> pts;
    for (const auto& j : bone_chain_) pts.push_back(gl::overlay_vertex(j, rgba(1, 0.75f, 0.3f)));
    view_->add_overlay_points(pts, 10.0f);
  }
  const bool finish = viewport_hovered_ && ImGui::IsMouseClicked(ImGuiMouseButton_Right) && !bone_chain_.empty();
  if (finish) {
    if (bone_chain_.size() >= 2) {
      const int first = doc_.add_bone_chain(bone_chain_, bone_chain_parent_);
      select_handle(num_point_handles(doc_.rig()) + first, false);
      status("added " + std::to_string(bone_chain_.size() - 1) + " bone(s)");
    }
    bone_chain_.clear();
    bone_chain_parent_ = -1;
    return;
  }
  if (!clicked) return;
  if (bone_chain_.empty()) {
    const int j = view::pick_projected_point(cam_, view_->joint_positions(), m, 8);
    if (j >= 0) {
      bone_chain_parent_ = j;
      bone_chain_.push_back(view_->joint_positions().row(j));
      return;
    }
    bone_chain_parent_ = -1;
  }
  const view::Ray ray = view::pixel_ray(cam_, m.x(), m.y());
  Eigen::Vector3d p;
  if (!view::pick_inside_point(ray, view_->display_vertices(), view_->display_faces(), p)) {
    if (bone_chain_.empty()) return status("click inside the surface to start a bone chain");
    view::Camera c = cam_;  // off the surface: continue at the last joint's depth
    c.target = bone_chain_.back();
    p = view::pixel_on_target_plane(c, m.x(), m.y());
  }
  bone_chain_.push_back(p);
}

void Editor::tool_paint(bool down, bool clicked, bool released) {
  const Eigen::Vector2d m = mouse_in_viewport();
  const Eigen::MatrixXd& V = view_->display_vertices();
  const view::SurfaceHit hit = viewport_hovered_ || drag_ == Drag::Paint
                                 ? view::pick_surface(view::pixel_ray(cam_, m.x(), m.y()), V, view_->display_faces())
                                 : view::SurfaceHit{};
  const double radius = brush_radius_ * std::max(1e-9, view_->surface_bounds().diagonal().norm());
  const bool erase = ImGui::GetIO().KeyCtrl || ImGui::GetIO().KeyShift;
  if (hit.hit()) {
    const Eigen::MatrixXi& F = view_->display_faces();
    const Eigen::Vector3d a = V.row(F(hit.face, 0)), b = V.row(F(hit.face, 1)), c = V.row(F(hit.face, 2));
    brush_center_ = hit.point;
    brush_normal_ = (b - a).cross(c - a).normalized();
    brush_visible_ = true;
    const Eigen::Vector4f col = erase ? rgba(1, 0.35f, 0.3f) : rgba(1, 1, 1, 0.9f);
    const Eigen::Vector3d lift = brush_center_ + 1e-3 * radius * brush_normal_;
    view_->add_overlay_lines(gl::circle_lines(lift, brush_normal_, radius, col, 64), 2.0f);
    // Inner circle where the falloff starts.
    if (brush_falloff_ < 0.99)
      view_->add_overlay_lines(gl::circle_lines(lift, brush_normal_, radius * (1 - brush_falloff_),
                                                rgba(col.x(), col.y(), col.z(), 0.35f), 48), 1.0f);
  }
  if (clicked && hit.hit()) {
    drag_ = Drag::Paint;
    doc_.begin_gesture();
    if (paint_target_ == PaintTarget::Region && (paint_region_ < 0 || paint_region_ >= int(doc_.rig().regions.size())))
      paint_region_ = doc_.add_region();
  }
  if (drag_ == Drag::Paint && down && hit.hit()) {
    const Brush brush{radius, brush_strength_, brush_falloff_, erase ? BrushMode::Erase : BrushMode::Add};
    const Eigen::VectorXd& mask = doc_.mask();
    const BrushDab dab = brush_dab(V, mask.size() == V.rows() ? mask : Eigen::VectorXd(), brush_center_, brush);
    if (!dab.vertices.empty()) {
      if (paint_target_ == PaintTarget::Mask) doc_.paint_mask(dab.vertices, dab.values);
      else doc_.paint_region(paint_region_, dab.vertices, erase);
    }
  }
  if (drag_ == Drag::Paint && released) {
    doc_.end_gesture();
    drag_ = Drag::None;
  }
}

void Editor::tool_pose(bool clicked, bool released) {
  const Eigen::Vector2d m = mouse_in_viewport();
  const auto& sel = doc_.selection().handles;
  const Eigen::MatrixXd& P = view_->handle_positions();
  const bool rig_shown = show_handles_ && view_->overlay_opacity() >= kMinOverlayOpacity;
  if (sel.empty() || sel.front() >= P.rows() || !rig_shown) {  // no gizmo on a handle that is not drawn
    if (clicked) tool_select(true, false);  // click selects a handle to pose
    if (drag_ == Drag::Handle) {            // but posing never drags rest positions
      doc_.end_gesture();
      drag_ = Drag::None;
    }
    return;
  }
  const int h = sel.front();
  const Eigen::Vector3d origin = P.row(h);
  const bool can_rotate = handle_ref(doc_.rig(), h).kind != HandleKind::CageVertex;
  const bool rotate = gizmo_rotate_ && can_rotate;
  const GizmoPart hover = drag_ == Drag::Gizmo ? gizmo_part_ : gizmo_hit(cam_, origin, rotate, m);

  // Draw the gizmo.
  const double len = world_per_pixels(cam_, origin, GizmoLayout{}.axis_px);
  auto hl = [&](GizmoPart p, Eigen::Vector4f c) { return hover == p ? rgba(1, 0.9f, 0.3f) : c; };
  std::vector<gl::OverlayVertex> l;
  if (!rotate) {
    const Eigen::Vector4f ax[3] = {rgba(0.95f, 0.3f, 0.3f), rgba(0.4f, 0.9f, 0.35f), rgba(0.35f, 0.55f, 1.0f)};
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector4f c = hl(GizmoPart(int(GizmoPart::AxisX) + k), ax[k]);
      l.push_back(gl::overlay_vertex(origin, c));
      l.push_back(gl::overlay_vertex(origin + len * Eigen::Vector3d::Unit(k), c));
      // Plane square between the other two axes.
      const Eigen::Vector3d u = Eigen::Vector3d::Unit((k + 1) % 3), v = Eigen::Vector3d::Unit((k + 2) % 3);
      const double a = 0.25 * len, b = a + len * GizmoLayout{}.plane_px / GizmoLayout{}.axis_px;
      const Eigen::Vector4f pc = hl(GizmoPart(int(GizmoPart::PlaneYZ) + k), rgba(ax[k].x(), ax[k].y(), ax[k].z(), 0.7f));
      const Eigen::Vector3d q[4] = {origin + a * u + a * v, origin + b * u + a * v, origin + b * u + b * v, origin + a * u + b * v};
      for (int e = 0; e < 4; ++e) {
        l.push_back(gl::overlay_vertex(q[e], pc));
        l.push_back(gl::overlay_vertex(q[(e + 1) % 4], pc));
      }
    }
  } else {
    const double r = world_per_pixels(cam_, origin, GizmoLayout{}.ring_px);
    for (auto& v : gl::circle_lines(origin, -view::camera_forward(cam_), r, hl(GizmoPart::Ring, rgba(0.95f, 0.95f, 1.0f)), 72))
      l.push_back(v);
    for (auto& v : gl::circle_lines(origin, -view::camera_forward(cam_), 0.98 * r,
                                    hover == GizmoPart::Trackball ? rgba(1, 0.9f, 0.3f, 0.35f) : rgba(1, 1, 1, 0.12f), 72))
      l.push_back(v);
  }
  view_->add_overlay_lines(l, 3.0f);

  if (clicked) {
    if (hover != GizmoPart::None) {
      drag_ = Drag::Gizmo;
      gizmo_part_ = hover;
      drag_last_ = m;
      drag_start_ = m;
      doc_.begin_gesture();
    } else {
      tool_select(true, false);
      if (drag_ == Drag::Handle) {
        doc_.end_gesture();
        drag_ = Drag::None;
      }
    }
    return;
  }
  if (drag_ == Drag::Gizmo) {
    if (m != drag_last_) {
      if (rotate) {
        const Eigen::Quaterniond q = gizmo_rotation(cam_, origin, gizmo_part_, drag_last_, m);
        if (q.angularDistance(Eigen::Quaterniond::Identity()) > 1e-9) doc_.rotate_handle(h, q);
      } else {
        const Eigen::Vector3d d = gizmo_translation(cam_, origin, gizmo_part_, drag_last_, m);
        if (d.norm() > 0) doc_.translate_handle(h, d);
      }
      drag_last_ = m;
    }
    if (released) {
      doc_.end_gesture();
      drag_ = Drag::None;
      gizmo_part_ = GizmoPart::None;
    }
  }
}

}  // namespace dfm::editor
