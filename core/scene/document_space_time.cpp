// The document's space-time edits (space_time_edit.h): stored with the keys, undone with them.
#include <string>

#include "core/scene/document.h"
#include "core/scene/document_parts.h"
#include "core/util/error.h"

namespace dfm {

void Document::add_space_time_edit(const SpaceTimeEdit& e) {
  check_space_time_edit(e);
  // Its merge target is set_space_time_edit's: the tool's drag that starts a new edit stays one step.
  execute("space-time edit", kKeys, "space-time edit " + std::to_string(s_.space_time_edits.size()),
          [&](SceneData& s) { s.space_time_edits.push_back(e); });
}

void Document::set_space_time_edit(int index, const SpaceTimeEdit& e) {
  if (index < 0 || index >= static_cast<int>(s_.space_time_edits.size()))
    throw Error("no space-time edit " + std::to_string(index) + " (the scene has " +
                std::to_string(s_.space_time_edits.size()) + ")");
  check_space_time_edit(e);
  if (s_.space_time_edits[index] == e) return;
  execute("space-time drag", kKeys, "space-time edit " + std::to_string(index),
          [&](SceneData& s) { s.space_time_edits[index] = e; });
}

void Document::clear_space_time_edits() {
  if (s_.space_time_edits.empty()) return;
  execute("clear space-time edits", kKeys, "", [](SceneData& s) { s.space_time_edits.clear(); });
}

}  // namespace dfm
