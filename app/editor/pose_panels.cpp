// The Transform and Posing sections (pose_panels.h). Every change is a document command (undoable);
// the solve itself runs inside the document's pose edits.
#include <cstdio>

#include <imgui.h>

#include "app/editor/pose_panels.h"

#include "app/editor/editor.h"
#include "app/editor/theme.h"
#include "core/pose/fast_rig.h"
#include "core/rig/forward_kinematics.h"
#include "core/rig/rig.h"

namespace dfm::editor {

void Editor::draw_transform_section() {
  // The values of the pose on display: over the animation that is the key poses interpolated at the
  // current time (what the viewport shows), not the pose last edited.
  const bool animated = view_->showing_slice() && slice_axis_ == SliceAxis::T && doc_.keys().size() >= 2;
  pose_panels_.draw_transform(doc_, view_->shown_pose(doc_), animated ? format_time(doc_.time(), frame_rate_) : "",
                              0.002 * cam_.scene_radius);
}

void Editor::draw_posing_section() { pose_panels_.draw_posing(doc_, frame_rate_); }

void PosePanels::draw_transform(Document& doc, const Pose& pose, const std::string& animated_at, double drag_step) {
  const auto& sel = doc.selection().handles;
  if (sel.empty()) {
    ImGui::TextDisabled("no handle selected");
    return;
  }
  const int h = sel.front();
  const Rig& rig = doc.rig();
  ImGui::TextWrapped("%d  %s  (%s)", h, handle_name(rig, h).c_str(), handle_kind_name(handle_ref(rig, h).kind));
  if (!animated_at.empty()) text_disabled_wrapped("the animation at %s", animated_at.c_str());
  if (h < pose.size()) draw_typed_values(doc, h, pose.transforms[h], drag_step);
  const HandleRef r = handle_ref(rig, h);
  if (r.kind == HandleKind::Bone) draw_twist_stretch(doc, r.index);
  if (ImGui::Button("Reset pose", ImVec2(-1, 0))) doc.reset_pose();
}

// The bone's twist (degrees, at its second joint), stretch (length factor) and twist at its first joint
// (Eq. 6.5's theta_a), dragged: one undo step a drag (Jacobson 2013 ch. 6: STBS spreads them along the
// bone; every method moves the bones below by the twist and stretch).
void PosePanels::draw_twist_stretch(Document& doc, int bone) {
  const BoneTwistStretch ts = twist_stretch_of(doc.pose_params(), bone);
  float v[3] = {float(ts.twist * 180 / M_PI), float(ts.stretch), float(ts.twist_start * 180 / M_PI)};
  struct Field {
    const char* id;
    float speed, lo, hi;
    const char* format;
    const char* tip;
  };
  const Field fields[3] = {
      {"##twist", 0.5f, -720.0f, 720.0f, "twist %.1f deg", "Twist about the bone's axis at its second joint (script: twist)"},
      {"##stretch", 0.005f, 0.05f, 10.0f, "stretch %.3f", "Length factor of the bone (script: stretch)"},
      {"##twist_start", 0.5f, -720.0f, 720.0f, "twist at start %.1f deg",
       "Twist at the bone's first joint: STBS turns its skin from this to the twist (script: twist BONE DEG START)"}};
  bool changed = false, started = false, done = false;
  for (int i = 0; i < 3; ++i) {
    ImGui::SetNextItemWidth(-1);
    changed |= ImGui::DragFloat(fields[i].id, &v[i], fields[i].speed, fields[i].lo, fields[i].hi, fields[i].format);
    started |= ImGui::IsItemActivated();
    done |= ImGui::IsItemDeactivated();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", fields[i].tip);
  }
  if (started) doc.begin_gesture();
  if (changed) doc.set_bone_twist_stretch(bone, {v[0] * M_PI / 180, std::max(0.05f, v[1]), v[2] * M_PI / 180});
  if (done) doc.end_gesture();
  if (!is_stbs(doc.method()) && !is_rest_twist_stretch(ts))
    text_disabled_wrapped("the methods STBS spread them along the bone");
  if (is_stbs(doc.method()) && doc.has_weights()) {
    text_disabled_wrapped(doc.endpoint_weights().size() ? "endpoint weights: the bind's (shape-aware)"
                                                        : "endpoint weights: projection onto the bone (weights not from a bind)");
    draw_endpoint_filter(doc, bone);
  }
}

// Fig. 6.9: the endpoint weights through a curve from (0, 0) to (1, 1) via one point (x, y) dragged
// here (scripts take more: endpoint-filter). Below the diagonal the twist gathers toward the second joint.
void PosePanels::draw_endpoint_filter(Document& doc, int bone) {
  const std::vector<EndpointFilter>& all = doc.endpoint_filters();
  const EndpointFilter f = bone < static_cast<int>(all.size()) ? all[bone] : EndpointFilter{};
  bool on = !f.empty();
  float p[2] = {f.empty() ? 0.5f : float(f.front().x()), f.empty() ? 0.5f : float(f.front().y())};
  const bool toggled = ImGui::Checkbox("Filter endpoint weights", &on);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Passes the bone's endpoint weights through a curve via one point: where the twist and stretch gather");
  bool moved = false, started = false, done = false;
  if (on && f.size() <= 1) {
    ImGui::SetNextItemWidth(-1);
    moved = ImGui::DragFloat2("##filter", p, 0.005f, 0.01f, 0.99f, "%.2f");
    started = ImGui::IsItemActivated(), done = ImGui::IsItemDeactivated();
  } else if (on) {
    text_disabled_wrapped("a curve of several points (script endpoint-filter)");
  }
  if (started) doc.begin_gesture();
  if (toggled || moved) {
    EndpointFilter g;
    if (on) g.emplace_back(std::clamp(double(p[0]), 0.01, 0.99), std::clamp(double(p[1]), 0.0, 1.0));
    doc.set_endpoint_filter(bone, g);
  }
  if (done) doc.end_gesture();
}

// Typed values: world offset of the pivot and rotation (axis-angle) of this handle's transform, shown
// as the fields print them (no -0.000); a drag moves by the change from what is shown.
void PosePanels::draw_typed_values(Document& doc, int h, const Eigen::Affine3d& T, double drag_step) {
  const Eigen::Vector3d pivot = doc.handle_pivot(h);
  const float label_w = ImGui::CalcTextSize("Rotate").x + ImGui::GetStyle().ItemSpacing.x;
  auto label = [&](const char* text) {
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted(text);
    ImGui::SameLine(label_w + ImGui::GetStyle().WindowPadding.x);
    ImGui::SetNextItemWidth(-1);
  };
  const Eigen::Vector3d offset = T * pivot - pivot;
  const Eigen::Vector3d shown(display_value(offset.x(), 3), display_value(offset.y(), 3), display_value(offset.z(), 3));
  float t[3] = {float(shown.x()), float(shown.y()), float(shown.z())};
  label("Move");
  if (ImGui::DragFloat3("##move", t, float(drag_step), 0, 0, "%.3f")) {
    if (ImGui::IsItemActivated()) doc.begin_gesture();
    doc.translate_handle(h, Eigen::Vector3d(t[0], t[1], t[2]) - shown);
  }
  if (ImGui::IsItemDeactivated()) doc.end_gesture();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Translation of the handle's pivot, world x y z");
  if (handle_ref(doc.rig(), h).kind == HandleKind::CageVertex) return;  // cage vertices only move
  Eigen::AngleAxisd aa(T.linear());
  float* deg = rotate_deg_;
  label("Rotate");
  ImGui::InputFloat3("##rot", deg, "%.1f");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Degrees about world x, y, z (applied z * y * x)");
  const double angle = display_value(aa.angle() * 180 / M_PI, 1);
  if (angle == 0.0) {
    text_disabled_wrapped("rotation now: none");
  } else {
    // Two lines: a narrow panel wraps at spaces, and the axis has none to break at.
    text_disabled_wrapped("rotation now: %.1f deg", angle);
    text_disabled_wrapped("about (%.2f, %.2f, %.2f)", display_value(aa.axis().x(), 2), display_value(aa.axis().y(), 2),
                          display_value(aa.axis().z(), 2));
  }
  if (ImGui::Button("Apply rotation", ImVec2(-1, 0))) {
    const Eigen::Quaterniond q = Eigen::AngleAxisd(deg[2] * M_PI / 180, Eigen::Vector3d::UnitZ()) *
                                 Eigen::AngleAxisd(deg[1] * M_PI / 180, Eigen::Vector3d::UnitY()) *
                                 Eigen::AngleAxisd(deg[0] * M_PI / 180, Eigen::Vector3d::UnitX());
    doc.rotate_handle(h, q);
  }
}

void PosePanels::draw_posing(Document& doc, double frame_rate) {
  PosingSettings p = doc.posing();
  if (ImGui::Checkbox("Drag solves the free handles", &p.fast)) doc.set_posing(p);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("FAST (Jacobson 2013 ch. 7): handles not pinned get the transforms that keep the shape as\n"
                      "rigid as possible; a point you drag keeps its position and gets its rotation solved.");
  if (!doc.has_weights()) text_disabled_wrapped("bind first: FAST solves with the weights");
  if (iterations_ < 0 || !ImGui::IsAnyItemActive()) iterations_ = p.iterations;
  ImGui::SetNextItemWidth(-1);
  ImGui::SliderInt("##iterations", &iterations_, 1, 50, "%d iterations a frame");
  if (ImGui::IsItemDeactivatedAfterEdit()) p.iterations = iterations_, doc.set_posing(p);
  const auto& sel = doc.selection().handles;
  if (!sel.empty()) draw_handle_state(doc, sel.front());
  const FastSolveReport& f = doc.last_fast_solve();
  if (f.iterations > 0) {
    text_disabled_wrapped("last solve: %d iterations, %.1f us each", f.iterations, 1e6 * f.iterate_seconds / f.iterations);
    text_disabled_wrapped("%d rotation clusters, energy %.3g", f.clusters, f.energy);
  }
  if (f.precomputed) precompute_s_ = f.precompute_seconds;
  if (f.switched) switch_s_ = f.switch_seconds;
  if (precompute_s_ > 0) text_disabled_wrapped("precompute %.2f s, last switch %.2f ms", precompute_s_, 1e3 * switch_s_);
  draw_dynamics(doc, frame_rate);
}

// The handle's FAST state (pinned, position, free) and, for a bone, the IK chain to its tip.
void PosePanels::draw_handle_state(Document& doc, int h) {
  const std::vector<HandleConstraint> states = doc.handle_states();
  int s = static_cast<int>(states[h]);
  ImGui::TextWrapped("%d  %s is", h, handle_name(doc.rig(), h).c_str());
  bool changed = false;
  ItemFlow flow;
  for (HandleConstraint c : {HandleConstraint::Fixed, HandleConstraint::Position, HandleConstraint::Free}) {
    flow.next(ItemFlow::check_width(constraint_state_name(c)));
    changed |= ImGui::RadioButton(constraint_state_name(c), &s, static_cast<int>(c));
  }
  if (changed) {
    // A handle's state only matters to FAST: choosing one turns FAST on (one undo step), as the IK
    // chain does; FAST is off by default in every document.
    PosingSettings q = doc.posing();
    q.fast = true;
    q.states = states;
    q.states[h] = static_cast<HandleConstraint>(s);
    doc.set_posing(q);
  }
  const HandleRef r = handle_ref(doc.rig(), h);
  if (r.kind == HandleKind::Bone && ImGui::Button("IK chain to this bone's tip", ImVec2(-1, 0))) {
    PosingSettings q = doc.posing();
    q.fast = true;
    q.states = ik_chain_states(doc.rig(), states, h);
    doc.set_posing(q);
  }
  if (r.kind == HandleKind::Bone && ImGui::IsItemHovered())
    ImGui::SetTooltip("Frees the bones above this one (the chain's root stays pinned) and makes this bone's\n"
                      "tip the point you drag: move it and the chain follows.");
}

}  // namespace dfm::editor
