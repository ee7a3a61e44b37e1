// The Posing section's dynamics part: the switch that makes drags live, its settings, and Simulate
// (document.h's dynamics; every change a document command, Simulate one undo step).
#include <cstdio>
#include <exception>
#include <limits>

#include <imgui.h>

#include "app/editor/pose_panels.h"
#include "app/editor/theme.h"

namespace dfm::editor {

void PosePanels::draw_dynamics(Document& doc, double frame_rate) {
  ImGui::Separator();
  try {
    draw_dynamics_controls(doc, frame_rate);
      } catch (const std::exception& e) {
    dynamics_error_ = e.what();
  }
  if (!dynamics_error_.empty()) ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", dynamics_error_.c_str());
}

void PosePanels::draw_dynamics_controls(Document& doc, double frame_rate) {
  PosingSettings p = doc.posing();
  if (ImGui::Checkbox("Dynamics", &p.dynamics)) {
    p.fast = p.fast || p.dynamics;  // the Pose tool's drags solve only with FAST on (as `dynamics on`)
    doc.set_posing(p);
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Secondary dynamics (Jacobson 2013, 7.7): a drag steps a simulation once a frame, so\n"
                      "free handles lag, overshoot and settle; it keeps stepping after the drag until the\n"
                      "mesh is still. Undo restores the pose from before the drag.");
  float hz = float(1.0 / p.dt), damping = float(p.damping), density = float(p.density);
  ImGui::SetNextItemWidth(-1);
  ImGui::DragFloat("##dyn_rate", &hz, 0.5f, 1.0f, 1000.0f, "step 1/%.0f s", ImGuiSliderFlags_AlwaysClamp);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Time step of a live drag (one step per drawn frame: 60 for a 60 Hz display)");
  if (ImGui::IsItemDeactivatedAfterEdit()) p.dt = 1.0 / hz, doc.set_posing(p);
  ImGui::SetNextItemWidth(-1);
  ImGui::DragFloat("##dyn_damping", &damping, 0.05f, 0.0f, 100.0f, "damping %.2f /s", ImGuiSliderFlags_AlwaysClamp);
  if (ImGui::IsItemDeactivatedAfterEdit()) p.damping = damping, doc.set_posing(p);
  ImGui::SetNextItemWidth(-1);
  ImGui::DragFloat("##dyn_density", &density, 0.01f, 0.01f, 100.0f, "density %.2f", ImGuiSliderFlags_AlwaysClamp);
  if (ImGui::IsItemDeactivatedAfterEdit()) p.density = density, doc.set_posing(p);
  if (doc.dynamics_live()) text_disabled_wrapped("settling...");
  char label[64];
  std::snprintf(label, sizeof label, "Simulate at %.0f fps", frame_rate);
  ImGui::BeginDisabled(!doc.has_weights() || doc.keys().empty());
  if (ImGui::Button(label, ImVec2(-1, 0))) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    doc.simulate(frame_rate, nan, nan);
    dynamics_error_.clear();
  }
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("Runs the keyed animation through the dynamics (keyed handles follow their keys, free\n"
                      "handles follow by momentum) and keys every frame, replacing the keys: one undo step.");
}

}  // namespace dfm::editor
