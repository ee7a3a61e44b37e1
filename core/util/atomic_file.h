#pragma once
// Atomic saves: write to a temporary file beside the target, flush and close it, then rename it over
// the target. On any failure (full disk, permission denied, a writer that throws) the previous file
// is untouched, no temporary file is left behind, and an Error names the path and the cause.
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace dfm {

// Calls write(stream) on a temp file in the target's folder, then renames it to `path`.
void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& write,
                       bool binary = false);

// Several files that belong together (a scene's JSON and its sidecar): every file is written to its
// own temp first; only when all writes succeeded are they renamed into place, in the given order.
// So a full disk or a refused folder while writing any of them leaves every previous file as it was.
struct AtomicWrite {
  std::string path;
  std::function<void(std::ostream&)> write;
  bool binary = false;
};
void write_files_atomic(const std::vector<AtomicWrite>& files);

// Lower-case extension without the dot ("obj" for "a/b.OBJ"), "" if none.
std::string file_extension(const std::string& path);

// Throws dfm::Error if `path` is missing, a directory, a pipe or socket, or unreadable.
void require_readable_file(const std::string& path);

}  // namespace dfm
