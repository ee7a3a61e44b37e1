#pragma once
// How posing by dragging (FAST, core/pose) treats a handle: pinned keeps its transform, position keeps
// where its anchor goes and solves the rest, free solves it entirely. Plain data of the rig and the
// scene file, so it lives here rather than beside the solver.
#include <string>

namespace dfm {

enum class HandleConstraint { Fixed, Position, Free };

const char* constraint_state_name(HandleConstraint s);  // "pinned", "position", "free"
HandleConstraint parse_constraint_state(const std::string& name);  // throws dfm::Error naming the word

}  // namespace dfm
