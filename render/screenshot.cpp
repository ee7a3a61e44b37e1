#include "render/screenshot.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#include <stb/stb_image.h>

#include <cstring>
#include <fstream>

#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "render/gl.h"

namespace dfm::gl {

Image read_framebuffer(int width, int height) {
  Image img;
  img.width = width;
  img.height = height;
  std::vector<std::uint8_t> raw(static_cast<size_t>(width) * height * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, raw.data());
  img.rgba.resize(raw.size());
  const size_t row = static_cast<size_t>(width) * 4;
  for (int y = 0; y < height; ++y)  // GL's row 0 is the bottom
    std::memcpy(&img.rgba[y * row], &raw[(height - 1 - y) * row], row);
  for (size_t i = 3; i < img.rgba.size(); i += 4) img.rgba[i] = 255;  // opaque file
  return img;
}

void write_png(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0) throw Error(path + ": cannot write an empty image");
  int len = 0;
  unsigned char* png = stbi_write_png_to_mem(image.rgba.data(), image.width * 4, image.width,
                                             image.height, 4, &len);
  if (!png) throw Error(path + ": PNG encoding failed");
  try {
    write_file_atomic(path, [&](std::ostream& out) { out.write(reinterpret_cast<const char*>(png), len); }, true);
  } catch (...) {
    STBIW_FREE(png);
    throw;
  }
  STBIW_FREE(png);
}

Image read_png(const std::string& path) {
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 4);
  if (!data) throw Error(path + ": cannot read PNG (" + std::string(stbi_failure_reason()) + ")");
  Image img;
  img.width = w;
  img.height = h;
  img.rgba.assign(data, data + static_cast<size_t>(w) * h * 4);
  stbi_image_free(data);
  return img;
}

}  // namespace dfm::gl
