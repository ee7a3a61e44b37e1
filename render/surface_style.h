#pragma once
// How the surface pass shades (render/surface_pass.h): plain data with no GL, so the viewport's colour
// choices (app/editor/scene_view.h) are testable without a context.
#include <Eigen/Core>

namespace dfm::gl {

enum class SurfaceColorMode { Shaded = 0, Scalar = 1, VertexColor = 2 };

struct SurfaceStyle {
  Eigen::Vector3f base_color{0.50f, 0.40f, 0.31f};  // linear RGB: warm clay
  Eigen::Vector3f back_color{0.55f, 0.12f, 0.10f};
  Eigen::Vector3f wire_color{0.08f, 0.08f, 0.09f};
  bool wireframe = false;
  bool flat = false;
  // Skip back faces: only for a closed surface oriented outward (is_closed_outward), whose back faces
  // the front ones hide; software GL (llvmpipe) then rasterizes about half the triangles.
  bool cull_back_faces = false;
  SurfaceColorMode mode = SurfaceColorMode::Shaded;
  float isolines = 10.0f;  // intervals over [0,1] for the scalar map; 0 = none
};

}  // namespace dfm::gl
