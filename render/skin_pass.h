#pragma once
// GPU skinning: the mesh's rest positions and normals are uploaded once as vertex attributes, and
// every nonzero influence of the binding (all weights, or the k kept by make_skin_binding) once in
// compressed sparse rows (core/skin/influences.h: SparseInfluences) held in texture buffers: the row
// offsets (#V + 1), the (handle, weight) pairs and the STBS endpoint weights, so a vertex skins with
// as many influences as the bind gave it. Each pose uploads one record per handle into another
// texture buffer (so there is no small uniform limit on the handle count); the vertex shader
// (shaders/skin.vert.glsl) skins positions and normals by LBS, DQS or STBS and transform feedback
// writes them into a PosNormal buffer that the surface pass draws and that can be read back, so a
// saved mesh is exactly what was on screen.
// Needs a current OpenGL 3.3 context (gl_context.h) for its whole life.
#include <map>
#include <memory>
#include <vector>

#include "core/rig/pose.h"
#include "core/skin/skin.h"
#include "render/gl_buffer.h"
#include "render/gl_program.h"
#include "render/vertex_format.h"

namespace dfm::gl {

class SkinPass {
 public:
  // Any number of influences per vertex (zero weights are dropped). Rest normals: binding.N, or zero
  // normals when it is empty. Throws dfm::Error on bad sizes, or when the sparse rows exceed the
  // driver's texture buffer.
  explicit SkinPass(const SkinBinding& binding);

  // One transform per handle (the additional ones last, SkinBinding::additional); stbs: per-handle
  // records (stbs_handles; per rig handle will do), empty = none active.
  // Throws dfm::Error if the pose has fewer handles than the influences name, or too many for the
  // driver's texture buffer.
  void set_pose(const Pose& pose, const std::vector<StbsHandle>& stbs = {});
  // Skins every vertex into output_buffer() (a transform feedback pass, rasterizer off).
  void run(SkinMethod method);

  GLuint output_buffer() const { return output_.id(); }  // #V PosNormal
  int num_vertices() const { return num_vertices_; }
  int num_entries() const { return num_entries_; }  // nonzero influences over all vertices
  int max_influences() const { return max_row_; }    // the most in one vertex
  int num_handles() const { return num_handles_; }
  // The last run's output, read back to the CPU.
  std::vector<PosNormal> read_back() const;
  SkinResult read_back_result() const;

 private:
  const Program& program(SkinMethod method);

  int num_vertices_ = 0, num_entries_ = 0, max_row_ = 0, num_handles_ = 0, max_handle_ = -1;
  int first_additional_ = 0;  // SkinBinding::additional: handles from here on skin linearly
  VertexArray vao_;
  Buffer rest_, output_, handle_data_, offsets_, pairs_, endpoints_;
  Texture handle_texture_, offsets_texture_, pairs_texture_, endpoints_texture_;
  std::map<SkinMethod, Program> programs_;
};

}  // namespace dfm::gl
