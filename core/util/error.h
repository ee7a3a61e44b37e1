#pragma once
// One exception type for every user-facing failure: the message names the file and the problem.
#include <sstream>
#include <stdexcept>
#include <string>

namespace dfm {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& msg) : std::runtime_error(msg) {}
};

// The user stopped the work (a cancel flag, or a progress callback returning false): not a failure.
// Thrown by bind, bake and the animation manifold's build; callers tell it from an error by its type.
class Cancelled : public Error {
 public:
  explicit Cancelled(const std::string& msg = "cancelled") : Error(msg) {}
};

// "path:line: problem" (line <= 0 omits it).
inline Error file_error(const std::string& path, long line, const std::string& problem) {
  std::ostringstream s;
  s << path;
  if (line > 0) s << ":" << line;
  s << ": " << problem;
  return Error(s.str());
}

// "path: byte offset N: problem", for binary formats.
inline Error byte_error(const std::string& path, long long offset, const std::string& problem) {
  std::ostringstream s;
  s << path << ": byte offset " << offset << ": " << problem;
  return Error(s.str());
}

}  // namespace dfm
