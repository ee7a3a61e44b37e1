#pragma once
// The Paint tool (V): a brush on the surface under the cursor that paints the shape-preservation mask
// or a region handle (Ctrl/Shift erases), one undo step per stroke through the document's paint_mask
// and paint_region, with its settings in the Tools panel. Owns its settings and its stroke.
#include <Eigen/Core>

#include "app/editor/scene_view.h"
#include "core/scene/document.h"
#include "core/view/camera.h"

namespace dfm::editor {

enum class PaintTarget { Mask, Region };

class PaintTool {
 public:
  struct Input {
    Eigen::Vector2d mouse = Eigen::Vector2d::Zero();  // viewport pixels
    bool hovered = false;  // the cursor is over the viewport
    bool down = false, clicked = false, released = false;
    bool erase = false;  // Ctrl or Shift held
  };
  // Draws the brush circle where the cursor meets the surface and paints while the button is down.
  void update(Document& doc, SceneView& view, const view::Camera& cam, const Input& in);
  // The Tools panel's settings: target (mask or region), radius, strength, falloff, "New region".
  void draw_options(Document& doc);
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
  bool painting_ = false;
};

}  // namespace dfm::editor
