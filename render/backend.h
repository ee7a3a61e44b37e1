#pragma once
// The seam between the editor's viewport (app/editor/scene_view.h) and the GPU: what the viewport asks
// for, with no GL type in sight, so its decisions (what to upload and when, which source the surface
// draws, colours, overlays) are tested headless against a recording mock (tests/mock_render_backend.h).
// render/gl_backend.h implements it with the OpenGL passes. Polyscope's engine / mock-engine split,
// at the level of passes rather than of GL objects.
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "core/anim/interval_slice.h"
#include "core/anim/manifold.h"
#include "core/anim/slice.h"
#include "core/mesh/mesh.h"
#include "core/rig/pose.h"
#include "core/skin/skin.h"
#include "core/view/camera.h"
#include "render/interval_records.h"
#include "render/overlay_geometry.h"
#include "render/surface_style.h"
#include "render/vertex_format.h"

namespace dfm::gl {

// Vertices a deformer wrote on the GPU, as the surface draws them: a PosNormal buffer and optional
// uint32 triangle indices (index_buffer 0: a triangle soup). Buffer names belong to the backend.
// With interval set, vertex_buffer holds IntervalVertex records drawn at time t_lo + interval_dt.
struct GeometryRef {
  unsigned vertex_buffer = 0;
  int vertex_count = 0;
  unsigned index_buffer = 0;
  int index_count = 0;
  bool interval = false;
  float interval_dt = 0;
};

// The posed surface of one skin binding (render/skin_pass.h).
class SkinDeformer {
 public:
  virtual ~SkinDeformer() = default;
  virtual void set_pose(const Pose& pose, const std::vector<StbsHandle>& stbs) = 0;
  virtual void run(SkinMethod method) = 0;
  virtual GeometryRef output() const = 0;                // indexed by the rest surface's triangles
  virtual std::vector<PosNormal> read_back() const = 0;  // the last run's vertices
};

// An animation manifold sliced along any axis by one pass over its tetrahedra (render/slice_pass.h).
class ManifoldSlicer {
 public:
  virtual ~ManifoldSlicer() = default;
  virtual void upload(const AnimationManifold& m, const Eigen::MatrixXd& vertex_normals4) = 0;
  // The last upload's tetrahedra and times with new positions and normals (SlicePass::upload_vertices).
  virtual void upload_vertices(const AnimationManifold& m, const Eigen::MatrixXd& vertex_normals4) = 0;
  virtual int slice(SliceAxis axis, double value) = 0;  // returns the triangles written
  virtual GeometryRef output() const = 0;               // a soup, 3 vertices per triangle
  virtual std::vector<PosNormal> read_back() const = 0;
};

// One time interval's slice topology, interpolated to any t inside it (render/interval_slice_pass.h).
class IntervalSlicer {
 public:
  virtual ~IntervalSlicer() = default;
  // prepared: interval_records(interval, m, vertex_normals4) made beforehand (a worker's), or null.
  virtual void upload(const IntervalSlice& interval, const AnimationManifold& m,
                      const Eigen::MatrixXd& vertex_normals4, const IntervalRecords* prepared) = 0;
  virtual void evaluate(double t) = 0;     // the time output() is drawn at
  virtual GeometryRef output() const = 0;  // welded interval records, indexed by faces()
  virtual const Eigen::MatrixXi& faces() const = 0;
  virtual std::vector<PosNormal> read_back() const = 0;
};

// One viewport's GPU: the displayed surface (render/surface_pass.h), the overlays
// (render/overlay_pass.h), and the deformers that feed the surface. What it makes must not outlive it.
class RenderBackend {
 public:
  virtual ~RenderBackend() = default;
  // F: the rest surface's triangles (the index buffer the skinned vertices are drawn with).
  virtual std::unique_ptr<SkinDeformer> make_skin(const SkinBinding& binding, const Eigen::MatrixXi& F) = 0;
  virtual std::unique_ptr<ManifoldSlicer> make_slicer() = 0;
  virtual std::unique_ptr<IntervalSlicer> make_interval_slicer() = 0;

  // The surface shows a static mesh (copied into the backend's own buffers) or a deformer's output.
  virtual void show_mesh(const TriMesh& mesh) = 0;
  virtual void show_geometry(const GeometryRef& geometry) = 0;
  // One vec4 per displayed vertex for the colour modes (surface_style.h); empty clears it.
  virtual void set_surface_data(const std::vector<Eigen::Vector4f>& data) = 0;
  virtual void draw_surface(const view::Camera& cam, const SurfaceStyle& style) = 0;
  // Pairs of vertices; width in pixels. depth_test=false draws on top of the surface (x-ray).
  virtual void draw_lines(const view::Camera& cam, const std::vector<OverlayVertex>& pairs, float width,
                          bool depth_test) = 0;
  virtual void draw_points(const view::Camera& cam, const std::vector<OverlayVertex>& points, float size_px,
                           bool depth_test) = 0;
};

}  // namespace dfm::gl
