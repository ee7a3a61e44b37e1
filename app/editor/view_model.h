#pragma once
// What the editor's panels and viewport show, computed as plain data from the document and the window
// size: no ImGui, no GL, so tests/test_editor_view_model.cpp checks it directly. The ImGui code in
// editor_panels.cpp, pose_panels.cpp and editor_timeline.cpp only draws what these return.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/anim/key_alignment.h"
#include "core/scene/document.h"
#include "core/view/camera.h"

namespace dfm::editor {

struct Rect {
  double x = 0, y = 0, w = 1, h = 1;
  bool contains(double px, double py) const { return px >= x && py >= y && px < x + w && py < y + h; }
};

// The fixed panels around the viewport in a window of width x height pixels under a menu bar `top`
// high, with a timeline `timeline_h` high, at UI `scale`. The side panels narrow on small windows (down
// to what their widgets need) so the viewport keeps what is left; nothing overlaps the viewport.
struct PanelLayout {
  Rect left, right, timeline, viewport;
};
PanelLayout layout_panels(double width, double height, double top, double timeline_h, double scale = 1.0);

// Items laid left to right in `avail` pixels, `spacing` apart, wrapping to a new row when the next one
// would not fit (an item wider than a row gets a row of its own). place(width) returns its row.
struct FlowCursor {
  double avail = 0, spacing = 0;
  double x = 0;  // width used on the current row
  int row = 0;
  int place(double width);
};
// The row of each of these widths (FlowCursor over all of them).
std::vector<int> flow_rows(const std::vector<double>& widths, double avail, double spacing);

// Why the editor cannot open `path` by its extension ("" when it can): the formats it opens, e.g. for a
// .glb, which is an export format only.
std::string unopenable_reason(const std::string& path);

// How the key interval k -> k + 1 is joined: its in-between method, or a transition where the two
// keys' surfaces differ in connectivity (the method does not apply then).
enum class IntervalJoin { Handles, Arap, Linear, Transition };
IntervalJoin interval_join(const Document& doc, int k);
// "handles", "ARAP", "linear", "transition (different meshes)".
const char* interval_join_label(IntervalJoin join);
// The key interval holding time t: k with keys[k].time <= t <= keys[k + 1].time, -1 outside the keys.
int interval_at(const Document& doc, double t);

// True when key k's surface is the rigged mesh's connectivity (a pose key, or a mesh key with the
// surface's triangles): the rig's handles mean something over it.
bool key_is_rigged(const Document& doc, int k);
// How opaque the rig overlays (handles, bones, cages) are over the animation at time t: 1 where the
// surface shown is the rigged mesh, 0 at a key of another connectivity, and inside a transition a
// linear fade from the rigged key's end (1) to the other's (0).
float rig_overlay_opacity(const Document& doc, double t);
// Below this opacity the overlays are not drawn at all, and the handles cannot be picked.
constexpr float kMinOverlayOpacity = 0.02f;

// Text at a point of the viewport (pixels from its top left, as view::project_to_pixel gives them).
struct ViewportLabel {
  std::string text;
  double x = 0, y = 0;
};
// Where the picked pairs of the interval at the document's time are now (pair_position; #pairs x 3),
// with the transition's `placement`; empty at or outside the interval's keys or without a placement.
Eigen::MatrixXd pairs_now(const Document& doc, const KeyPlacement* placement);
// The numbers of the picked pairs of the interval at the document's time (pair_interval), from 1 as
// the Pair tool's count reads: each beside both of its points, and, inside the interval with the
// transition's `placement` (null: none), beside where the pair is now (pair_position), `offset`
// pixels to their upper right; none for a point outside the camera's depth range.
std::vector<ViewportLabel> pair_labels(const Document& doc, const view::Camera& cam, const KeyPlacement* placement,
                                       double offset = 6);

// The outliner's row for handle h: its number (what scripts take), its name and, when FAST is on and
// `with_state`, its state, e.g. "5  l_upper_arm  [pinned]" (a narrow outliner marks the state on the
// swatch instead).
std::string outliner_label(const Document& doc, int h, bool with_state = true);

// A value as a field shows it with `decimals` decimals: rounded there, and never a negative zero.
double display_value(double v, int decimals);

// Time shown as animation tools do: the frame at `fps` frames a second and the seconds,
// e.g. "frame 12  (0.500 s)"; a time between frames shows its fraction ("frame 12.4").
double time_to_frame(double t, double fps);
std::string format_time(double t, double fps);

// The selection's look in the viewport: a body colour and an outline (a wider line or point under the
// handle) that no handle colour (handle_color) comes near.
struct SelectionStyle {
  Eigen::Vector4f body{1.0f, 0.52f, 0.05f, 1.0f};    // orange
  Eigen::Vector4f outline{1.0f, 1.0f, 1.0f, 1.0f};  // white
  float line_extra = 5.0f;   // the outline line is this much wider than the handle's
  float point_extra = 7.0f;  // ...and the outline point this much larger
};
const SelectionStyle& selection_style();
// Handle colours keep their hues out of this band (degrees) around the selection's orange.
constexpr double kSelectionHueLo = 10.0, kSelectionHueHi = 70.0;

}  // namespace dfm::editor
