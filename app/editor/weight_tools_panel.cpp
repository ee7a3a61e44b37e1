// The Weights panel's "Weight tools" (weight_tools_panel.h): limit total influences, normalize with
// locked handles, smooth, mirror, and the report of handles with no weight. Each button runs the
// script's weights-* command with the panel's settings as its words, so one undo step.
#include <algorithm>
#include <cstdio>
#include <functional>
#include <string>

#include <imgui.h>

#include "app/editor/weight_tools_panel.h"

#include "app/editor/editor.h"
#include "app/editor/theme.h"
#include "core/rig/rig.h"

namespace dfm::editor {
namespace {

std::vector<int> valid_locks(std::vector<int> locked, int num_handles) {
  locked.erase(std::remove_if(locked.begin(), locked.end(), [&](int h) { return h < 0 || h >= num_handles; }), locked.end());
  return locked;
}

// Runs one command line; what it printed becomes the panel's last line.
using RunTool = std::function<void(const CommandWords& words)>;

// The words after a command's own: the locked handles' numbers.
CommandWords with_locks(CommandWords w, const std::vector<int>& locked) {
  for (int h : locked) w.push_back(CommandArg(h).word);
  return w;
}

constexpr float kButtonW = 96;
// A row of settings then its button fits one line on a wide panel; on a narrow one (under 266 px) the
// settings take the whole line and the button the next, so no slider's text is cut.
bool roomy() { return ImGui::GetContentRegionAvail().x >= 266.0f; }  // k 70 + "radius 1.0" 84 + button 96 + spacing
// The width left on this line for one more item before a right-aligned button (wide) or the line's end.
float fill(bool wide) {
  return std::max(40.0f, ImGui::GetContentRegionAvail().x - (wide ? kButtonW + ImGui::GetStyle().ItemSpacing.x : 0.0f));
}

// A combo without an arrow (the panel is narrow).
void small_combo(const char* id, int& value, const char* const* items, int count) {
  if (!ImGui::BeginCombo(id, items[value], ImGuiComboFlags_NoArrowButton)) return;
  for (int i = 0; i < count; ++i)
    if (ImGui::Selectable(items[i], i == value)) value = i;
  ImGui::EndCombo();
}

void limit_smooth_normalize(const Document& doc, WeightToolsUi& ui, const RunTool& run) {
  const bool wide = roomy();
  ImGui::SetNextItemWidth(70);
  ImGui::SliderInt("##k", &ui.limit_k, 1, std::max(1, std::min(doc.num_handles(), 8)), "k %d");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(fill(wide));
  ImGui::SliderFloat("##radius", &ui.limit_radius, 0.0f, 5.0f, "radius %.1f");
  if (wide) ImGui::SameLine();
  if (ImGui::Button("Limit total", ImVec2(-1, 0)))
    run(command_words("weights-limit", {ui.limit_k, static_cast<double>(ui.limit_radius)}));
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Keeps each vertex's k largest weights; near each cut the kept weights are re-solved over\n"
                      "about `radius` edges so they fade out instead of jumping (0: plain cut and rescale).");
  ImGui::SetNextItemWidth(70);
  ImGui::SliderInt("##iter", &ui.smooth_iterations, 1, 20, "%d x");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(fill(wide));
  ImGui::SliderFloat("##factor", &ui.smooth_factor, 0.05f, 1.0f, "factor %.2f");
  if (wide) ImGui::SameLine();
  if (ImGui::Button("Smooth", ImVec2(-1, 0)))
    run(with_locks(command_words("weights-smooth", {ui.smooth_iterations, static_cast<double>(ui.smooth_factor),
                                                    ui.smooth_cotangent ? "cotan" : "uniform"}),
                   ui.locked));
  ImGui::Checkbox("cotangent", &ui.smooth_cotangent);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Smooth with cotangent weights instead of the plain neighbour mean.");
  ImGui::SameLine(ImGui::GetWindowContentRegionMax().x - kButtonW);
  if (ImGui::Button("Normalize", ImVec2(-1, 0)))
    run(with_locks(command_words("weights-normalize"), ui.locked));
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Rows back to a sum of 1, scaling only the unlocked handles.");
}

void mirror(WeightToolsUi& ui, const RunTool& run) {
  const bool wide = roomy();
  static const char* const axes[] = {"x", "y", "z"};
  static const char* const modes[] = {"+ to -", "- to +", "flip"};
  static const char* const mode_words[] = {"+", "-", "flip"};  // weights-mirror's, in MirrorMode order
  ImGui::SetNextItemWidth(28);
  small_combo("##axis", ui.mirror_axis, axes, 3);
  ImGui::SameLine();
  const float w = fill(wide), offset_w = 52;
  ImGui::SetNextItemWidth(offset_w);
  ImGui::InputFloat("##offset", &ui.mirror_offset, 0, 0, "%.3f");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("The plane: axis = this offset.");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(std::max(40.0f, w - offset_w - ImGui::GetStyle().ItemSpacing.x));
  small_combo("##mode", ui.mirror_mode, modes, 3);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("+ to -: the positive side copied onto the other; flip: both sides swap.");
  if (wide) ImGui::SameLine();
  if (ImGui::Button("Mirror", ImVec2(-1, 0)))
    run(command_words("weights-mirror", {axes[ui.mirror_axis], static_cast<double>(ui.mirror_offset), mode_words[ui.mirror_mode]}));
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Across the plane axis = offset. Handles pair by left/right names (l_arm / r_arm, arm.L / arm.R)\n"
                      "or else by mirrored position; a vertex reads the weights at its reflection on the surface.");
}

// The locks (normalize and smooth keep those columns) and the report of handles that move nothing.
void locks_and_report(const Document& doc, WeightToolsUi& ui) {
  const int nh = doc.num_handles();
  if (ImGui::TreeNode("locks", "Locked handles (%d)", int(ui.locked.size()))) {
    ImGui::BeginChild("##locks", ImVec2(0, std::min(150.0f, 22.0f * nh + 4)), true);
    for (int h = 0; h < nh; ++h) {
      bool on = std::find(ui.locked.begin(), ui.locked.end(), h) != ui.locked.end();
      if (ImGui::Checkbox((handle_name(doc.rig(), h) + "##lock" + std::to_string(h)).c_str(), &on)) {
        if (on) ui.locked.push_back(h);
        else ui.locked.erase(std::remove(ui.locked.begin(), ui.locked.end(), h), ui.locked.end());
      }
    }
    ImGui::EndChild();
    ImGui::TreePop();
  }
  ImGui::SetNextItemWidth(-1);
  ImGui::SliderFloat("##threshold", &ui.report_threshold, 1e-5f, 0.1f, "report weights below %.4f",
                     ImGuiSliderFlags_Logarithmic);
  const auto report = doc.weights_report(ui.report_threshold);
  if (report.empty()) {
    text_disabled_wrapped("every handle reaches it somewhere");
  } else {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.95f, 0.75f, 0.35f, 1));
    ImGui::TextWrapped("%d handle(s) move nothing:", int(report.size()));
    ImGui::PopStyleColor();
    for (const ZeroWeightHandle& z : report) ImGui::BulletText("%d %s (max %.2g)", z.handle, z.name.c_str(), z.max_weight);
  }
}

}  // namespace

void WeightToolsUi::draw(const Document& doc, const Run& run_command) {
  if (!doc.has_weights()) {
    text_disabled_wrapped("bind first: the tools edit the bind's weights");
    return;
  }
  locked = valid_locks(locked, doc.num_handles());
  const RunTool run = [&](const CommandWords& words) {
    std::string printed;
    if (run_command(words, printed)) last = printed;
  };
  limit_smooth_normalize(doc, *this, run);
  mirror(*this, run);
  locks_and_report(doc, *this);
  if (!last.empty()) ImGui::TextWrapped("%s", last.c_str());  // what the last tool did
}

void Editor::draw_weight_tools_section() {
  weight_tools_.draw(doc_, [&](const CommandWords& words, std::string& printed) { return run_ui_command(words, &printed); });
  // transfer-weights: a bound scene, or a mesh and then its weights file (editor_panels.cpp asks for it).
  const std::string why = command_unavailable("transfer-weights", doc_);
  const bool can = why.empty() && doc_.num_handles() > 0;
  if (!can) ImGui::BeginDisabled();
  if (ImGui::Button("Weights from..."))
    files_.show(FilePanel::Mode::Open, "Weights from a bound scene, or a mesh (then its weights)", "transfer-weights");
  if (!can) ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("%s", can ? "Carries another surface's weights onto this one (closest points, the rest inpainted)"
                                : "needs a surface and handles");
}

}  // namespace dfm::editor
