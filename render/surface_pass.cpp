#include "render/surface_pass.h"

#include <cstddef>
#include <string>
#include <vector>

#include "core/view/colormap.h"

namespace dfm::gl {

Eigen::MatrixXd vertex_normals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(V.rows(), 3);
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);  // length = 2 * area: area weighting
    for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n.transpose();
  }
  for (int i = 0; i < N.rows(); ++i) {
    const double len = N.row(i).norm();
    if (len > 0)
      N.row(i) /= len;
    else
      N.row(i) << 0, 0, 1;
  }
  return N;
}

std::vector<PosNormal> interleave_pos_normal(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                             const Eigen::MatrixXd& N_in) {
  const Eigen::MatrixXd N = N_in.rows() == V.rows() ? N_in : vertex_normals(V, F);
  std::vector<PosNormal> out(V.rows());
  for (int i = 0; i < V.rows(); ++i)
    for (int k = 0; k < 3; ++k) {
      out[i].position[k] = static_cast<float>(V(i, k));
      out[i].normal[k] = static_cast<float>(N(i, k));
    }
  return out;
}

void to_gl(const Eigen::Matrix4d& m, float out[16]) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out[c * 4 + r] = static_cast<float>(m(r, c));
}

namespace {

std::vector<std::string> with_turbo(std::vector<std::string> defines) {
  for (std::string& d : view::turbo_shader_defines()) defines.push_back(std::move(d));
  return defines;
}

}  // namespace

SurfacePass::SurfacePass()
    : shaded_(ProgramDesc{"surface.vert.glsl", "", "surface.frag.glsl", with_turbo({}), {}}),
      wireframe_(ProgramDesc{"surface.vert.glsl", "surface.geom.glsl", "surface.frag.glsl", with_turbo({"WIREFRAME"}), {}}),
      interval_shaded_(ProgramDesc{"surface.vert.glsl", "", "surface.frag.glsl", with_turbo({"INTERVAL"}), {}}),
      interval_wireframe_(ProgramDesc{"surface.vert.glsl", "surface.geom.glsl", "surface.frag.glsl",
                                      with_turbo({"WIREFRAME", "INTERVAL"}), {}}) {}

void SurfacePass::set_interval_geometry(GLuint records, int vertex_count, GLuint ibo, int index_count, float dt) {
  vao_.bind();
  glBindBuffer(GL_ARRAY_BUFFER, records);
  interval_vertex_attributes();
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);  // recorded in the VAO
  glBindVertexArray(0);
  vertex_count_ = vertex_count;
  index_count_ = ibo ? index_count : 0;
  indexed_ = ibo != 0;
  interval_ = true;
  dt_ = dt;
}

void SurfacePass::set_geometry(GLuint vbo, int vertex_count, GLuint ibo, int index_count) {
  vao_.bind();
  for (GLuint loc : {3u, 4u, 5u}) glDisableVertexAttribArray(loc);  // interval records' extra attributes
  interval_ = false;
  glBindBuffer(GL_ARRAY_BUFFER, vbo);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(PosNormal),
                        reinterpret_cast<void*>(offsetof(PosNormal, position)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(PosNormal),
                        reinterpret_cast<void*>(offsetof(PosNormal, normal)));
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);  // recorded in the VAO
  glBindVertexArray(0);
  vertex_count_ = vertex_count;
  index_count_ = ibo ? index_count : 0;
  indexed_ = ibo != 0;
}

void SurfacePass::set_vertex_data(const std::vector<Eigen::Vector4f>& data) {
  data_count_ = static_cast<int>(data.size());
  vao_.bind();
  if (data.empty()) {
    glDisableVertexAttribArray(2);
  } else {
    data_.upload(GL_ARRAY_BUFFER, data.data(), data.size() * sizeof(Eigen::Vector4f), GL_DYNAMIC_DRAW);
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, sizeof(Eigen::Vector4f), nullptr);
  }
  glBindVertexArray(0);
}

void SurfacePass::upload_mesh(const TriMesh& mesh) {
  const std::vector<PosNormal> v = interleave_pos_normal(mesh.V, mesh.F, mesh.N);
  std::vector<std::uint32_t> idx(mesh.F.size());
  for (int f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) idx[3 * f + k] = static_cast<std::uint32_t>(mesh.F(f, k));
  own_vertices_.upload(GL_ARRAY_BUFFER, v);
  vao_.bind();  // the element binding is VAO state: bind the VAO before uploading indices
  own_indices_.upload(GL_ELEMENT_ARRAY_BUFFER, idx);
  glBindVertexArray(0);
  set_geometry(own_vertices_.id(), static_cast<int>(v.size()), own_indices_.id(), static_cast<int>(idx.size()));
}

void SurfacePass::draw(const view::Camera& cam, const SurfaceStyle& style) {
  const int count = indexed_ ? index_count_ : vertex_count_;
  if (count <= 0) return;
  const Program& prog = interval_ ? (style.wireframe ? interval_wireframe_ : interval_shaded_)
                                  : (style.wireframe ? wireframe_ : shaded_);
  prog.use();
  if (interval_) glUniform1f(prog.uniform("u_dt"), dt_);
  float m[16];
  to_gl(view::view_matrix(cam), m);
  glUniformMatrix4fv(prog.uniform("u_view"), 1, GL_FALSE, m);
  to_gl(view::projection_matrix(cam), m);
  glUniformMatrix4fv(prog.uniform("u_proj"), 1, GL_FALSE, m);
  glUniform2f(prog.uniform("u_viewport"), static_cast<float>(cam.width), static_cast<float>(cam.height));
  glUniform3fv(prog.uniform("u_base_color"), 1, style.base_color.data());
  glUniform3fv(prog.uniform("u_back_color"), 1, style.back_color.data());
  glUniform3fv(prog.uniform("u_wire_color"), 1, style.wire_color.data());
  const bool has_data = data_count_ > 0 && data_count_ >= vertex_count_;
  const SurfaceColorMode mode = has_data ? style.mode : SurfaceColorMode::Shaded;
  glUniform1i(prog.uniform("u_color_mode"), static_cast<int>(mode));
  glUniform1f(prog.uniform("u_isolines"), style.isolines);
  glUniform1i(prog.uniform("u_flat"), style.flat ? 1 : 0);

  vao_.bind();
  if (has_data) {
    glEnableVertexAttribArray(2);
  } else {  // never read a stale, shorter data buffer
    glDisableVertexAttribArray(2);
    glVertexAttrib4f(2, 0.f, 0.f, 0.f, 1.f);
  }
  glEnable(GL_DEPTH_TEST);
  if (style.cull_back_faces) {
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
  } else {
    glDisable(GL_CULL_FACE);  // open meshes show their back faces
  }
  if (indexed_)
    glDrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, nullptr);
  else
    glDrawArrays(GL_TRIANGLES, 0, count);
  glBindVertexArray(0);
}

}  // namespace dfm::gl
