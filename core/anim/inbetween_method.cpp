#include "core/anim/inbetween_method.h"

#include "core/util/error.h"

namespace dfm {

const char* inbetween_method_name(InbetweenMethod m) {
  switch (m) {
    case InbetweenMethod::Handles: return "handles";
    case InbetweenMethod::Arap: return "arap";
    case InbetweenMethod::Linear: return "linear";
  }
  return "handles";
}

InbetweenMethod parse_inbetween_method(const std::string& word) {
  for (InbetweenMethod m : {InbetweenMethod::Handles, InbetweenMethod::Arap, InbetweenMethod::Linear})
    if (word == inbetween_method_name(m)) return m;
  throw Error("in-between method '" + word + "': use handles, arap or linear");
}

}  // namespace dfm
