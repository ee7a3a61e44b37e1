#include "render/gl_program.h"

#include <utility>

#include "core/util/error.h"
#include "shaders/embedded_shaders.h"

namespace dfm::gl {

GLuint compile_shader(GLenum type, const std::string& name, const std::vector<std::string>& defines) {
  std::string src = "#version 330 core\n";
  for (const auto& d : defines) src += "#define " + d + "\n";
  src += "#line 1\n";
  src += shader_source(name);
  GLuint s = glCreateShader(type);
  const char* p = src.c_str();
  glShaderSource(s, 1, &p, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetShaderiv(s, GL_INFO_LOG_LENGTH, &len);
    std::string log(len > 0 ? len : 1, '\0');
    glGetShaderInfoLog(s, len, nullptr, log.data());
    glDeleteShader(s);
    throw Error("shader " + name + " failed to compile:\n" + log);
  }
  return s;
}

Program::Program(const ProgramDesc& d) {
  std::vector<GLuint> stages;
  try {
    stages.push_back(compile_shader(GL_VERTEX_SHADER, d.vertex, d.defines));
    if (!d.geometry.empty()) stages.push_back(compile_shader(GL_GEOMETRY_SHADER, d.geometry, d.defines));
    if (!d.fragment.empty()) stages.push_back(compile_shader(GL_FRAGMENT_SHADER, d.fragment, d.defines));
  } catch (...) {
    for (GLuint s : stages) glDeleteShader(s);
    throw;
  }
  id_ = glCreateProgram();
  for (GLuint s : stages) glAttachShader(id_, s);
  if (!d.feedback_varyings.empty()) {
    std::vector<const char*> names;
    for (const auto& v : d.feedback_varyings) names.push_back(v.c_str());
    glTransformFeedbackVaryings(id_, static_cast<GLsizei>(names.size()), names.data(), GL_INTERLEAVED_ATTRIBS);
  }
  glLinkProgram(id_);
  for (GLuint s : stages) {
    glDetachShader(id_, s);
    glDeleteShader(s);
  }
  GLint ok = 0;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetProgramiv(id_, GL_INFO_LOG_LENGTH, &len);
    std::string log(len > 0 ? len : 1, '\0');
    glGetProgramInfoLog(id_, len, nullptr, log.data());
    glDeleteProgram(id_);
    id_ = 0;
    throw Error("program (" + d.vertex + (d.geometry.empty() ? "" : ", " + d.geometry) +
                (d.fragment.empty() ? "" : ", " + d.fragment) + ") failed to link:\n" + log);
  }
}

Program::~Program() {
  if (id_) glDeleteProgram(id_);
}

Program::Program(Program&& o) noexcept : id_(std::exchange(o.id_, 0)) {}

Program& Program::operator=(Program&& o) noexcept {
  if (this != &o) {
    if (id_) glDeleteProgram(id_);
    id_ = std::exchange(o.id_, 0);
  }
  return *this;
}

}  // namespace dfm::gl
