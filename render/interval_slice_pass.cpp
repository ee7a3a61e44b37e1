#include "render/interval_slice_pass.h"

#include <cstddef>
#include <cstdint>
#include <string>

#include "core/util/error.h"

namespace dfm::gl {

IntervalSlicePass::IntervalSlicePass()
    : capture_(ProgramDesc{"surface.vert.glsl", "", "", {"INTERVAL", "CAPTURE"}, {"out_position", "out_normal"}}) {
  check_error("interval slice pass setup");
}

void IntervalSlicePass::upload(const IntervalSlice& s, const AnimationManifold& m,
                               const Eigen::MatrixXd& vertex_normals4) {
  upload(s, interval_records(s, m, vertex_normals4));
}

void IntervalSlicePass::upload(const IntervalSlice& s, const IntervalRecords& r) {
  if (static_cast<int>(r.vertices.size()) != s.num_vertices() || r.indices.size() != static_cast<size_t>(s.F.size()))
    throw Error("interval slice pass: records do not match the interval's topology");
  vao_.bind();
  records_.upload(GL_ARRAY_BUFFER, r.vertices);
  interval_vertex_attributes();
  glBindVertexArray(0);
  // GL_ARRAY_BUFFER: binding GL_ELEMENT_ARRAY_BUFFER would change whatever VAO is bound.
  indices_.upload(GL_ARRAY_BUFFER, r.indices);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  F_ = s.F;
  num_vertices_ = s.num_vertices();
  t_lo_ = s.t_lo;
  t_hi_ = s.t_hi;
  dt_ = 0;
  check_error("interval slice pass upload");
}

void IntervalSlicePass::evaluate(double t) {
  if (!reaches(t))
    throw Error("interval slice pass: t = " + std::to_string(t) + " is outside [" + std::to_string(t_lo_) + ", " +
                std::to_string(t_hi_) + "]");
  dt_ = static_cast<float>(t - t_lo_);
}

std::vector<PosNormal> IntervalSlicePass::read_back() const {
  if (num_vertices_ == 0) return {};
  out_.upload(GL_TRANSFORM_FEEDBACK_BUFFER, nullptr, static_cast<size_t>(num_vertices_) * sizeof(PosNormal),
              GL_DYNAMIC_COPY);
  glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, 0);
  capture_.use();
  glUniform1f(capture_.uniform("u_dt"), dt_);
  capture_points(vao_, out_, num_vertices_);
  check_error("interval slice pass read-back");
  return out_.read<PosNormal>(static_cast<size_t>(num_vertices_));
}

}  // namespace dfm::gl
