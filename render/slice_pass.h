#pragma once
// GPU slicing of an animation manifold (OpenGL 3.3 core): slice.geom.glsl takes each tetrahedron as
// lines_adjacency and emits 0-2 triangles, captured by transform feedback into a buffer of PosNormal
// (3 vertices per triangle, unwelded) that the editor draws directly and tests read back. Normals are
// the smooth ones of the CPU slicer: per-vertex 4D normals (core/anim/manifold_normals.h) uploaded with
// the positions, interpolated along the cut edge with the position's mu. For t only the tetrahedra of the active slab(s) are drawn.
// Same case table, tie rule and winding as the CPU slicer (core/anim/slice.h). Positions are floats
// on the GPU. Needs a current GL context for its whole life.
#include <vector>

#include "core/anim/manifold.h"
#include "core/anim/slice.h"
#include "render/gl_buffer.h"
#include "render/gl_program.h"
#include "render/vertex_format.h"

namespace dfm::gl {

class SlicePass {
 public:
  SlicePass();  // compiles the program; throws dfm::Error on a driver failure

  // Uploads positions and unit 4D vertex normals (as floats) and tetrahedra; keeps the layer times and
  // slab offsets. vertex_normals4: manifold_vertex_normals(m) when the caller has it, else computed.
  void upload(const AnimationManifold& m, const Eigen::MatrixXd* vertex_normals4 = nullptr);

  // New positions and normals for the last upload's tetrahedra and times (a space-time drag frame
  // moves vertices in x, y, z only): no validation, no index upload. The caller keeps T and every t as
  // they were; throws dfm::Error when the vertex count or the normals' size differs.
  void upload_vertices(const AnimationManifold& m, const Eigen::MatrixXd& vertex_normals4);

  // Slices into output(); returns the triangle count. Grows the output buffer when needed.
  int slice(SliceAxis axis, double value);

  const Buffer& output() const { return out_; }
  int triangle_count() const { return triangles_; }
  // The last slice's vertices, 3 per triangle.
  std::vector<PosNormal> read_back() const;
  // Tetrahedra the last slice drew (the slab range for t, all for x, y, z).
  long long last_tets_drawn() const { return last_tets_; }

 private:
  Program program_;
  VertexArray vao_;
  Buffer positions_, normals_, indices_, out_;
  size_t capacity_ = 0;  // triangles out_ can hold
  AnimationManifold meta_;  // times and slab offsets only (no vertices or tetrahedra)
  int num_tets_ = 0;
  double lowest_[4] = {0, 0, 0, 0};
  int num_vertices_ = 0;
  int triangles_ = 0;
  long long last_tets_ = 0;
};

}  // namespace dfm::gl
