#pragma once
// The GPU mirror of the document: the displayed surface (rest, posed, or the animation manifold's
// slice at the current time), weight colours, and the overlays (grid, handles, bones, cages, brush).
// sync() is cheap when nothing changed, so the editor calls it every frame. Everything it asks of the
// GPU goes through a gl::RenderBackend (render/backend.h): the OpenGL one in the editor, a recording
// mock in tests/test_scene_view.cpp, where this logic runs without a GL context.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/anim/key_alignment.h"
#include "core/anim/slice.h"
#include "core/scene/document.h"
#include "core/view/camera.h"
#include "render/backend.h"

namespace dfm::editor {

// What the Weights panel colours the surface by. Difference: how far the weights moved from those the
// last bind replaced (weight_difference.h): the selected handle's, or with none selected, the share of
// each vertex's weight that moved (total variation).
enum class WeightView { Off, Selected, AllHandles, Mask, Difference };

struct ViewSettings {
  bool wireframe = false;
  bool grid = true;
  bool handles = true;
  WeightView weight_view = WeightView::Off;
  SliceAxis slice_axis = SliceAxis::T;  // T: time slices; X, Y, Z: the sweep view along that axis
  double sweep_value = 0.5;   // fraction of the extent along the sweep axis
  // The Sculpt tool's heat map over a sculpt session's result: fixed 0, free region 0.55, handle 1.
  bool sculpt_colors = false;
};

// Per-handle display colour (distinct hues, golden-ratio spaced), linear RGB.
Eigen::Vector3f handle_color(int handle);
// Per-vertex blend of handle colours by weight (the "all handles" view).
std::vector<Eigen::Vector4f> blend_handle_colors(const Eigen::MatrixXd& W);

class SceneView {
 public:
  // Draws through `gpu`, which must outlive the view.
  explicit SceneView(gl::RenderBackend& gpu);
  ~SceneView();
  void sync(const Document& doc, const ViewSettings& s);
  void draw(const Document& doc, const view::Camera& cam, const ViewSettings& s);
  // Extra overlay lines for this frame only (brush circle, gizmo, bone being drawn).
  void add_overlay_lines(const std::vector<gl::OverlayVertex>& pairs, float width);
  void add_overlay_points(const std::vector<gl::OverlayVertex>& points, float size);

  // The displayed surface on the CPU (for picking and painting): rest or posed positions.
  // Posed vertices are read back from the GPU on first use after a change.
  const Eigen::MatrixXd& display_vertices();
  const Eigen::MatrixXi& display_faces();
  // Welded vertices (a general-pass slice is a triangle soup on the GPU: counted by the slice's weld).
  int display_vertex_count() const;
  int display_face_count() const { return display_faces_; }
  // The time slice on display came from the interval cache (an interpolation), not the general pass.
  bool slice_from_cache() const;
  int intervals_built() const;  // interval topologies built for the current manifold
  double interval_build_ms() const;  // ...and the time spent building them (CPU topology + upload)
  int vertex_time_count() const;  // distinct vertex times of the current manifold
  bool showing_slice() const { return showing_slice_; }
  // The pose the viewport shows: on a time slice the key poses interpolated at the document's time,
  // else the document's pose (the Transform panel reports this one).
  Pose shown_pose(const Document& doc) const;
  // Shows the current pose (skinned) instead of the manifold slice until the time changes, as a pose
  // edit after a scrub does.
  void show_pose();
  // Shows `mesh` instead of the document's frame (the Shape space panel's shape) until the next change
  // of the document, time or view settings, or clear_preview(). A sculpt session (Document::sculpt)
  // shows its result this way while it lasts.
  void show_preview(const TriMesh& mesh);
  void clear_preview();
  bool showing_preview() const { return showing_preview_; }
  bool display_is_rest() const { return display_is_rest_; }
  Eigen::AlignedBox3d surface_bounds() const { return bounds_; }
  // What "Frame all" fits: the surface's bounds and every handle and joint as displayed (handles such
  // as the default scene's ear points lie outside the surface); with neither, the grid drawn then.
  Eigen::AlignedBox3d framing_bounds() const;
  // Handle glyph positions as displayed (posed when posing), rows in handle order; joints separately.
  const Eigen::MatrixXd& handle_positions() const { return handle_pos_; }
  const Eigen::MatrixXd& joint_positions() const { return joint_pos_; }
  const std::string& last_error() const { return error_; }
  // How opaque the rig overlays are drawn (0: hidden): below 1 over a surface that is not the rigged
  // mesh (a transition's in-betweens, a mesh key of other triangles); rig_overlay_opacity, view_model.h.
  float overlay_opacity() const { return overlay_opacity_; }
  // The animation manifold is building on its worker thread (a transition), and what it is doing.
  bool manifold_building() const;
  // The placement of the transition whose interval holds the document's time (the picked pairs'
  // paths go by it: pair_position), null where that interval is no transition or has not been
  // prepared.
  const KeyPlacement* pair_placement(const Document& doc) const;
  std::string manifold_progress() const;

 private:
  void update_surface(const Document& doc, const ViewSettings& s);
  void show_slice(const Document& doc, const ViewSettings& s);
  struct Deformer;  // posing and slicing state (skin binding, manifold cache)
  static void grow_interval_cache(Deformer& d, const IntervalSlice& built);
  void update_skin(const Document& doc);
  void update_colors(const Document& doc, const ViewSettings& s);
  bool surface_closed(const Document& doc);
  void show_rest(const TriMesh& rest, bool closed);
  // The one rule for which pose is on screen (shown_pose with the axis being synced).
  Pose pose_on_screen(const Document& doc, SliceAxis axis) const;
  // scene_overlays.cpp: the rig's glyphs as displayed, and their overlay draw.
  void update_handles(const Document& doc, const ViewSettings& s);
  void draw_overlays(const Document& doc, const view::Camera& cam);

  gl::RenderBackend& gpu_;
  std::unique_ptr<Deformer> deformer_;
  Eigen::MatrixXd display_V_;
  Eigen::MatrixXi display_F_;
  bool display_is_rest_ = true;
  bool showing_slice_ = false;
  bool showing_animation_pose_ = false;  // the animation's pose skinned (a weight view on pose keys)
  bool showing_preview_ = false;
  bool display_closed_ = false;  // the displayed surface is closed and outward: cull its back faces
  mutable int display_count_ = 0;  // -1: a general-pass slice, counted when asked
  int display_faces_ = 0;
  SliceAxis general_axis_ = SliceAxis::T;
  double general_value_ = 0;
  float overlay_opacity_ = 1.0f;  // rig_overlay_opacity over the animation (view_model.h)
  // is_closed_outward of the document's surface, for the rest and posed display (cached: it sorts edges).
  struct ClosedCache {
    std::uint64_t revision = ~0ull;
    const void* faces = nullptr;
    Eigen::Index rows = -1;
    bool closed = false;
  } surface_closed_;
  Eigen::AlignedBox3d bounds_;
  Eigen::MatrixXd handle_pos_, joint_pos_;
  std::vector<gl::OverlayVertex> extra_lines_, extra_points_;
  std::vector<float> extra_line_widths_;
  float extra_point_size_ = 12.f;
  std::uint64_t synced_revision_ = ~0ull;
  std::uint64_t shown_sculpt_ = 0;  // the sculpt session's revision on display (0: none)
  double synced_time_ = -1e300;
  ViewSettings synced_settings_;
  std::vector<int> synced_selection_;
  bool colors_valid_ = false;
  bool surface_requested_ = false;  // show_pose(): update the surface at the next sync
  std::string error_;
};

}  // namespace dfm::editor
