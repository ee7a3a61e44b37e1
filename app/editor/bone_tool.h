#pragma once
// The Bones tool (B): clicks inside the surface add joints to a chain (started on an existing joint,
// the chain hangs from it); right-click or Enter finishes it through the add-bone / add-bone-from
// command (SCRIPT.md), Esc drops it. Owns the chain in the making and draws its preview.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "app/editor/scene_view.h"
#include "core/scene/command.h"
#include "core/view/camera.h"

namespace dfm::editor {

class BoneTool {
 public:
  struct Input {
    Eigen::Vector2d mouse = Eigen::Vector2d::Zero();  // viewport pixels
    bool hovered = false, clicked = false;
  };
  // A click: on a joint (first click only) the chain starts there, else inside the surface (or, off
  // it, at the last joint's depth) a joint is added. Returns a status line ("" when none).
  std::string click(SceneView& view, const view::Camera& cam, const Eigen::Vector2d& mouse);
  // Draws the chain so far and a rubber band to the cursor.
  void draw_preview(SceneView& view, const view::Camera& cam, const Input& in) const;
  // The command that adds the chain (empty words when it has no bone yet), and forgets the chain.
  CommandWords finish();
  void cancel() { joints_.clear(), parent_ = -1; }
  bool active() const { return !joints_.empty(); }
  int joints() const { return static_cast<int>(joints_.size()); }

 private:
  std::vector<Eigen::Vector3d> joints_;  // the chain's joints; with parent_ >= 0 the first is that joint
  int parent_ = -1;
};

}  // namespace dfm::editor
