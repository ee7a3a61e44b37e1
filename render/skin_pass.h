#pragma once
// GPU skinning: the mesh's rest positions, normals and k = 4 or 8 influences (handle indices,
// weights, STBS endpoint weights) are uploaded once as vertex attributes; each pose uploads one
// record per handle into a texture buffer (so there is no small uniform limit on the handle count);
// the vertex shader (shaders/skin.vert.glsl) skins positions and normals by LBS, DQS or STBS and
// transform feedback writes them into a PosNormal buffer that the surface pass draws and that can be
// read back, so a saved mesh is exactly what was on screen.
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
  // binding.influences.k() must be <= 8 (padded to 4 or 8 here). Rest normals: binding.N, or zero
  // normals when it is empty. Throws dfm::Error on bad sizes.
  explicit SkinPass(const SkinBinding& binding);

  // One transform per handle; stbs: per-handle records (stbs_handles), empty = none active.
  // Throws dfm::Error if the pose has fewer handles than the influences name, or too many for the
  // driver's texture buffer.
  void set_pose(const Pose& pose, const std::vector<StbsHandle>& stbs = {});
  // Skins every vertex into output_buffer() (a transform feedback pass, rasterizer off).
  void run(SkinMethod method);

  GLuint output_buffer() const { return output_.id(); }  // #V PosNormal
  int num_vertices() const { return num_vertices_; }
  int k() const { return k_; }
  int num_handles() const { return num_handles_; }
  // The last run's output, read back to the CPU.
  std::vector<PosNormal> read_back() const;
  SkinResult read_back_result() const;

 private:
  const Program& program(SkinMethod method);

  int num_vertices_ = 0, k_ = 4, num_handles_ = 0, max_handle_ = -1;
  VertexArray vao_;
  Buffer rest_, handle_index_, weight_, endpoint_, output_, handle_data_;
  Texture handle_texture_;
  std::map<SkinMethod, Program> programs_;
};

}  // namespace dfm::gl
