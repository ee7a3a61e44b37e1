#pragma once
// The Paint tool (V): a brush on the surface under the cursor that paints the shape-preservation mask,
// a region handle, or the selected handle's weights (Ctrl/Shift erases; on weights it swaps Add and
// Subtract), one undo step per stroke, with its settings in the Tools panel. The mask and regions go
// through the document's paint_mask and paint_region; each weight dab is a paint-weights line
// (core/scene/weight_brush.h) run by the caller, so a script of those lines repeats the stroke. Owns
// its settings and its stroke.
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "app/editor/scene_view.h"
#include "core/scene/command.h"
#include "core/scene/document.h"
#include "core/scene/weight_brush.h"
#include "core/view/camera.h"

namespace dfm::editor {

enum class PaintTarget { Mask, Region, Weights };

class PaintTool {
 public:
  struct Input {
    Eigen::Vector2d mouse = Eigen::Vector2d::Zero();  // viewport pixels
    bool hovered = false;  // the cursor is over the viewport
    bool down = false, clicked = false, released = false;
    bool erase = false;  // Ctrl or Shift held
    std::vector<int> locked;  // handles the weight brush keeps (the Weights panel's locks)
  };
  // Runs a weight dab's line (the editor: as a UI command); false when it failed (the caller has said why).
  using Run = std::function<bool(const CommandWords& words)>;
  // Draws the brush circle where the cursor meets the surface and paints while the button is down.
  void update(Document& doc, SceneView& view, const view::Camera& cam, const Input& in, const Run& run = {});
  // The Tools panel's settings: target (mask, region or weights), radius, strength, falloff, "New
  // region"; for weights the mode, the mix value, front faces only and X mirror.
  void draw_options(Document& doc);
  void set_target(PaintTarget t) { target_ = t; }
  void set_weight_brush(WeightPaintMode mode, double value, bool front_only, bool mirror_x) {
    weight_mode_ = mode, weight_value_ = value, front_only_ = front_only, mirror_x_ = mirror_x;
  }
  void set_brush(double radius, double strength, double falloff) { radius_ = radius, strength_ = strength, falloff_ = falloff; }
  void new_document() { region_ = -1; }  // the region painted belonged to the old document
  bool painting() const { return painting_; }
  // Ends a stroke cut short (an error in an edit): closes its undo step.
  void cancel(Document& doc);

 private:
  PaintTarget target_ = PaintTarget::Mask;
  int region_ = -1;
  double radius_ = 0.08;  // fraction of the surface's bounding-box diagonal
  double strength_ = 0.5;
  double falloff_ = 0.5;  // 0 = hard edge, 1 = smooth to the rim
  WeightPaintMode weight_mode_ = WeightPaintMode::Add;
  double weight_value_ = 1.0;  // Mix's target
  bool front_only_ = true;
  bool mirror_x_ = false;
  bool painting_ = false;

  void draw_weight_options(const Document& doc);
  // The paint-weights line of one dab on the selected handle's weights (view: the pixel ray's direction).
  CommandWords weight_dab_line(const Document& doc, const Eigen::Vector3d& center, double radius,
                               const Eigen::Vector3d& view, const Input& in) const;
};

}  // namespace dfm::editor
