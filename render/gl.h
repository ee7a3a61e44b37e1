#pragma once
// OpenGL through libepoxy (a maintained loader); include this instead of any GL header.
#include <epoxy/gl.h>

#include <string>

namespace dfm::gl {
// Throws dfm::Error "<where>: GL error 0x...." if glGetError reports one (drains the queue).
void check_error(const char* where);
}  // namespace dfm::gl
