#pragma once
// The timeline's ruler: ticks on whole frames, the animated span, the keys (pose keys as amber diamonds,
// mesh keys as teal squares; drag one to move it, snapped to whole frames; right-click deletes it), the
// in-between bars and the current time; dragging elsewhere scrubs. Owns its drag state; every edit is
// one of the document's undoable calls.
#include <optional>
#include <string>
#include <utility>

#include "core/scene/document.h"

namespace dfm::editor {

class TimelineRuler {
 public:
  // Fills the current ImGui window's remaining space. A refused key move is reported in `error`.
  void draw(Document& doc, double frame_rate, std::string& error);
  bool dragging() const { return drag_ != Drag::None; }
  // A time window drawn as a band (the Space-time tool's), or none. The document's space-time edits'
  // windows are drawn fainter.
  void set_band(std::optional<std::pair<double, double>> band) { band_ = band; }

  // Where the ruler lies this frame: screen x of a time and back, over [t0, t1].
  struct Span {
    float x0 = 0, y0 = 0, w = 1, h = 1, pad = 10;
    double t0 = 0, t1 = 1;
    float x_of(double time) const { return x0 + pad + float((time - t0) / (t1 - t0)) * (w - 2 * pad); }
    double t_of(float x) const { return t0 + (t1 - t0) * double(x - x0 - pad) / double(w - 2 * pad); }
    float key_y() const { return y0 + h * 0.55f; }
  };

 private:
  enum class Drag { None, Scrub, Key };
  // Clicks, drags and right-clicks on the ruler (an invisible button over `s`): returns the key under
  // the cursor, -1 for none.
  int handle_input(Document& doc, const Span& s, double frame_rate, std::string& error);
  void draw_keys(const Document& doc, const Span& s, int hover_key) const;

  std::optional<std::pair<double, double>> band_;
  Drag drag_ = Drag::None;
  int drag_key_ = -1;
};

}  // namespace dfm::editor
