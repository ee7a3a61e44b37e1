#pragma once
// Reads the current framebuffer back and writes it as a PNG (atomically).
#include <cstdint>
#include <string>
#include <vector>

namespace dfm::gl {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // top row first
};

// glReadPixels of the bound read framebuffer's back buffer, flipped so row 0 is the top.
Image read_framebuffer(int width, int height);
// Throws dfm::Error naming the path when the file cannot be written.
void write_png(const std::string& path, const Image& image);
// Reads a PNG back (for tests). Throws dfm::Error naming the path.
Image read_png(const std::string& path);

}  // namespace dfm::gl
