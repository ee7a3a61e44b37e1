#pragma once
// Playback of an animation manifold at the cost of posing: one time interval's slice topology
// (core/anim/interval_slice.h: per slice vertex the manifold edge it lies on, and welded triangles)
// is uploaded once, with both endpoints' positions and 3D slice normals per vertex and the
// interpolation parameter as a linear function of t (in double at upload, so float rounding of the
// times does not matter: a transition's edges can be very short in time and long in space); each frame
// shaders/interval_slice.vert.glsl interpolates every slice vertex to time t by transform feedback
// into a PosNormal buffer (like the skin pass), which the surface pass draws with the interval's
// index buffer. Equals the CPU slicer (slice_manifold) at every t inside the open interval, up to
// float rounding. Needs a current GL context for its whole life.
#include <vector>

#include <Eigen/Core>

#include "core/anim/interval_slice.h"
#include "core/anim/manifold.h"
#include "render/gl_buffer.h"
#include "render/gl_program.h"
#include "render/vertex_format.h"

namespace dfm::gl {

class IntervalSlicePass {
 public:
  IntervalSlicePass();  // compiles the program; throws dfm::Error on a driver failure

  // Uploads the interval's vertex records (from m and its unit 4D vertex normals) and triangles.
  void upload(const IntervalSlice& interval, const AnimationManifold& m, const Eigen::MatrixXd& vertex_normals4);
  // Writes the slice at time t (t_lo < t < t_hi) into output_buffer(); throws dfm::Error outside.
  void evaluate(double t);

  bool contains(double t) const { return t_lo_ < t && t < t_hi_; }
  double t_lo() const { return t_lo_; }
  double t_hi() const { return t_hi_; }
  GLuint output_buffer() const { return out_.id(); }    // num_vertices() PosNormal
  GLuint index_buffer() const { return indices_.id(); }  // 3 uint32 per triangle
  int num_vertices() const { return num_vertices_; }
  int num_triangles() const { return static_cast<int>(F_.rows()); }
  int index_count() const { return 3 * num_triangles(); }
  const Eigen::MatrixXi& faces() const { return F_; }
  // The last evaluate's vertices (welded, in the interval's vertex order).
  std::vector<PosNormal> read_back() const;

 private:
  Program program_;
  VertexArray vao_;
  Buffer records_, indices_, out_;
  Eigen::MatrixXi F_;
  int num_vertices_ = 0;
  double t_lo_ = 0, t_hi_ = 0;
};

}  // namespace dfm::gl
