#pragma once
// Atomic saves: write to a temporary file beside the target, flush, then rename over it.
// On any failure the previous file is untouched and an Error names the path and the cause.
#include <functional>
#include <ostream>
#include <string>

namespace dfm {

// Calls write(stream) on a temp file in the target's folder, then renames it to `path`.
void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& write,
                       bool binary = false);

// Lower-case extension without the dot ("obj" for "a/b.OBJ"), "" if none.
std::string file_extension(const std::string& path);

// Throws dfm::Error if `path` is missing, a directory, or unreadable.
void require_readable_file(const std::string& path);

}  // namespace dfm
