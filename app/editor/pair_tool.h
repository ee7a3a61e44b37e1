#pragma once
// The Pair tool (issue 30): click a point on a key, the timeline goes to the next key, click its
// partner there; the pair reaches the document through the key-pair command (SCRIPT.md), so a script
// does exactly what the clicks did. Escape, or switching tools, forgets a first point. Owns the
// half-made pair; the document holds the finished ones (SceneKey::pairs_to_next).
#include <optional>
#include <string>

#include <Eigen/Core>

#include "core/scene/command.h"
#include "core/scene/document.h"

namespace dfm::editor {

class PairTool {
 public:
  // What a click asks of the editor: a command to run, a time to scrub to, a line for the status bar.
  struct Step {
    CommandWords command;
    std::optional<double> go_to;
    std::string status;
  };
  // A click at the document's current time; `hit` is where the cursor ray meets the shown surface.
  Step click(const Document& doc, const std::optional<Eigen::Vector3d>& hit);
  void cancel() { first_.reset(); }
  // The first point of a pair in the making (drawn by the editor), if any.
  const std::optional<Eigen::Vector3d>& first() const { return first_; }
  // The Tools panel's text: what to click next and how many pairs the interval holds.
  std::string hint(const Document& doc) const;

 private:
  std::optional<Eigen::Vector3d> first_;
  int interval_ = -1;  // the key the first point lies on
};

}  // namespace dfm::editor
