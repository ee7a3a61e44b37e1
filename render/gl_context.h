#pragma once
// An OpenGL 3.3 core context in a GLFW window (hidden for offscreen work: tests, `deform pose`).
// Without a display the constructor throws dfm::Error telling the user to run under xvfb-run.
#include <string>

#include "render/gl.h"

struct GLFWwindow;

namespace dfm::gl {

struct ContextOptions {
  int width = 1280;
  int height = 800;
  bool visible = false;
  int samples = 0;  // MSAA samples for the default framebuffer (windows only)
  std::string title = "deform";
};

class Context {
 public:
  explicit Context(const ContextOptions& opts = {});
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  GLFWwindow* window() const { return window_; }
  void make_current();
  // "Mesa llvmpipe (LLVM 15...), 4.5 (Core Profile) Mesa 22.3.6" etc.
  std::string renderer() const;

 private:
  GLFWwindow* window_ = nullptr;
};

// True when a context can be created here (a display is reachable and GLFW initialises).
bool display_available();

}  // namespace dfm::gl
