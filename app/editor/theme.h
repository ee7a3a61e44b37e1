#pragma once
// A calm dark theme for the editor (neutral greys, one blue accent), scaled for HiDPI, and the few
// small widgets the panels share so that nothing they show is clipped on a narrow panel.
#include "app/editor/view_model.h"

namespace dfm::editor {
void apply_theme(float scale);

// Disabled-colour text that wraps at the panel's edge (ImGui::TextDisabled does not wrap).
void text_disabled_wrapped(const char* fmt, ...);

// Keeps items on one line while they fit the window's content width, else starts a new line
// (FlowCursor's rule, view_model.h). Call next(width) before each item with the width it takes.
class ItemFlow {
 public:
  ItemFlow();
  void next(float width);
  int rows() const { return row_ + 1; }  // rows used so far
  // The width a button with this label takes, and a checkbox or radio button.
  static float button_width(const char* label);
  static float check_width(const char* label);

 private:
  FlowCursor cursor_;
  bool first_ = true;
  int row_ = 0;
};
}  // namespace dfm::editor
