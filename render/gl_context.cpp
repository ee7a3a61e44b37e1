#include "render/gl_context.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <chrono>
#include <cstdlib>
#include <mutex>
#include <string>
#include <thread>

#include "core/util/error.h"

namespace dfm::gl {
namespace {

std::mutex g_mutex;
int g_users = 0;
std::string g_last_error;

void on_glfw_error(int code, const char* msg) { g_last_error = msg ? msg : "unknown GLFW error"; }

// GLFW is process-global: initialise on first context, terminate after the last.
void acquire_glfw() {
  std::lock_guard<std::mutex> lock(g_mutex);
  if (g_users == 0) {
    glfwSetErrorCallback(on_glfw_error);
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((!display || !*display) && (!wayland || !*wayland))
      throw Error("no display found (DISPLAY is not set): run under a virtual X server, e.g. "
                  "xvfb-run -a -s \"-screen 0 1280x1024x24\" <command>");
    // A busy virtual X server (Xvfb beside CPU-heavy work) now and then refuses a connection that
    // succeeds a moment later: retry briefly before calling the display unreachable.
    bool ok = false;
    for (int attempt = 0; attempt < 5 && !ok; ++attempt) {
      if (attempt > 0) std::this_thread::sleep_for(std::chrono::milliseconds(250 * attempt));
      ok = glfwInit() == GLFW_TRUE;
    }
    if (!ok)
      throw Error("cannot initialise GLFW (" + g_last_error +
                  "): is a display reachable? Without one, run under xvfb-run -a <command>");
  }
  ++g_users;
}

void release_glfw() {
  std::lock_guard<std::mutex> lock(g_mutex);
  if (--g_users == 0) glfwTerminate();
}

}  // namespace

void check_error(const char* where) {
  GLenum first = glGetError();
  if (first == GL_NO_ERROR) return;
  while (glGetError() != GL_NO_ERROR) {
  }
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%04x", first);
  throw Error(std::string(where) + ": GL error " + buf);
}

Context::Context(const ContextOptions& opts) {
  acquire_glfw();
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_VISIBLE, opts.visible ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_SAMPLES, opts.samples);
  window_ = glfwCreateWindow(opts.width, opts.height, opts.title.c_str(), nullptr, nullptr);
  if (!window_) {
    std::string why = g_last_error;
    release_glfw();
    throw Error("cannot create an OpenGL 3.3 core context (" + why + ")");
  }
  glfwMakeContextCurrent(window_);
  if (epoxy_gl_version() < 33) {
    glfwDestroyWindow(window_);
    window_ = nullptr;
    release_glfw();
    throw Error("OpenGL 3.3 core is required; the driver offers only " +
                std::to_string(epoxy_gl_version() / 10) + "." + std::to_string(epoxy_gl_version() % 10));
  }
}

Context::~Context() {
  if (window_) {
    glfwDestroyWindow(window_);
    release_glfw();
  }
}

void Context::make_current() { glfwMakeContextCurrent(window_); }

std::string Context::renderer() const {
  const char* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const char* v = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return std::string(r ? r : "?") + ", " + (v ? v : "?");
}

bool display_available() {
  try {
    Context probe;
    return true;
  } catch (const Error&) {
    return false;
  }
}

}  // namespace dfm::gl
