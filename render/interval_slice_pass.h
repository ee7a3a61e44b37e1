#pragma once
// Playback of an animation manifold at the cost of posing: one time interval's slice topology
// (core/anim/interval_slice.h: per slice vertex the manifold edge it lies on, and welded triangles)
// is uploaded once, as IntervalVertex records (render/interval_records.h: both endpoints' positions
// and 3D slice normals, and the interpolation parameter as a linear function of t, in double at
// upload, so float rounding of the times does not matter: a transition's edges can be very short in
// time and long in space), with the interval's index buffer. Each frame the surface pass draws them straight away: its vertex shader
// (shaders/surface.vert.glsl, INTERVAL) interpolates every slice vertex to time t, so a frame costs no
// pass of its own. read_back runs that same shader by transform feedback. Equals the CPU slicer
// (slice_manifold) at every t inside the open interval, up to float rounding. Needs a current GL
// context for its whole life.
#include <vector>

#include <Eigen/Core>

#include "core/anim/interval_slice.h"
#include "core/anim/manifold.h"
#include "render/gl_buffer.h"
#include "render/gl_program.h"
#include "render/interval_records.h"
#include "render/vertex_format.h"

namespace dfm::gl {

class IntervalSlicePass {
 public:
  IntervalSlicePass();  // compiles the read-back program; throws dfm::Error on a driver failure

  // Uploads the interval's vertex records (from m and its unit 4D vertex normals) and triangles.
  void upload(const IntervalSlice& interval, const AnimationManifold& m, const Eigen::MatrixXd& vertex_normals4);
  // The same from records prepared beforehand (interval_records; e.g. on a worker thread).
  void upload(const IntervalSlice& interval, const IntervalRecords& records);
  // Sets the time the records are drawn at (t_lo < t < t_hi, or an end: the limit, see
  // core/anim/interval_slice.h); throws dfm::Error outside.
  void evaluate(double t);

  bool contains(double t) const { return t_lo_ < t && t < t_hi_; }
  bool reaches(double t) const { return t_lo_ <= t && t <= t_hi_; }
  double t_lo() const { return t_lo_; }
  double t_hi() const { return t_hi_; }
  GLuint record_buffer() const { return records_.id(); }  // num_vertices() IntervalVertex
  GLuint index_buffer() const { return indices_.id(); }    // 3 uint32 per triangle
  float dt() const { return dt_; }                         // t - t_lo of the last evaluate
  int num_vertices() const { return num_vertices_; }
  int num_triangles() const { return static_cast<int>(F_.rows()); }
  int index_count() const { return 3 * num_triangles(); }
  const Eigen::MatrixXi& faces() const { return F_; }
  // The vertices at the last evaluate's time, as the surface pass draws them (welded, in the
  // interval's vertex order).
  std::vector<PosNormal> read_back() const;

 private:
  Program capture_;
  VertexArray vao_;
  Buffer records_, indices_;
  mutable Buffer out_;
  Eigen::MatrixXi F_;
  int num_vertices_ = 0;
  double t_lo_ = 0, t_hi_ = 0;
  float dt_ = 0;
};

}  // namespace dfm::gl
