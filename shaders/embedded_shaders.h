#pragma once
// GLSL sources from shaders/*.glsl, compiled into the binary at build time.
#include <string>
#include <vector>

namespace dfm {
// The text of shaders/<name> (e.g. "surface.vert.glsl"); throws std::runtime_error if unknown.
const char* shader_source(const std::string& name);
std::vector<std::string> shader_names();
}  // namespace dfm
