#pragma once
// The Shape space panel's state (editor view state: not in the document, not saved, not undoable):
// which keys are the bases (by time, in chain order), where each sits on the 2D pad, the cursor, the
// morph, and the shape space built from the document's keys (its ARAP setups kept while the bases'
// surfaces stay the same). ARAP shapes are synthesized on a worker thread (shape_space_cursor.h), the
// linear blend at the cursor standing in until the one for the cursor arrives. The panel itself is
// Editor::draw_shape_space_section.
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "app/editor/shape_space_cursor.h"
#include "core/anim/shape_space.h"
#include "core/anim/shape_space_pad.h"

namespace dfm::editor {

struct ShapeSpacePanel {
  std::vector<double> times;   // the bases: key times, in the order of Eq. 5.31's chain
  PadPoints points;            // one row per base, pad coordinates in [0, 1]^2 (v down)
  Eigen::Vector2d cursor{0.5, 0.5};
  ShapeMorph morph = ShapeMorph::Linear;
  bool preview = true;         // show the shape in the viewport
  bool open_request = false;   // --ui shape_space=...: open the header and scroll to it until built
  double key_time = 0;         // "Key this shape" keys at this time
  bool key_time_set = false;   // key_time follows the document's time until edited

  // Null until two or more bases build. Built from copies of the keys; shared with the worker's
  // requests, which alone call its synthesize (and fill its ARAP cache); this thread reads only its
  // bases, faces and morph, which synthesize never writes.
  std::shared_ptr<ShapeSpace> space;
  std::uint64_t built_revision = ~0ull;
  std::vector<double> built_times;
  ShapeMorph built_morph = ShapeMorph::Linear;
  std::string build_error;      // building the space from the keys

  Eigen::VectorXd weights;      // at the cursor
  CursorShape shape;            // what the viewport shows at the cursor (ARAP on a worker)
  int dragging_point = -1;
};

// Base i's default pad position: the n points on a circle (two: a horizontal segment).
Eigen::Vector2d default_pad_point(int i, int n);

}  // namespace dfm::editor
