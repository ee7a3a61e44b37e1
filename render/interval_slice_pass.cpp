#include "render/interval_slice_pass.h"

#include <cstddef>
#include <cstdint>
#include <string>

#include "core/anim/manifold_normals.h"
#include "core/anim/slice.h"
#include "core/util/error.h"

namespace dfm::gl {

IntervalSlicePass::IntervalSlicePass()
    : capture_(ProgramDesc{"surface.vert.glsl", "", "", {"INTERVAL", "CAPTURE"}, {"out_position", "out_normal"}}) {
  check_error("interval slice pass setup");
}

void IntervalSlicePass::upload(const IntervalSlice& s, const AnimationManifold& m,
                               const Eigen::MatrixXd& vertex_normals4) {
  if (vertex_normals4.rows() != m.num_vertices() || vertex_normals4.cols() != 4)
    throw Error("interval slice pass: vertex normals must be " + std::to_string(m.num_vertices()) + " x 4");
  const int nv = s.num_vertices();
  std::vector<IntervalVertex> rec(nv);
  for (int v = 0; v < nv; ++v) {
    const int up = s.edges[v][0], dn = s.edges[v][1];
    if (up < 0 || dn < 0 || up >= m.num_vertices() || dn >= m.num_vertices())
      throw Error("interval slice pass: edge vertex out of range");
    const Eigen::Vector3d nu = slice_normal3(vertex_normals4.row(up).transpose(), SliceAxis::T),
                          nd = slice_normal3(vertex_normals4.row(dn).transpose(), SliceAxis::T);
    for (int d = 0; d < 3; ++d) {
      rec[v].up[d] = static_cast<float>(m.V(up, d));
      rec[v].down[d] = static_cast<float>(m.V(dn, d));
      rec[v].n_up[d] = static_cast<float>(nu[d]);
      rec[v].n_down[d] = static_cast<float>(nd[d]);
    }
    const double span = m.V(up, 3) - m.V(dn, 3);  // > 0 (build_interval_slice's edges)
    if (!(span > 0)) throw Error("interval slice pass: an edge does not go forward in time");
    rec[v].mu[0] = static_cast<float>((m.V(up, 3) - s.t_lo) / span);
    rec[v].mu[1] = static_cast<float>(-1.0 / span);
  }
  std::vector<std::uint32_t> idx(static_cast<size_t>(s.F.size()));
  for (int f = 0; f < s.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      if (s.F(f, c) < 0 || s.F(f, c) >= nv) throw Error("interval slice pass: triangle index out of range");
      idx[3 * f + c] = static_cast<std::uint32_t>(s.F(f, c));
    }
  vao_.bind();
  records_.upload(GL_ARRAY_BUFFER, rec);
  interval_vertex_attributes();
  glBindVertexArray(0);
  // GL_ARRAY_BUFFER: binding GL_ELEMENT_ARRAY_BUFFER would change whatever VAO is bound.
  indices_.upload(GL_ARRAY_BUFFER, idx);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  F_ = s.F;
  num_vertices_ = nv;
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
