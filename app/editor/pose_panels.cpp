// The Transform section (typed moves and rotations of the selected handle) and the Posing section: FAST on or off, iterations per frame, the selected handle's state (pinned,
// position, free), an IK chain shortcut for bones, and the last solve's timings. Every change is a
// document command (undoable); the solve itself runs inside the document's pose edits.
#include <cstdio>

#include <imgui.h>

#include "app/editor/editor.h"
#include "core/pose/fast_rig.h"
#include "core/rig/rig.h"

namespace dfm::editor {

void Editor::draw_transform_section() {
  const auto& sel = doc_.selection().handles;
  if (sel.empty()) {
    ImGui::TextDisabled("no handle selected");
    return;
  }
  const int h = sel.front();
  const Rig& rig = doc_.rig();
  const HandleRef r = handle_ref(rig, h);
  ImGui::Text("%s  (%s)", handle_name(rig, h).c_str(), handle_kind_name(r.kind));
  Pose pose = doc_.pose();
  if (h < pose.size()) {
    const Eigen::Affine3d& T = pose.transforms[h];
    const Eigen::Vector3d pivot = doc_.handle_pivot(h);
    // Typed values: world offset of the pivot and rotation (axis-angle) of this handle's transform.
    const Eigen::Vector3d offset = T * pivot - pivot;
    float t[3] = {float(offset.x()), float(offset.y()), float(offset.z())};
    ImGui::SetNextItemWidth(-1);
    if (ImGui::DragFloat3("##move", t, 0.002f * float(cam_.scene_radius), 0, 0, "%.3f")) {
      if (ImGui::IsItemActivated()) doc_.begin_gesture();
      doc_.translate_handle(h, Eigen::Vector3d(t[0], t[1], t[2]) - offset);
    }
    if (ImGui::IsItemDeactivated()) doc_.end_gesture();
    ImGui::TextDisabled("translation (world)");
    if (r.kind != HandleKind::CageVertex) {
      Eigen::AngleAxisd aa(T.linear());
      static float deg[3] = {0, 0, 0};
      ImGui::SetNextItemWidth(-1);
      ImGui::InputFloat3("##rot", deg, "%.1f");
      ImGui::TextDisabled("rotation now: %.1f deg about (%.2f %.2f %.2f)", aa.angle() * 180 / M_PI, aa.axis().x(),
                          aa.axis().y(), aa.axis().z());
      if (ImGui::Button("Apply rotation (XYZ degrees)", ImVec2(-1, 0))) {
        const Eigen::Quaterniond q = Eigen::AngleAxisd(deg[2] * M_PI / 180, Eigen::Vector3d::UnitZ()) *
                                     Eigen::AngleAxisd(deg[1] * M_PI / 180, Eigen::Vector3d::UnitY()) *
                                     Eigen::AngleAxisd(deg[0] * M_PI / 180, Eigen::Vector3d::UnitX());
        doc_.rotate_handle(h, q);
      }
    }
  }
  if (ImGui::Button("Reset pose", ImVec2(-1, 0))) doc_.reset_pose();
}

void Editor::draw_posing_section() {
  PosingSettings p = doc_.posing();
  if (ImGui::Checkbox("Drag solves the free handles (FAST)", &p.fast)) doc_.set_posing(p);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Jacobson 2013 ch. 7: handles not pinned get the transforms that keep the shape as rigid\n"
                      "as possible; a point you drag keeps its position and gets its rotation solved.");
  if (!doc_.has_weights()) ImGui::TextDisabled("bind first: FAST solves with the weights");
  static int iterations = p.iterations;
  if (!ImGui::IsAnyItemActive()) iterations = p.iterations;
  ImGui::SetNextItemWidth(-110);
  ImGui::SliderInt("iterations/frame", &iterations, 1, 50);
  if (ImGui::IsItemDeactivatedAfterEdit()) p.iterations = iterations, doc_.set_posing(p);

  const auto& sel = doc_.selection().handles;
  if (!sel.empty()) {
    const int h = sel.front();
    const std::vector<HandleConstraint> states = doc_.handle_states();
    int s = static_cast<int>(states[h]);
    ImGui::Text("%s is", handle_name(doc_.rig(), h).c_str());
    bool changed = ImGui::RadioButton("pinned", &s, static_cast<int>(HandleConstraint::Fixed));
    ImGui::SameLine();
    changed |= ImGui::RadioButton("position", &s, static_cast<int>(HandleConstraint::Position));
    ImGui::SameLine();
    changed |= ImGui::RadioButton("free", &s, static_cast<int>(HandleConstraint::Free));
    if (changed) doc_.set_handle_state(h, static_cast<HandleConstraint>(s));
    const HandleRef r = handle_ref(doc_.rig(), h);
    if (r.kind == HandleKind::Bone && ImGui::Button("IK chain to this bone's tip", ImVec2(-1, 0))) {
      PosingSettings q = doc_.posing();
      q.fast = true;
      q.states = ik_chain_states(doc_.rig(), states, h);
      doc_.set_posing(q);
    }
    if (r.kind == HandleKind::Bone && ImGui::IsItemHovered())
      ImGui::SetTooltip("Frees the bones above this one (the chain's root stays pinned) and makes this bone's\n"
                        "tip the point you drag: move it and the chain follows.");
  }
  const FastSolveReport& f = doc_.last_fast_solve();
  if (f.iterations > 0) {
    ImGui::TextDisabled("last solve: %d iterations, %.1f us each", f.iterations, 1e6 * f.iterate_seconds / f.iterations);
    ImGui::TextDisabled("%d rotation clusters, energy %.3g", f.clusters, f.energy);
  }
  static double precompute = 0, switched = 0;
  if (f.precomputed) precompute = f.precompute_seconds;
  if (f.switched) switched = f.switch_seconds;
  if (precompute > 0) ImGui::TextDisabled("precompute %.2f s, last switch %.2f ms", precompute, 1e3 * switched);
}

}  // namespace dfm::editor
