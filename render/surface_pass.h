#pragma once
// Draws a PosNormal vertex buffer (indexed or a triangle soup) lit with two camera lights, back faces
// of open meshes in their own colour, an optional wireframe overlay, and either a scalar colour map
// with isolines (weights, masks) or per-vertex colours (the all-handles weight blend).
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/mesh/mesh.h"
#include "core/view/camera.h"
#include "render/gl_buffer.h"
#include "render/gl_program.h"
#include "render/surface_style.h"
#include "render/vertex_format.h"

namespace dfm::gl {

// Area-weighted vertex normals for display (zero-area faces ignored; isolated vertices get +z).
Eigen::MatrixXd vertex_normals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);
// Interleaves positions and normals (N empty -> vertex_normals(V, F)).
std::vector<PosNormal> interleave_pos_normal(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                             const Eigen::MatrixXd& N = {});

class SurfacePass {
 public:
  SurfacePass();
  // Where the vertices come from: a PosNormal buffer (owned elsewhere: skin or slice output, or
  // upload_mesh below) and an optional index buffer of uint32 triangles (0 -> draw as a soup).
  void set_geometry(GLuint pos_normal_buffer, int vertex_count, GLuint index_buffer, int index_count);
  // Or IntervalVertex records of a cached manifold interval (render/interval_slice_pass.h), drawn at
  // dt = t - t_lo: the vertex shader interpolates them (INTERVAL).
  void set_interval_geometry(GLuint records, int vertex_count, GLuint index_buffer, int index_count, float dt);
  // Per-vertex data for the colour modes (one vec4 per vertex, same order as the geometry). An empty
  // vector clears it.
  void set_vertex_data(const std::vector<Eigen::Vector4f>& data);
  // Convenience: uploads a static mesh into the pass's own buffers and uses them.
  void upload_mesh(const TriMesh& mesh);
  void draw(const view::Camera& cam, const SurfaceStyle& style);

  int vertex_count() const { return vertex_count_; }
  int index_count() const { return index_count_; }

 private:
  // Shaded only (vertex + fragment) and shaded with the single-pass wireframe (+ geometry shader):
  // the geometry stage costs a lot on software GL, so it runs only when the wireframe is on.
  // Each also for interval records (INTERVAL).
  Program shaded_, wireframe_, interval_shaded_, interval_wireframe_;
  VertexArray vao_;
  Buffer own_vertices_, own_indices_, data_;
  int vertex_count_ = 0, index_count_ = 0, data_count_ = 0;
  bool indexed_ = false;
  bool interval_ = false;
  float dt_ = 0;
};

// Column-major float copy for glUniformMatrix4fv.
void to_gl(const Eigen::Matrix4d& m, float out[16]);

}  // namespace dfm::gl
