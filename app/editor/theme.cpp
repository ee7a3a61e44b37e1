#include "app/editor/theme.h"

#include <cstdarg>

#include <imgui.h>

namespace dfm::editor {

void apply_theme(float scale) {
  ImGuiStyle& s = ImGui::GetStyle();
  ImGui::StyleColorsDark(&s);
  s.WindowRounding = 0.0f;
  s.ChildRounding = 3.0f;
  s.FrameRounding = 3.0f;
  s.GrabRounding = 3.0f;
  s.PopupRounding = 3.0f;
  s.ScrollbarRounding = 3.0f;
  s.TabRounding = 3.0f;
  s.WindowBorderSize = 1.0f;
  s.FrameBorderSize = 0.0f;
  s.WindowPadding = ImVec2(10, 8);
  s.FramePadding = ImVec2(7, 4);
  s.ItemSpacing = ImVec2(8, 6);
  s.ItemInnerSpacing = ImVec2(6, 4);
  s.IndentSpacing = 14.0f;
  s.ScrollbarSize = 12.0f;
  s.GrabMinSize = 9.0f;

  ImVec4* c = s.Colors;
  const ImVec4 bg(0.105f, 0.110f, 0.120f, 1.0f), panel(0.135f, 0.140f, 0.152f, 1.0f);
  const ImVec4 frame(0.190f, 0.197f, 0.214f, 1.0f), frame_hi(0.235f, 0.245f, 0.265f, 1.0f);
  const ImVec4 accent(0.310f, 0.560f, 0.900f, 1.0f), accent_dim(0.260f, 0.420f, 0.660f, 1.0f);
  c[ImGuiCol_Text] = ImVec4(0.88f, 0.89f, 0.91f, 1.0f);
  c[ImGuiCol_TextDisabled] = ImVec4(0.52f, 0.54f, 0.58f, 1.0f);
  c[ImGuiCol_WindowBg] = panel;
  c[ImGuiCol_ChildBg] = ImVec4(0.115f, 0.120f, 0.130f, 1.0f);
  c[ImGuiCol_PopupBg] = ImVec4(0.120f, 0.125f, 0.137f, 0.98f);
  c[ImGuiCol_Border] = ImVec4(0.060f, 0.062f, 0.068f, 1.0f);
  c[ImGuiCol_FrameBg] = frame;
  c[ImGuiCol_FrameBgHovered] = frame_hi;
  c[ImGuiCol_FrameBgActive] = ImVec4(0.27f, 0.29f, 0.32f, 1.0f);
  c[ImGuiCol_TitleBg] = bg;
  c[ImGuiCol_TitleBgActive] = bg;
  c[ImGuiCol_MenuBarBg] = bg;
  c[ImGuiCol_ScrollbarBg] = ImVec4(0, 0, 0, 0);
  c[ImGuiCol_CheckMark] = accent;
  c[ImGuiCol_SliderGrab] = accent_dim;
  c[ImGuiCol_SliderGrabActive] = accent;
  c[ImGuiCol_Button] = frame;
  c[ImGuiCol_ButtonHovered] = frame_hi;
  c[ImGuiCol_ButtonActive] = accent_dim;
  c[ImGuiCol_Header] = ImVec4(0.22f, 0.30f, 0.42f, 1.0f);
  c[ImGuiCol_HeaderHovered] = ImVec4(0.26f, 0.36f, 0.50f, 1.0f);
  c[ImGuiCol_HeaderActive] = accent_dim;
  c[ImGuiCol_Separator] = ImVec4(0.21f, 0.22f, 0.24f, 1.0f);
  c[ImGuiCol_Tab] = frame;
  c[ImGuiCol_TabHovered] = accent_dim;
  c[ImGuiCol_TabActive] = ImVec4(0.24f, 0.34f, 0.50f, 1.0f);
  c[ImGuiCol_PlotHistogram] = accent;
  c[ImGuiCol_PlotLines] = accent;
  s.ScaleAllSizes(scale);
  ImGui::GetIO().FontGlobalScale = scale;
}

void text_disabled_wrapped(const char* fmt, ...) {
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
  va_list args;
  va_start(args, fmt);
  ImGui::TextWrappedV(fmt, args);
  va_end(args);
  ImGui::PopStyleColor();
}

ItemFlow::ItemFlow() {
  cursor_.avail = ImGui::GetContentRegionAvail().x;
  cursor_.spacing = ImGui::GetStyle().ItemSpacing.x;
}

void ItemFlow::next(float width) {
  const int row = cursor_.place(width);
  if (!first_ && row == row_) ImGui::SameLine();
  first_ = false;
  row_ = row;
}

float ItemFlow::button_width(const char* label) {
  return ImGui::CalcTextSize(label, nullptr, true).x + 2 * ImGui::GetStyle().FramePadding.x;
}

float ItemFlow::check_width(const char* label) {
  const float text = ImGui::CalcTextSize(label, nullptr, true).x;
  return ImGui::GetFrameHeight() + (text > 0 ? ImGui::GetStyle().ItemInnerSpacing.x + text : 0.0f);
}

}  // namespace dfm::editor
