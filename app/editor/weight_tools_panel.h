#pragma once
// The Weights panel's "Weight tools" (Blender's weight paint menu) as one unit: their settings, the
// handles locked for normalize and smooth, what the last tool did, and the panel that shows and runs
// them. UI state only: each button runs one weights-* command of the table (SCRIPT.md), one undo step,
// exactly the line a script would give.
#include <functional>
#include <string>
#include <vector>

#include "core/scene/command.h"
#include "core/scene/document.h"

namespace dfm::editor {

struct WeightToolsUi {
  std::vector<int> locked;
  int limit_k = 4;
  float limit_radius = 1.0f;
  int smooth_iterations = 1;
  float smooth_factor = 0.5f;
  bool smooth_cotangent = false;
  int mirror_axis = 0;  // x y z
  float mirror_offset = 0.0f;
  int mirror_mode = 0;  // MirrorMode
  float report_threshold = 1e-3f;
  std::string last;  // what the last tool did

  // Runs a command line for the panel: true and what the command printed, or false (the caller has
  // shown why).
  using Run = std::function<bool(const CommandWords& words, std::string& printed)>;
  // Draws the tools into the current ImGui window and runs the one clicked.
  void draw(const Document& doc, const Run& run);
};

}  // namespace dfm::editor
