#pragma once
// A calm dark theme for the editor (neutral greys, one blue accent), scaled for HiDPI.
namespace dfm::editor {
void apply_theme(float scale);
}
