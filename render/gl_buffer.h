#pragma once
// RAII wrappers for GL objects that passes own: buffers, vertex arrays, textures, queries.
#include <cstddef>
#include <utility>
#include <vector>

#include "render/gl.h"
#include "render/vertex_format.h"

namespace dfm::gl {

class Buffer {
 public:
  Buffer() { glGenBuffers(1, &id_); }
  ~Buffer() {
    if (id_) glDeleteBuffers(1, &id_);
  }
  Buffer(Buffer&& o) noexcept : id_(std::exchange(o.id_, 0)), bytes_(o.bytes_) {}
  Buffer& operator=(Buffer&& o) noexcept {
    if (this != &o) {
      if (id_) glDeleteBuffers(1, &id_);
      id_ = std::exchange(o.id_, 0);
      bytes_ = o.bytes_;
    }
    return *this;
  }
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  GLuint id() const { return id_; }
  size_t bytes() const { return bytes_; }

  // (Re)allocates and fills; data may be null to only allocate.
  void upload(GLenum target, const void* data, size_t bytes, GLenum usage = GL_STATIC_DRAW) {
    glBindBuffer(target, id_);
    glBufferData(target, static_cast<GLsizeiptr>(bytes), data, usage);
    bytes_ = bytes;
  }
  template <class T>
  void upload(GLenum target, const std::vector<T>& v, GLenum usage = GL_STATIC_DRAW) {
    upload(target, v.data(), v.size() * sizeof(T), usage);
  }
  void update(GLenum target, const void* data, size_t bytes, size_t offset = 0) {
    glBindBuffer(target, id_);
    glBufferSubData(target, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
  }
  // Reads `count` elements of T back from the start of the buffer.
  template <class T>
  std::vector<T> read(size_t count) const {
    std::vector<T> out(count);
    glBindBuffer(GL_COPY_READ_BUFFER, id_);
    glGetBufferSubData(GL_COPY_READ_BUFFER, 0, static_cast<GLsizeiptr>(count * sizeof(T)), out.data());
    return out;
  }

 private:
  GLuint id_ = 0;
  size_t bytes_ = 0;
};

class VertexArray {
 public:
  VertexArray() { glGenVertexArrays(1, &id_); }
  ~VertexArray() {
    if (id_) glDeleteVertexArrays(1, &id_);
  }
  VertexArray(VertexArray&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  VertexArray& operator=(VertexArray&& o) noexcept {
    if (this != &o) {
      if (id_) glDeleteVertexArrays(1, &id_);
      id_ = std::exchange(o.id_, 0);
    }
    return *this;
  }
  VertexArray(const VertexArray&) = delete;
  VertexArray& operator=(const VertexArray&) = delete;
  GLuint id() const { return id_; }
  void bind() const { glBindVertexArray(id_); }

 private:
  GLuint id_ = 0;
};

// Runs the bound program's vertex shader once per point of `vao` (count points) with the rasterizer
// off, capturing its outputs into `out` by transform feedback (the skin and interval-slice passes).
inline void capture_points(const VertexArray& vao, const Buffer& out, int count) {
  vao.bind();
  glEnable(GL_RASTERIZER_DISCARD);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, out.id());
  glBeginTransformFeedback(GL_POINTS);
  glDrawArrays(GL_POINTS, 0, count);
  glEndTransformFeedback();
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
  glDisable(GL_RASTERIZER_DISCARD);
  glBindVertexArray(0);
}

// Points the bound VAO's attributes at the bound GL_ARRAY_BUFFER of IntervalVertex records, at the
// locations shaders/surface.vert.glsl (INTERVAL) reads; location 2 (per-vertex data) is left alone.
inline void interval_vertex_attributes() {
  const GLsizei stride = sizeof(IntervalVertex);
  auto attrib = [&](GLuint loc, GLint size, size_t offset) {
    glEnableVertexAttribArray(loc);
    glVertexAttribPointer(loc, size, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(offset));
  };
  attrib(0, 3, offsetof(IntervalVertex, up));
  attrib(1, 3, offsetof(IntervalVertex, n_up));
  attrib(3, 3, offsetof(IntervalVertex, down));
  attrib(4, 3, offsetof(IntervalVertex, n_down));
  attrib(5, 2, offsetof(IntervalVertex, mu));
}

class Texture {
 public:
  Texture() { glGenTextures(1, &id_); }
  ~Texture() {
    if (id_) glDeleteTextures(1, &id_);
  }
  Texture(Texture&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  Texture& operator=(Texture&& o) noexcept {
    if (this != &o) {
      if (id_) glDeleteTextures(1, &id_);
      id_ = std::exchange(o.id_, 0);
    }
    return *this;
  }
  Texture(const Texture&) = delete;
  Texture& operator=(const Texture&) = delete;
  GLuint id() const { return id_; }

 private:
  GLuint id_ = 0;
};

// Counts primitives of a pass: written to transform feedback (default), or generated
// (GL_PRIMITIVES_GENERATED, which also counts those that overflow the feedback buffer).
class PrimitivesQuery {
 public:
  explicit PrimitivesQuery(GLenum target = GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN) : target_(target) {
    glGenQueries(1, &id_);
  }
  ~PrimitivesQuery() {
    if (id_) glDeleteQueries(1, &id_);
  }
  PrimitivesQuery(const PrimitivesQuery&) = delete;
  PrimitivesQuery& operator=(const PrimitivesQuery&) = delete;
  void begin() { glBeginQuery(target_, id_); }
  void end() { glEndQuery(target_); }
  GLuint result() const {
    GLuint n = 0;
    glGetQueryObjectuiv(id_, GL_QUERY_RESULT, &n);
    return n;
  }

 private:
  GLenum target_;
  GLuint id_ = 0;
};

}  // namespace dfm::gl
