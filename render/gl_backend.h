#pragma once
// The viewport's RenderBackend (render/backend.h) on OpenGL 3.3: the surface and overlay passes, and
// deformers wrapping the skin, slice and interval-slice passes. Needs a current context for its whole
// life, and so does everything it makes.
#include <memory>
#include <vector>

#include "render/backend.h"
#include "render/overlay_pass.h"
#include "render/surface_pass.h"

namespace dfm::gl {

class GlBackend final : public RenderBackend {
 public:
  GlBackend();  // compiles the surface and overlay programs; throws dfm::Error on a driver failure

  std::unique_ptr<SkinDeformer> make_skin(const SkinBinding& binding, const Eigen::MatrixXi& F) override;
  std::unique_ptr<ManifoldSlicer> make_slicer() override;
  std::unique_ptr<IntervalSlicer> make_interval_slicer() override;

  void show_mesh(const TriMesh& mesh) override { surface_.upload_mesh(mesh); }
  void show_geometry(const GeometryRef& g) override;
  void set_surface_data(const std::vector<Eigen::Vector4f>& data) override { surface_.set_vertex_data(data); }
  void draw_surface(const view::Camera& cam, const SurfaceStyle& style) override { surface_.draw(cam, style); }
  void draw_lines(const view::Camera& cam, const std::vector<OverlayVertex>& pairs, float width,
                  bool depth_test) override {
    overlay_.draw_lines(cam, pairs, width, depth_test);
  }
  void draw_points(const view::Camera& cam, const std::vector<OverlayVertex>& points, float size_px,
                   bool depth_test) override {
    overlay_.draw_points(cam, points, size_px, depth_test);
  }

 private:
  SurfacePass surface_;
  OverlayPass overlay_;
};

}  // namespace dfm::gl
