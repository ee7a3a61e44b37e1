#pragma once
// The timeline's ruler: ticks on whole frames, the animated span, the keys (pose keys as amber diamonds,
// mesh keys as teal squares; drag one to move it, snapped to whole frames; right-click deletes it), the
// in-between bars, the current time and the Space-time tool's window (drag an edge of its band to move
// it, snapped to whole frames); dragging elsewhere scrubs. Owns its drag state; every edit is
// one of the document's undoable calls.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "core/scene/document.h"

namespace dfm::editor {

// The band [first, second] with edge 0 (its start) or 1 (its end) dragged to time t: snapped to whole
// frames, and kept at least a frame wide (the other edge stays).
inline std::pair<double, double> dragged_band(std::pair<double, double> band, int edge, double t, double frame_rate) {
  const double snapped = std::round(t * frame_rate) / frame_rate, frame = 1 / frame_rate;
  if (edge == 0)
    band.first = std::min(snapped, band.second - frame);
  else
    band.second = std::max(snapped, band.first + frame);
  return band;
}

class TimelineRuler {
 public:
  // Fills the current ImGui window's remaining space. A refused key move is reported in `error`.
  void draw(Document& doc, double frame_rate, std::string& error);
  bool dragging() const { return drag_ != Drag::None; }
  // A time window drawn as a band (the Space-time tool's), or none; dragging either edge moves it (band()
  // then has the new window). The document's space-time edits' windows are drawn fainter.
  void set_band(std::optional<std::pair<double, double>> band) { band_ = band; }
  std::optional<std::pair<double, double>> band() const { return band_; }

  // Where the ruler lies this frame: screen x of a time and back, over [t0, t1].
  struct Span {
    float x0 = 0, y0 = 0, w = 1, h = 1, pad = 10;
    double t0 = 0, t1 = 1;
    float x_of(double time) const { return x0 + pad + float((time - t0) / (t1 - t0)) * (w - 2 * pad); }
    double t_of(float x) const { return t0 + (t1 - t0) * double(x - x0 - pad) / double(w - 2 * pad); }
    float key_y() const { return y0 + h * 0.55f; }
  };

 private:
  enum class Drag { None, Scrub, Key, BandStart, BandEnd };
  // Clicks, drags and right-clicks on the ruler (an invisible button over `s`): returns the key under
  // the cursor, -1 for none.
  int handle_input(Document& doc, const Span& s, double frame_rate, std::string& error);
  void draw_keys(const Document& doc, const Span& s, int hover_key) const;

  std::optional<std::pair<double, double>> band_;
  Drag drag_ = Drag::None;
  int drag_key_ = -1;
};

}  // namespace dfm::editor
