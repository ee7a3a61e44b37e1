#include "core/rig/handle_constraint.h"

#include "core/util/error.h"

namespace dfm {

const char* constraint_state_name(HandleConstraint s) {
  switch (s) {
    case HandleConstraint::Fixed: return "pinned";
    case HandleConstraint::Position: return "position";
    case HandleConstraint::Free: return "free";
  }
  return "pinned";
}

HandleConstraint parse_constraint_state(const std::string& name) {
  if (name == "pinned") return HandleConstraint::Fixed;
  if (name == "position") return HandleConstraint::Position;
  if (name == "free") return HandleConstraint::Free;
  throw Error("unknown handle state '" + name + "' (expected pinned, position or free)");
}

}  // namespace dfm
