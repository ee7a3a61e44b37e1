// The GL foundation: a 3.3 core context, embedded shaders, transform feedback readback.
#include <catch2/catch.hpp>

#include "core/util/error.h"
#include "render/gl_buffer.h"
#include "render/gl_context.h"
#include "render/gl_program.h"
#include "shaders/embedded_shaders.h"

using namespace dfm;

TEST_CASE("context is OpenGL 3.3 core or later", "[gl]") {
  gl::Context ctx;
  INFO(ctx.renderer());
  REQUIRE(epoxy_gl_version() >= 33);
}

TEST_CASE("transform feedback returns exactly what the shader computed", "[gl]") {
  gl::Context ctx;
  gl::Program prog({"feedback_scale.vert.glsl", "", "", {}, {"scaled"}});
  std::vector<float> in = {1, 2, 3, -4, 5.5f, 0, 1e-3f, 7, -8};
  gl::VertexArray vao;
  vao.bind();
  gl::Buffer src, dst;
  src.upload(GL_ARRAY_BUFFER, in);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  dst.upload(GL_TRANSFORM_FEEDBACK_BUFFER, nullptr, in.size() * sizeof(float), GL_STREAM_READ);
  prog.use();
  glUniform1f(prog.uniform("scale"), 2.0f);
  glEnable(GL_RASTERIZER_DISCARD);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, dst.id());
  gl::PrimitivesQuery q;
  q.begin();
  glBeginTransformFeedback(GL_POINTS);
  glDrawArrays(GL_POINTS, 0, 3);
  glEndTransformFeedback();
  q.end();
  glDisable(GL_RASTERIZER_DISCARD);
  gl::check_error("feedback draw");
  REQUIRE(q.result() == 3);
  auto out = dst.read<float>(in.size());
  for (size_t i = 0; i < in.size(); ++i) REQUIRE(out[i] == 2.0f * in[i]);
}

TEST_CASE("unknown embedded shader names are errors, not crashes", "[gl]") {
  REQUIRE_THROWS(shader_source("no-such-shader.glsl"));
  gl::Context ctx;
  REQUIRE_THROWS_WITH(gl::Program({"no-such-shader.glsl"}), Catch::Contains("no-such-shader.glsl"));
}
