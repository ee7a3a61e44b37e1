#pragma once
// Shader programs built from embedded shaders (shaders/*.glsl). Each stage file holds the body
// without a #version line; the build prepends "#version 330 core" and the given defines.
#include <string>
#include <vector>

#include "render/gl.h"

namespace dfm::gl {

struct ProgramDesc {
  std::string vertex;    // shader file names, e.g. "skin.vert.glsl"
  std::string geometry;  // optional
  std::string fragment;  // optional (transform-feedback-only programs have none)
  std::vector<std::string> defines;              // e.g. {"METHOD_DQS", "K 8"} -> #define METHOD_DQS, #define K 8
  std::vector<std::string> feedback_varyings;    // transform feedback outputs, captured interleaved
};

class Program {
 public:
  Program() = default;
  explicit Program(const ProgramDesc& desc);
  ~Program();
  Program(Program&& o) noexcept;
  Program& operator=(Program&& o) noexcept;
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  GLuint id() const { return id_; }
  void use() const { glUseProgram(id_); }
  // -1 when the uniform is absent or optimised away (setting it is then a no-op, as in GL).
  GLint uniform(const char* name) const { return glGetUniformLocation(id_, name); }

 private:
  GLuint id_ = 0;
};

// Compiles one stage; throws dfm::Error with the driver's log and the shader's name.
GLuint compile_shader(GLenum type, const std::string& name, const std::vector<std::string>& defines);

}  // namespace dfm::gl
