#include "render/slice_pass.h"

#include <algorithm>
#include <string>

#include "core/anim/manifold_normals.h"
#include "core/anim/slice_table.h"
#include "core/util/error.h"

namespace dfm::gl {

SlicePass::SlicePass()
    : program_(ProgramDesc{"slice.vert.glsl", "slice.geom.glsl", "", {}, {"out_position", "out_normal"}}) {
  // The derived case table, packed: count in bits 0-1, then 3 bits per corner's edge index.
  const auto& table = slice_table();
  GLint cases[16];
  for (int m = 0; m < 16; ++m) {
    int code = table[m].num_triangles;
    for (int t = 0; t < table[m].num_triangles; ++t)
      for (int j = 0; j < 3; ++j) code |= table[m].triangles[t][j] << (2 + 3 * (3 * t + j));
    cases[m] = code;
  }
  GLint edges[12];
  for (int e = 0; e < 6; ++e) {
    edges[2 * e] = kSliceEdges[e][0];
    edges[2 * e + 1] = kSliceEdges[e][1];
  }
  program_.use();
  glUniform1iv(program_.uniform("u_cases"), 16, cases);
  glUniform2iv(program_.uniform("u_edges"), 6, edges);
  check_error("slice pass setup");
}

namespace {

// Positions (row-major x y z t) and 4D normals as the vertex attributes' floats.
void float_vertices(const AnimationManifold& m, const Eigen::MatrixXd& normals4, std::vector<float>& pos,
                    std::vector<float>& nrm) {
  pos.resize(m.V.size());
  nrm.resize(m.V.size());
  for (Eigen::Index i = 0; i < m.V.size(); ++i) pos[i] = static_cast<float>(m.V.data()[i]);
  for (int v = 0; v < m.num_vertices(); ++v)
    for (int d = 0; d < 4; ++d) nrm[4 * v + d] = static_cast<float>(normals4(v, d));
}

}  // namespace

void SlicePass::upload(const AnimationManifold& m, const Eigen::MatrixXd* vertex_normals4) {
  validate_manifold(m, "GPU slice manifold");
  Eigen::MatrixXd computed;
  if (!vertex_normals4) {
    computed = manifold_vertex_normals(m);
    vertex_normals4 = &computed;
  }
  if (vertex_normals4->rows() != m.num_vertices() || vertex_normals4->cols() != 4)
    throw Error("GPU slice: vertex normals must be " + std::to_string(m.num_vertices()) + " x 4");
  std::vector<float> pos, nrm;
  float_vertices(m, *vertex_normals4, pos, nrm);
  vao_.bind();
  positions_.upload(GL_ARRAY_BUFFER, pos);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 4 * sizeof(float), nullptr);
  normals_.upload(GL_ARRAY_BUFFER, nrm);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, 4 * sizeof(float), nullptr);
  // T is row-major int32: exactly the index layout lines_adjacency wants (4 per primitive).
  indices_.upload(GL_ELEMENT_ARRAY_BUFFER, m.T.data(), static_cast<size_t>(m.T.size()) * sizeof(int));
  glBindVertexArray(0);
  meta_ = AnimationManifold{};
  meta_.times = m.times;
  meta_.slab_offsets = m.slab_offsets;
  num_tets_ = m.num_tets();
  num_vertices_ = m.num_vertices();
  for (int d = 0; d < 4; ++d) lowest_[d] = m.num_vertices() ? m.V.col(d).minCoeff() : 0.0;
  lowest_[3] = m.times.front();
  triangles_ = 0;
  check_error("slice pass upload");
}

void SlicePass::upload_vertices(const AnimationManifold& m, const Eigen::MatrixXd& vertex_normals4) {
  if (m.num_vertices() != num_vertices_ || vertex_normals4.rows() != m.num_vertices() || vertex_normals4.cols() != 4)
    throw Error("GPU slice: new vertices for " + std::to_string(num_vertices_) + " uploaded ones, got " +
                std::to_string(m.num_vertices()) + " (normals " + std::to_string(vertex_normals4.rows()) + " x " +
                std::to_string(vertex_normals4.cols()) + ")");
  std::vector<float> pos, nrm;
  float_vertices(m, vertex_normals4, pos, nrm);
  // Same sizes: the buffers are rewritten in place.
  positions_.update(GL_ARRAY_BUFFER, pos.data(), pos.size() * sizeof(float));
  normals_.update(GL_ARRAY_BUFFER, nrm.data(), nrm.size() * sizeof(float));
  for (int d = 0; d < 3; ++d) lowest_[d] = m.num_vertices() ? m.V.col(d).minCoeff() : 0.0;
  triangles_ = 0;
  check_error("slice pass vertex upload");
}

int SlicePass::slice(SliceAxis axis, double value) {
  const int a = static_cast<int>(axis);
  // The GPU compares in float: a time within float rounding of a layer's time IS that layer there, while
  // the slab range is chosen in double. Unsnapped, t = 1.6000000000000003 picks only the slab starting
  // at the layer 1.6, whose vertices all compare >= 1.6f: an empty slice. Snapped, both slabs are drawn.
  if (axis == SliceAxis::T)
    for (double tk : meta_.times)
      if (static_cast<float>(tk) == static_cast<float>(value)) value = tk;
  std::pair<int, int> range = axis == SliceAxis::T ? slice_tet_range(meta_, axis, value) : std::pair<int, int>{0, num_tets_};
  last_tets_ = range.second - range.first;
  triangles_ = 0;
  if (range.second <= range.first) return 0;

  program_.use();
  glUniform1i(program_.uniform("u_axis"), a);
  glUniform1f(program_.uniform("u_value"), static_cast<float>(value));
  glUniform1i(program_.uniform("u_on_plane_above"), value > lowest_[a]);
  glUniform1i(program_.uniform("u_flip"), slice_flips_winding(a));
  vao_.bind();
  if (capacity_ == 0) {
    capacity_ = 1 << 16;
    out_.upload(GL_TRANSFORM_FEEDBACK_BUFFER, nullptr, capacity_ * 3 * sizeof(PosNormal), GL_DYNAMIC_COPY);
  }
  glEnable(GL_RASTERIZER_DISCARD);
  for (int attempt = 0; attempt < 2; ++attempt) {
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, out_.id());
    PrimitivesQuery generated(GL_PRIMITIVES_GENERATED);
    generated.begin();
    glBeginTransformFeedback(GL_TRIANGLES);
    glDrawElements(GL_LINES_ADJACENCY, 4 * (range.second - range.first), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(static_cast<size_t>(range.first) * 4 * sizeof(GLuint)));
    glEndTransformFeedback();
    generated.end();
    const size_t n = generated.result();
    if (n <= capacity_) {
      triangles_ = static_cast<int>(n);
      break;
    }
    // Overflow: grow with headroom and slice again (rare after the first frames).
    capacity_ = n + n / 4;
    out_.upload(GL_TRANSFORM_FEEDBACK_BUFFER, nullptr, capacity_ * 3 * sizeof(PosNormal), GL_DYNAMIC_COPY);
  }
  glDisable(GL_RASTERIZER_DISCARD);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
  glBindVertexArray(0);
  check_error("slice pass draw");
  return triangles_;
}

std::vector<PosNormal> SlicePass::read_back() const { return out_.read<PosNormal>(static_cast<size_t>(triangles_) * 3); }

}  // namespace dfm::gl
