#include "app/editor/pair_tool.h"

#include "core/scene/key_pairs.h"

namespace dfm::editor {

PairTool::Step PairTool::click(const Document& doc, const std::optional<Eigen::Vector3d>& hit) {
  const auto& keys = doc.keys();
  const int at = doc.key_at(doc.time());
  if (!first_) {
    if (at < 0 || at + 1 >= static_cast<int>(keys.size()))
      return {{}, {}, "Pair: go to a key with a key after it (the pair starts on that key)"};
    if (!hit) return {{}, {}, "Pair: click on the key's surface"};
    first_ = *hit;
    interval_ = at;
    return {{}, keys[at + 1].time, "Pair: now click its partner on the next key"};
  }
  if (interval_ + 1 >= static_cast<int>(keys.size()) || at != interval_ + 1) {
    first_.reset();
    return {{}, {}, "Pair: the keys changed; start again on a key"};
  }
  if (!hit) return {{}, {}, "Pair: click on this key's surface for the partner (Esc cancels)"};
  const Eigen::Vector3d& a = *first_;
  const Eigen::Vector3d& b = *hit;
  const CommandWords w = command_words("key-pair", {a.x(), a.y(), a.z(), b.x(), b.y(), b.z(), keys[interval_].time});
  const double back = keys[interval_].time;
  first_.reset();
  return {w, back, ""};
}

std::string PairTool::hint(const Document& doc) const {
  const auto& keys = doc.keys();
  std::string s = first_ ? "Click the partner on this key (Esc cancels)." : "On a key, click a point; then its partner on the next key.";
  if (keys.size() < 2) return s;
  const int k = first_ ? interval_ : pair_interval(doc, doc.time());
  if (k + 1 < static_cast<int>(keys.size()))
    s += " This interval has " + std::to_string(keys[k].pairs_to_next.rows()) + " pair(s).";
  return s;
}

}  // namespace dfm::editor
