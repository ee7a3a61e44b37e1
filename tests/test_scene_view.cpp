// app/editor/scene_view: what the viewport asks of the GPU, checked against a recording mock backend
// (tests/mock_render_backend.h) with no GL context: when it uploads and re-skins (caching on the
// document's revision), the posed surface or the animation manifold's slice (Southern 2008, 2.3) by
// keys and time, weight colours for the Weights panel, and the handle overlays. Expected positions
// are closed forms of translation-only poses (LBS of a translation: V + sum_j w_j d_j).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>
#include <vector>

#include <catch2/catch.hpp>

#include "app/editor/manifold_builder.h"
#include "app/editor/scene_view.h"
#include "core/anim/manifold_frame.h"
#include "core/anim/manifold_normals.h"
#include "core/scene/document.h"
#include "core/scene/key_surfaces.h"
#include "app/editor/paint_tool.h"
#include "app/editor/pose_tool.h"
#include "app/editor/sculpt_tool.h"
#include "app/editor/space_time_tool.h"
#include "app/editor/timeline_ruler.h"
#include "core/scene/command.h"
#include "core/scene/script.h"
#include "tests/mock_render_backend.h"
#include "tests/key_mesh_test_meshes.h"
#include "tests/space_time_test_scene.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;
using dfm::editor::ManifoldBuilder;
using dfm::editor::SceneView;
using dfm::editor::ViewSettings;
using dfm::editor::WeightView;
using dfm::test::MockRenderBackend;
using Eigen::Vector3d;
using Eigen::Vector4f;

namespace {

// Three point handles; rows sum to 1, no ties (k = 1 keeps each row's largest).
Eigen::MatrixXd weights() {
  Eigen::MatrixXd W(6, 3);
  W << 1, 0, 0,  //
      0, 1, 0,   //
      0, 0, 1,   //
      0.45, 0.55, 0, 0.2, 0.3, 0.5, 0.6, 0.1, 0.3;
  return W;
}

void make_bound(Document& doc) {
  doc.set_surface(test::octahedron(), "octahedron");
  doc.add_point(Vector3d(0.5, 0, 0));
  doc.add_point(Vector3d(-0.5, 0, 0));
  doc.add_point(Vector3d(0, 0.5, 0));
  doc.set_weights(weights(), BindStats{});
}

// V + W d, d one translation per handle.
Eigen::MatrixXd translated(const Eigen::MatrixXd& W, const std::vector<Vector3d>& d) {
  Eigen::MatrixXd V = test::octahedron().V;
  for (int i = 0; i < V.rows(); ++i)
    for (int j = 0; j < W.cols(); ++j) V.row(i) += W(i, j) * d[j].transpose();
  return V;
}

bool same(const gl::GeometryRef& a, const gl::GeometryRef& b) {
  return a.vertex_buffer == b.vertex_buffer && a.vertex_count == b.vertex_count &&
         a.index_buffer == b.index_buffer && a.index_count == b.index_count;
}

void require_color(const float* c, const Vector4f& expected, float tol = 1e-4f) {
  for (int k = 0; k < 4; ++k) REQUIRE(std::abs(c[k] - expected[k]) < tol);
}

// The batches drawn with this width or size.
std::vector<MockRenderBackend::OverlayBatch> batches(const std::vector<MockRenderBackend::OverlayBatch>& all,
                                                     float size) {
  std::vector<MockRenderBackend::OverlayBatch> out;
  for (const auto& b : all)
    if (b.size == size) out.push_back(b);
  return out;
}

// HSV (hue in degrees) to RGB by the closed form f(n) = v - v s max(0, min(k, 4 - k, 1)),
// k = (n + hue / 60) mod 6: r = f(5), g = f(3), b = f(1).
Vector4f hsv(double hue, double s, double v) {
  auto f = [&](double n) {
    const double k = std::fmod(n + hue / 60.0, 6.0);
    return float(v - v * s * std::max(0.0, std::min({k, 4.0 - k, 1.0})));
  };
  return Vector4f(f(5), f(3), f(1), 1.0f);
}
// The hue (degrees) of an RGB colour.
double hue_of(const float* c) {
  const double r = c[0], g = c[1], b = c[2], mx = std::max({r, g, b}), mn = std::min({r, g, b});
  if (mx - mn < 1e-9) return -1;  // grey: no hue
  double h = mx == r ? std::fmod((g - b) / (mx - mn), 6.0) : mx == g ? (b - r) / (mx - mn) + 2 : (r - g) / (mx - mn) + 4;
  h *= 60.0;
  return h < 0 ? h + 360 : h;
}
// Handle colours as the overlays show them: golden-ratio steps over the hues outside the selection's
// band [10, 70) degrees, s 0.62, v 0.92. Handle 0: 70 + 0.08 * 300 = 94 degrees; handle 3:
// fract(0.08 + 3 * 0.618034) = 0.934102 of the way, 70 + 280.23 = 350.23 degrees.
const Vector4f kHandle0 = hsv(70 + 0.08 * 300, 0.62, 0.92);
const Vector4f kHandle3 = hsv(70 + 0.934102 * 300, 0.62, 0.92);
// The selection: an orange body, outlined in white.
const Vector4f kSelected(1.0f, 0.52f, 0.05f, 1.0f), kOutline(1, 1, 1, 1);

}  // namespace

TEST_CASE("scene view: the rest surface uploads once per content revision", "[editor][scene_view]") {
  Document doc;
  doc.set_surface(test::octahedron(), "octahedron");
  MockRenderBackend gpu;
  SceneView scene(gpu);
  const ViewSettings s;
  scene.sync(doc, s);
  REQUIRE(gpu.mesh_uploads == 1);
  REQUIRE(gpu.mesh.V == test::octahedron().V);
  REQUIRE(gpu.mesh.F == test::octahedron().F);
  REQUIRE(gpu.geometry.vertex_buffer == gpu.mesh_vertex_buffer);
  REQUIRE(gpu.geometry.index_count == 24);
  REQUIRE(scene.display_is_rest());
  REQUIRE_FALSE(scene.showing_slice());
  REQUIRE(gpu.skins.empty());
  REQUIRE(gpu.slicers.empty());
  REQUIRE(scene.surface_bounds().min().isApprox(Vector3d(-1, -1, -1)));
  REQUIRE(scene.surface_bounds().max().isApprox(Vector3d(1, 1, 1)));
  // Nothing changed: nothing uploads again.
  const int sets = gpu.geometry_sets, data = gpu.data_uploads;
  for (int i = 0; i < 3; ++i) scene.sync(doc, s);
  REQUIRE(gpu.mesh_uploads == 1);
  REQUIRE(gpu.geometry_sets == sets);
  REQUIRE(gpu.data_uploads == data);
  // A selection is view state (no new revision): colours may change, the surface does not.
  doc.add_point(Vector3d(0, 0, 0));
  scene.sync(doc, s);
  REQUIRE(gpu.mesh_uploads == 2);  // a content edit
  doc.set_selection(Selection{{0}, -1});
  scene.sync(doc, s);
  REQUIRE(gpu.mesh_uploads == 2);
}

TEST_CASE("scene view: one skin per binding, re-run per pose, drawn and read back", "[editor][scene_view]") {
  Document doc;
  make_bound(doc);
  MockRenderBackend gpu;
  SceneView scene(gpu);
  const ViewSettings s;
  scene.sync(doc, s);
  REQUIRE(gpu.skins.size() == 1);
  const auto& skin = *gpu.skins[0];
  REQUIRE(skin.runs == 1);
  REQUIRE(skin.F == test::octahedron().F);
  REQUIRE(skin.binding.num_handles == 3);
  REQUIRE(same(gpu.geometry, skin.output));
  REQUIRE_FALSE(scene.display_is_rest());
  REQUIRE_FALSE(scene.showing_slice());
  REQUIRE(scene.display_face_count() == 8);

  const Vector3d d0(0.2, 0.3, 0), d1(0, 0, -0.2), d2(0, 0, 0);
  doc.translate_handle(0, d0);
  doc.translate_handle(1, d1);
  scene.sync(doc, s);
  REQUIRE(gpu.skins.size() == 1);  // same binding: only the pose uploads
  REQUIRE(skin.runs == 2);
  REQUIRE(skin.method == SkinMethod::LBS);
  REQUIRE((scene.display_vertices() - translated(weights(), {d0, d1, d2})).cwiseAbs().maxCoeff() < 1e-6);
  REQUIRE(scene.display_faces() == test::octahedron().F);
  // The handles are drawn where the pose puts them.
  REQUIRE(scene.handle_positions().row(0).transpose().isApprox(Vector3d(0.7, 0.3, 0)));
  REQUIRE(scene.handle_positions().row(1).transpose().isApprox(Vector3d(-0.5, 0, -0.2)));
  scene.sync(doc, s);
  scene.sync(doc, s);
  REQUIRE(skin.runs == 2);

  doc.set_method(SkinMethod::DQS);
  scene.sync(doc, s);
  REQUIRE(gpu.skins.size() == 1);
  REQUIRE(skin.runs == 3);
  REQUIRE(skin.method == SkinMethod::DQS);
  doc.set_method(SkinMethod::LBS);

  // One influence per vertex: a new binding; each vertex follows its largest weight's handle.
  BindSettings b = doc.bind_settings();
  b.max_influences = 1;
  doc.set_bind_settings(b);
  scene.sync(doc, s);
  REQUIRE(gpu.skins.size() == 2);
  REQUIRE_FALSE(gpu.skins[0]->alive);
  REQUIRE(same(gpu.geometry, gpu.skins[1]->output));
  Eigen::MatrixXd W1 = Eigen::MatrixXd::Zero(6, 3);
  for (int i = 0; i < 6; ++i) {
    Eigen::Index j;
    weights().row(i).maxCoeff(&j);
    W1(i, j) = 1;
  }
  REQUIRE((scene.display_vertices() - translated(W1, {d0, d1, d2})).cwiseAbs().maxCoeff() < 1e-6);

  // A re-bind with other weights of the same size: the viewport skins with the new ones.
  b.max_influences = 0;
  doc.set_bind_settings(b);
  scene.sync(doc, s);
  Eigen::MatrixXd W2 = weights();
  W2.row(0) << 0.5, 0.5, 0;
  W2.row(2) << 0, 0.25, 0.75;
  doc.set_weights(W2, BindStats{});
  scene.sync(doc, s);
  REQUIRE((scene.display_vertices() - translated(W2, {d0, d1, d2})).cwiseAbs().maxCoeff() < 1e-6);
  REQUIRE(gpu.skins.size() == 4);
}

TEST_CASE("scene view: the manifold's slice with two keys, the pose after a pose edit", "[editor][scene_view]") {
  Document doc;
  make_bound(doc);
  const Vector3d d0(0.2, 0.3, 0), d1(0, 0, -0.2), zero(0, 0, 0);
  doc.set_key(0.0);
  doc.translate_handle(0, d0);
  doc.set_key(1.0);
  doc.set_time(0.5);
  MockRenderBackend gpu;
  SceneView scene(gpu);
  ViewSettings s;
  scene.sync(doc, s);
  REQUIRE(scene.showing_slice());
  REQUIRE(gpu.slicers.size() == 1);
  REQUIRE(gpu.slicers[0]->uploads == 1);
  // Inside an interval between vertex times: its topology is built once and interpolated.
  REQUIRE(scene.slice_from_cache());
  REQUIRE(gpu.intervals.size() == 1);
  REQUIRE(gpu.intervals[0]->evaluations == std::vector<double>{0.5});
  REQUIRE(same(gpu.geometry, gpu.intervals[0]->output));
  // Four in-betweens: layers every 0.2; translations blend linearly, so layer t is V + t W d. Between
  // keys of one connectivity the frame is the mesh itself (issue 38): the octahedron's 6 vertices in
  // order, each half way along its own path from layer 0.4 to layer 0.6, and its 8 triangles.
  REQUIRE(doc.inbetweens() == 4);
  const Eigen::MatrixXd mid = 0.5 * (translated(weights(), {0.4 * d0, zero, zero}) +
                                     translated(weights(), {0.6 * d0, zero, zero}));
  REQUIRE(scene.display_vertices().rows() == 6);
  REQUIRE((scene.display_vertices() - mid).cwiseAbs().maxCoeff() < 1e-6);  // read back as floats
  REQUIRE(scene.display_faces() == test::octahedron().F);
  REQUIRE(scene.display_faces() == gpu.intervals[0]->topology.F);
  REQUIRE(scene.display_face_count() == 8);
  // The handles follow the animation, not the current pose.
  REQUIRE(scene.handle_positions().row(0).transpose().isApprox(Vector3d(0.6, 0.15, 0)));

  // On a key's time (a vertex time): the interval ending there, whose end is the key's mesh exactly
  // (not the general pass's triangle soup).
  doc.set_time(1.0);
  scene.sync(doc, s);
  REQUIRE(scene.slice_from_cache());
  REQUIRE(gpu.intervals.back()->evaluations.back() == 1.0);
  REQUIRE(scene.display_face_count() == 8);
  REQUIRE((scene.display_vertices() - translated(weights(), {d0, zero, zero})).cwiseAbs().maxCoeff() < 1e-6);
  REQUIRE(scene.display_faces() == test::octahedron().F);

  // A pose edit after the scrub shows the pose being edited (the keys, and so the manifold, stay).
  doc.translate_handle(1, d1);
  scene.sync(doc, s);
  REQUIRE_FALSE(scene.showing_slice());
  REQUIRE(same(gpu.geometry, gpu.skins.back()->output));
  REQUIRE(gpu.slicers[0]->uploads == 1);
  REQUIRE((scene.display_vertices() - translated(weights(), {d0, d1, zero})).cwiseAbs().maxCoeff() < 1e-6);
  // ...until the time moves.
  doc.set_time(0.25);
  scene.sync(doc, s);
  REQUIRE(scene.showing_slice());

  // The sweep along x slices at that fraction of the manifold's x extent: the rest's -1 to the
  // keyed +x vertex's 1 + 0.2.
  s.slice_axis = SliceAxis::X;
  s.sweep_value = 0.25;
  scene.sync(doc, s);
  REQUIRE(gpu.slicers[0]->slices.back().first == SliceAxis::X);
  REQUIRE(gpu.slicers[0]->slices.back().second == Approx(-1 + 0.25 * 2.2));

  // One key left: no manifold, the pose.
  s.slice_axis = SliceAxis::T;
  doc.delete_key(1);
  scene.sync(doc, s);
  REQUIRE_FALSE(scene.showing_slice());
  REQUIRE(same(gpu.geometry, gpu.skins.back()->output));
}

TEST_CASE("scene view: a looping playback builds every interval once", "[editor][scene_view]") {
  Document doc;
  make_bound(doc);
  doc.set_key(0.0);
  doc.translate_handle(0, Vector3d(0.2, 0.3, 0));
  doc.set_key(1.0);
  REQUIRE(doc.inbetweens() == 4);  // 5 intervals, more than the 4 slots the cache starts with
  MockRenderBackend gpu;
  SceneView scene(gpu);
  ViewSettings s;
  const double step = 1.0 / 30.0;
  for (int loop = 0; loop < 3; ++loop)
    for (int f = 1; f < 30; ++f) {
      doc.set_time(f * step);
      scene.sync(doc, s);
      REQUIRE(scene.showing_slice());
    }
  REQUIRE(scene.intervals_built() == 5);
  int uploads = 0, prepared = 0;
  for (const auto& i : gpu.intervals) uploads += i->uploads, prepared += i->prepared;
  REQUIRE(uploads == 5);
  // Only the first interval is built when the time enters it; the worker had each later one ready.
  REQUIRE(prepared == 4);
}

TEST_CASE("scene view: back faces are culled only on a closed, outward surface", "[editor][scene_view]") {
  auto culled = [](Document& doc, double time) {
    doc.set_time(time);
    MockRenderBackend gpu;
    SceneView scene(gpu);
    ViewSettings s;
    scene.sync(doc, s);
    scene.draw(doc, view::Camera{}, s);
    REQUIRE(gpu.surface_draws.size() == 1);
    return gpu.surface_draws.back().style.cull_back_faces;
  };
  Document doc;
  make_bound(doc);
  CHECK(culled(doc, 0.0));  // the posed octahedron
  doc.set_key(0.0);
  doc.translate_handle(0, Vector3d(0.2, 0.3, 0));
  doc.set_key(1.0);
  CHECK(culled(doc, 0.5));  // a cached interval's welded slice, checked closed when it was built
  CHECK(culled(doc, 1.0));  // on a key: the end of its cached interval, the keys' closed mesh

  Document open;
  TriMesh m = test::octahedron();
  m.F.conservativeResize(m.F.rows() - 1, 3);  // a triangular hole: the inside shows through it
  open.set_surface(m, "open octahedron");
  CHECK_FALSE(culled(open, 0.0));
  Document inside_out;
  TriMesh f = test::octahedron();
  f.F.col(1).swap(f.F.col(2));  // closed, but its front faces point inward
  inside_out.set_surface(f, "inside-out octahedron");
  CHECK_FALSE(culled(inside_out, 0.0));
  inside_out.set_surface(test::octahedron(), "octahedron");  // the same document made right
  CHECK(culled(inside_out, 0.0));
}

TEST_CASE("scene view: weight colours follow the Weights panel and the selection", "[editor][scene_view]") {
  Document doc;
  make_bound(doc);
  MockRenderBackend gpu;
  SceneView scene(gpu);
  const view::Camera cam;
  ViewSettings s;
  s.weight_view = WeightView::Selected;
  doc.set_selection(Selection{{2}, -1});
  scene.sync(doc, s);
  scene.draw(doc, cam, s);
  REQUIRE(gpu.surface_draws.back().style.mode == gl::SurfaceColorMode::Scalar);
  REQUIRE(gpu.surface_draws.back().style.isolines == 10.0f);
  REQUIRE(gpu.data.size() == 6);
  for (int i = 0; i < 6; ++i) REQUIRE(gpu.data[i] == Vector4f(float(weights()(i, 2)), 0, 0, 1));
  // Another active handle: its weights, without touching the surface.
  const int runs = gpu.skins[0]->runs;
  doc.set_selection(Selection{{1, 2}, -1});
  scene.sync(doc, s);
  for (int i = 0; i < 6; ++i) REQUIRE(gpu.data[i].x() == float(weights()(i, 1)));
  REQUIRE(gpu.skins[0]->runs == runs);

  // All handles: each vertex blends the handle colours by weight.
  s.weight_view = WeightView::AllHandles;
  scene.sync(doc, s);
  gpu.clear_draws();
  scene.draw(doc, cam, s);
  REQUIRE(gpu.surface_draws.back().style.mode == gl::SurfaceColorMode::VertexColor);
  REQUIRE(gpu.surface_draws.back().style.isolines == 0.0f);
  for (int k = 0; k < 3; ++k) REQUIRE(std::pow(gpu.data[0][k], 1 / 2.2f) == Approx(kHandle0[k]).epsilon(1e-4));
  const Vector4f mix = 0.45f * gpu.data[0] + 0.55f * gpu.data[1];  // vertex 3: 0.45 handle 0, 0.55 handle 1
  REQUIRE((gpu.data[3] - mix).cwiseAbs().maxCoeff() < 1e-5f);
  REQUIRE((gpu.data[0] - gpu.data[1]).norm() > 0.1f);

  // The mask.
  doc.paint_mask({0, 4}, {1.0, 0.25});
  s.weight_view = WeightView::Mask;
  scene.sync(doc, s);
  REQUIRE(gpu.data.size() == 6);
  const float mask[6] = {1, 0, 0, 0, 0.25f, 0};
  for (int i = 0; i < 6; ++i) REQUIRE(gpu.data[i] == Vector4f(mask[i], 0, 0, 1));

  // Difference: nothing replaced yet, so no data; after a Rebind the moved share per vertex (all
  // handles) or the selected handle's change.
  s.weight_view = WeightView::Difference;
  scene.sync(doc, s);
  REQUIRE(gpu.data.empty());
  const Eigen::MatrixXd before = doc.weights();
  Eigen::MatrixXd after = before;
  after.row(3) = before.row(0);  // vertex 3 takes vertex 0's weights
  doc.set_weights(after, BindStats{});
  scene.sync(doc, s);
  REQUIRE(gpu.data.size() == 6);
  for (int i = 0; i < 6; ++i)
    REQUIRE(gpu.data[i].x() == Approx(0.5 * (after.row(i) - before.row(i)).cwiseAbs().sum()).margin(1e-7));
  REQUIRE(gpu.data[3].x() > 0.1f);
  doc.set_selection(Selection{{0}, -1});
  scene.sync(doc, s);
  for (int i = 0; i < 6; ++i) REQUIRE(gpu.data[i].x() == Approx(std::abs(after(i, 0) - before(i, 0))).margin(1e-7));
  doc.set_selection(Selection{{1, 2}, -1});

  // Off: shaded, no per-vertex data.
  s.weight_view = WeightView::Off;
  scene.sync(doc, s);
  gpu.clear_draws();
  scene.draw(doc, cam, s);
  REQUIRE(gpu.data.empty());
  REQUIRE(gpu.surface_draws.back().style.mode == gl::SurfaceColorMode::Shaded);

  // A slice has other vertices than the weights: with a weight view on, an animation of pose keys
  // shows skinned at the time (the animation's pose), with the weights on it; with the view off, the slice.
  doc.set_key(0.0);
  doc.translate_handle(0, Vector3d(0, 0.3, 0));
  doc.set_key(1.0);
  scene.sync(doc, s);  // a frame per edit, as in the editor: the scrub below comes after the pose edit
  doc.set_time(0.5);
  scene.sync(doc, s);
  REQUIRE(scene.showing_slice());
  s.weight_view = WeightView::Selected;
  scene.sync(doc, s);
  REQUIRE_FALSE(scene.showing_slice());
  REQUIRE(gpu.data.size() == 6);
  for (int i = 0; i < 6; ++i) REQUIRE(gpu.data[i].x() == float(doc.weights()(i, 1)));
  const Pose half = scene.shown_pose(doc);
  REQUIRE(half.transforms[0].translation().y() == Approx(0.15));  // halfway between the keys' 0 and 0.3
  s.weight_view = WeightView::Off;
  scene.sync(doc, s);
  REQUIRE(scene.showing_slice());
  REQUIRE(gpu.data.empty());
  // Before the first key the slice holds the first key's frame (as save-posed does), not nothing.
  doc.set_time(-0.5);
  scene.sync(doc, s);
  REQUIRE(scene.showing_slice());
  REQUIRE(scene.display_vertex_count() > 0);
}

TEST_CASE("scene view: region handles band the mask view", "[editor][scene_view]") {
  Document doc;
  doc.set_surface(test::octahedron(), "octahedron");
  doc.paint_mask({0, 1}, {0.5, 0.9});
  const int r = doc.add_region("band");
  doc.paint_region(r, {1, 2}, false);
  MockRenderBackend gpu;
  SceneView scene(gpu);
  ViewSettings s;
  s.weight_view = WeightView::Mask;
  scene.sync(doc, s);
  const float expected[6] = {0.5f, 0.9f, 0.75f, 0, 0, 0};  // a region shows at least 0.75
  for (int i = 0; i < 6; ++i) REQUIRE(gpu.data[i].x() == expected[i]);
}

TEST_CASE("scene view: handle overlays by selection and FAST state", "[editor][scene_view]") {
  Document doc;
  doc.set_surface(test::octahedron(), "octahedron");
  doc.add_point(Vector3d(0.5, 0, 0));
  doc.add_point(Vector3d(-0.5, 0, 0));
  doc.add_point(Vector3d(0, 0.5, 0));
  doc.add_bone_chain({Vector3d(0, -0.5, 0), Vector3d(0, -0.5, 0.8)});  // handle 3
  doc.set_selection(Selection{{1, 2}, -1});                               // 1 active, 2 selected
  PosingSettings posing;
  posing.fast = true;
  posing.states = {HandleConstraint::Fixed, HandleConstraint::Free, HandleConstraint::Position,
                   HandleConstraint::Fixed};
  doc.set_posing(posing);
  MockRenderBackend gpu;
  SceneView scene(gpu);
  const view::Camera cam;
  ViewSettings s;
  scene.sync(doc, s);
  scene.draw(doc, cam, s);

  // The grid first, depth-tested, one pixel wide, on the surface's floor.
  REQUIRE(gpu.lines.front().depth_test);
  REQUIRE(gpu.lines.front().size == 1.0f);
  REQUIRE_FALSE(gpu.lines.front().vertices.empty());
  for (const auto& v : gpu.lines.front().vertices) REQUIRE(v.position[1] == -1.0f);

  // Point handles (14 px): colour by index; selected ones (active or not) in the selection's orange,
  // over a 21 px white outline drawn first.
  const auto pts = batches(gpu.points, 14.0f);
  REQUIRE(pts.size() == 1);
  REQUIRE(pts[0].vertices.size() == 3);
  const float* p0 = pts[0].vertices[0].position;
  REQUIRE((p0[0] == 0.5f && p0[1] == 0 && p0[2] == 0));
  require_color(pts[0].vertices[0].color, kHandle0);
  require_color(pts[0].vertices[1].color, kSelected);
  require_color(pts[0].vertices[2].color, kSelected);
  const auto outlines = batches(gpu.points, 21.0f);
  REQUIRE(outlines.size() == 1);
  REQUIRE(outlines[0].vertices.size() == 2);
  for (const auto& v : outlines[0].vertices) require_color(v.color, kOutline);
  REQUIRE(outlines[0].vertices[0].position[0] == -0.5f);  // handle 1
  REQUIRE(outlines[0].vertices[1].position[1] == 0.5f);   // handle 2
  auto index_of = [&](const std::vector<MockRenderBackend::OverlayBatch>& all, float size) {
    for (size_t i = 0; i < all.size(); ++i)
      if (all[i].size == size) return int(i);
    return -1;
  };
  REQUIRE(index_of(gpu.points, 21.0f) < index_of(gpu.points, 14.0f));  // under the handles
  // The bone (5 px): from its first joint in its colour to its tip in half of it; joints as dots.
  const auto bones = batches(gpu.lines, 5.0f);
  REQUIRE(bones.size() == 1);
  REQUIRE(bones[0].vertices.size() == 2);
  require_color(bones[0].vertices[0].color, kHandle3);
  require_color(bones[0].vertices[1].color, Vector4f(0.5f * kHandle3[0], 0.5f * kHandle3[1], 0.5f * kHandle3[2], 1));
  REQUIRE(bones[0].vertices[1].position[2] == 0.8f);
  const auto joints = batches(gpu.points, 8.0f);
  REQUIRE(joints.size() == 1);
  REQUIRE(joints[0].vertices.size() == 2);
  for (const auto& v : joints[0].vertices) require_color(v.color, Vector4f(0.70f, 0.72f, 0.76f, 1));
  // No outline line while no bone is selected; a selected bone gets a 10 px white one under it.
  REQUIRE(batches(gpu.lines, 10.0f).empty());
  doc.set_selection(Selection{{3}, -1});
  scene.sync(doc, s);
  gpu.clear_draws();
  scene.draw(doc, cam, s);
  const auto bone_sel = batches(gpu.lines, 5.0f);
  REQUIRE(bone_sel.size() == 1);
  require_color(bone_sel[0].vertices[0].color, kSelected);
  const auto bone_outline = batches(gpu.lines, 10.0f);
  REQUIRE(bone_outline.size() == 1);
  REQUIRE(bone_outline[0].vertices.size() == 2);
  for (int k = 0; k < 3; ++k) {
    REQUIRE(bone_outline[0].vertices[0].position[k] == bone_sel[0].vertices[0].position[k]);
    REQUIRE(bone_outline[0].vertices[1].position[k] == bone_sel[0].vertices[1].position[k]);
  }
  for (const auto& v : bone_outline[0].vertices) require_color(v.color, kOutline);
  REQUIRE(index_of(gpu.lines, 10.0f) < index_of(gpu.lines, 5.0f));
  require_color(batches(gpu.points, 14.0f)[0].vertices[1].color, hsv(70 + 0.698034 * 300, 0.62, 0.92));  // handle 1 again
  // A selected joint (the bone's tip): the selection's orange over a 15 px outline; the other stays grey.
  doc.set_selection(Selection{{}, 1});
  scene.sync(doc, s);
  gpu.clear_draws();
  scene.draw(doc, cam, s);
  const auto sel_joints = batches(gpu.points, 8.0f);
  REQUIRE(sel_joints.size() == 1);
  require_color(sel_joints[0].vertices[0].color, Vector4f(0.70f, 0.72f, 0.76f, 1));
  require_color(sel_joints[0].vertices[1].color, kSelected);
  const auto joint_outline = batches(gpu.points, 15.0f);
  REQUIRE(joint_outline.size() == 1);
  REQUIRE(joint_outline[0].vertices.size() == 1);
  REQUIRE(joint_outline[0].vertices[0].position[2] == 0.8f);
  require_color(joint_outline[0].vertices[0].color, kOutline);
  doc.set_selection(Selection{{1, 2}, -1});
  // FAST marks (6 px): pinned dark, free white, position-constrained none; a bone's at its tip.
  const auto marks = batches(gpu.points, 6.0f);
  REQUIRE(marks.size() == 1);
  REQUIRE(marks[0].vertices.size() == 3);
  const Vector4f dark(0.08f, 0.08f, 0.1f, 1), white(1, 1, 1, 1);
  require_color(marks[0].vertices[0].color, dark);
  REQUIRE(marks[0].vertices[0].position[0] == 0.5f);
  require_color(marks[0].vertices[1].color, white);
  REQUIRE(marks[0].vertices[1].position[0] == -0.5f);
  require_color(marks[0].vertices[2].color, dark);
  REQUIRE(marks[0].vertices[2].position[2] == 0.8f);

  // Without FAST no marks; without handles no handle overlays; without the grid no depth-tested lines.
  posing.fast = false;
  doc.set_posing(posing);
  s.grid = false;
  scene.sync(doc, s);
  gpu.clear_draws();
  scene.draw(doc, cam, s);
  REQUIRE(batches(gpu.points, 6.0f).empty());
  REQUIRE(std::none_of(gpu.lines.begin(), gpu.lines.end(), [](const auto& b) { return b.depth_test; }));
  s.handles = false;
  gpu.clear_draws();
  scene.draw(doc, cam, s);
  REQUIRE(gpu.lines.empty());
  REQUIRE(batches(gpu.points, 14.0f).empty());
}

TEST_CASE("scene view: per-frame extras draw once, grouped by width", "[editor][scene_view]") {
  Document doc;
  doc.set_surface(test::octahedron(), "octahedron");
  MockRenderBackend gpu;
  SceneView scene(gpu);
  const view::Camera cam;
  ViewSettings s;
  s.grid = false;
  s.handles = false;
  const Vector4f c(1, 1, 1, 1);
  auto seg = [&](double x) {
    return std::vector<gl::OverlayVertex>{gl::overlay_vertex(Vector3d(x, 0, 0), c),
                                          gl::overlay_vertex(Vector3d(x, 1, 0), c)};
  };
  scene.sync(doc, s);
  scene.add_overlay_lines(seg(1), 2.0f);
  scene.add_overlay_lines(seg(2), 2.0f);
  scene.add_overlay_lines(seg(3), 3.0f);
  scene.add_overlay_points({gl::overlay_vertex(Vector3d(4, 0, 0), c)}, 9.0f);
  scene.draw(doc, cam, s);
  REQUIRE(gpu.lines.size() == 2);
  REQUIRE(gpu.lines[0].size == 2.0f);
  REQUIRE(gpu.lines[0].vertices.size() == 4);
  REQUIRE(gpu.lines[0].vertices[2].position[0] == 2.0f);
  REQUIRE(gpu.lines[1].size == 3.0f);
  REQUIRE(gpu.lines[1].vertices.size() == 2);
  REQUIRE(batches(gpu.points, 9.0f).at(0).vertices.size() == 1);
  // The next frame has none of them.
  gpu.clear_draws();
  scene.draw(doc, cam, s);
  REQUIRE(gpu.lines.empty());
  for (const auto& b : gpu.points) REQUIRE(b.vertices.empty());
}

// The Shape space panel's preview (app/editor/shape_space_panel.cpp): a mesh of the surface's
// triangles shown instead of the document's frame until the time or the document changes, or the
// panel clears it; the HUD and picking then see it (not the rest surface: rig edits stay off).
TEST_CASE("scene view: a shape-space preview shows until the time, the document or clear_preview", "[editor][scene_view]") {
  Document doc;
  make_bound(doc);
  doc.set_key(0.0);
  doc.translate_handle(0, Vector3d(0.2, 0.3, 0));
  doc.set_key(1.0);
  doc.set_time(0.5);
  MockRenderBackend gpu;
  SceneView scene(gpu);
  const ViewSettings s;
  scene.sync(doc, s);
  REQUIRE(scene.showing_slice());
  TriMesh shape = test::octahedron();
  shape.V *= 1.5;
  scene.show_preview(shape);
  auto shows_shape = [&] {
    REQUIRE(scene.showing_preview());
    REQUIRE_FALSE(scene.showing_slice());
    REQUIRE_FALSE(scene.display_is_rest());
    REQUIRE(gpu.mesh.V == shape.V);
    REQUIRE(gpu.geometry.vertex_buffer == gpu.mesh_vertex_buffer);
    REQUIRE(scene.display_vertices() == shape.V);
    REQUIRE(scene.display_faces() == shape.F);
  };
  shows_shape();
  const int uploads = gpu.mesh_uploads;
  for (int i = 0; i < 3; ++i) scene.sync(doc, s);  // nothing changed: it stays, uploaded once
  shows_shape();
  REQUIRE(gpu.mesh_uploads == uploads);
  doc.set_time(0.25);  // scrubbing shows the animation again
  scene.sync(doc, s);
  REQUIRE_FALSE(scene.showing_preview());
  REQUIRE(scene.showing_slice());
  scene.show_preview(shape);
  scene.clear_preview();  // the panel closed or its preview turned off
  scene.sync(doc, s);
  REQUIRE_FALSE(scene.showing_preview());
  REQUIRE(scene.showing_slice());
  scene.show_preview(shape);
  doc.translate_handle(1, Vector3d(0, 0, -0.2));  // a document edit: the pose being edited
  scene.sync(doc, s);
  REQUIRE_FALSE(scene.showing_preview());
  REQUIRE(same(gpu.geometry, gpu.skins.back()->output));
}

// Issue 38 (5): a selected handle's orange and white outline are colours no handle has: every
// handle's hue keeps out of the band around the selection's, and handles stay told apart.
TEST_CASE("scene view: handle colours keep out of the selection's hue band", "[editor][scene_view]") {
  const double sel_hue = hue_of(kSelected.data());
  REQUIRE(sel_hue >= 10.0);
  REQUIRE(sel_hue < 70.0);
  for (int h = 0; h < 500; ++h) {
    const Eigen::Vector3f c = dfm::editor::handle_color(h);
    const float shown[3] = {std::pow(c.x(), 1 / 2.2f), std::pow(c.y(), 1 / 2.2f), std::pow(c.z(), 1 / 2.2f)};
    const double hue = hue_of(shown);
    INFO("handle " << h << " hue " << hue);
    REQUIRE(hue >= 0);  // never grey or white (the outline's colour)
    REQUIRE((hue < 10.0 - 1e-3 || hue >= 70.0 - 1e-3));
    const double d = std::min(std::abs(hue - sel_hue), 360 - std::abs(hue - sel_hue));
    REQUIRE(d >= 19.5);  // the band starts 19.7 degrees below the selection's hue
    if (h > 0) {  // neighbours in the outliner differ visibly
      const Eigen::Vector3f p = dfm::editor::handle_color(h - 1);
      REQUIRE((p - c).norm() > 0.05f);
    }
  }
}

namespace {

// Syncs until the manifold's worker (a transition) has landed.
void sync_until_built(SceneView& scene, const Document& doc, const ViewSettings& s) {
  scene.sync(doc, s);
  for (int i = 0; i < 6000 && scene.manifold_building(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    scene.sync(doc, s);
  }
  REQUIRE_FALSE(scene.manifold_building());
  scene.sync(doc, s);
}

}  // namespace

// Issue 38 (4): keyed at 0 on the rigged octahedron and at 1 on a torus (a transition joins them), the
// rig is drawn fully over its own mesh, fades through the transition and is gone over the torus.
TEST_CASE("scene view: rig overlays fade over a transition and hide over another mesh", "[editor][scene_view]") {
  Document doc;
  make_bound(doc);
  doc.set_key(0.0);
  doc.key_mesh(test::torus(Vector3d::Zero(), 1.0, 0.35, 12, 8), "key-torus.obj", 1.0);
  MockRenderBackend gpu;
  SceneView scene(gpu);
  const view::Camera cam;
  const ViewSettings s;
  auto handle_alphas = [&](double t) {
    doc.set_time(t);
    sync_until_built(scene, doc, s);
    REQUIRE(scene.last_error().empty());
    REQUIRE(scene.showing_slice());
    gpu.clear_draws();
    scene.draw(doc, cam, s);
    std::vector<float> a;
    for (const auto& b : batches(gpu.points, 14.0f))
      for (const auto& v : b.vertices) a.push_back(v.color[3]);
    return a;
  };
  // The rigged key: every handle opaque.
  std::vector<float> a = handle_alphas(0.0);
  REQUIRE(a.size() == 3);
  for (float x : a) REQUIRE(x == 1.0f);
  REQUIRE(scene.overlay_opacity() == 1.0f);
  // Half way through the transition: half faded.
  a = handle_alphas(0.5);
  REQUIRE(a.size() == 3);
  for (float x : a) REQUIRE(x == Approx(0.5f));
  // On the torus: nothing of the rig is drawn (no handles, no lines but the grid).
  a = handle_alphas(1.0);
  REQUIRE(a.empty());
  REQUIRE(scene.overlay_opacity() == 0.0f);
  for (const auto& b : gpu.lines) REQUIRE(b.depth_test);  // only the grid
  // The torus shown has the torus's vertices, welded (the general pass draws a soup).
  REQUIRE(scene.display_vertex_count() == 12 * 8);
}

// Issue 38 (6): the HUD counts a slice's welded vertices, not the soup's three corners a face.
TEST_CASE("scene view: a general-pass slice counts its welded vertices", "[editor][scene_view]") {
  Document doc;
  make_bound(doc);
  doc.set_key(0.0);
  doc.translate_handle(0, Vector3d(0.2, 0.3, 0));
  doc.set_key(1.0);
  MockRenderBackend gpu;
  SceneView scene(gpu);
  ViewSettings s;
  s.slice_axis = SliceAxis::X;  // the sweep: always the general pass
  for (double f : {0.2, 0.5, 0.8}) {
    s.sweep_value = f;
    scene.sync(doc, s);
    REQUIRE(scene.showing_slice());
    REQUIRE_FALSE(scene.slice_from_cache());
    const AnimationManifold m = document_manifold(doc);
    const double lo = m.V.col(0).minCoeff(), hi = m.V.col(0).maxCoeff();
    const ManifoldSlice ref = slice_manifold(m, SliceAxis::X, lo + f * (hi - lo));
    INFO("sweep " << f);
    REQUIRE(ref.mesh.num_vertices() > 0);
    REQUIRE(scene.display_face_count() == ref.mesh.num_faces());
    REQUIRE(scene.display_vertex_count() == ref.mesh.num_vertices());
    REQUIRE(scene.display_vertex_count() < 3 * scene.display_face_count());
  }
  // A key's time shows the key's own 6 vertices, whichever pass draws it.
  s.slice_axis = SliceAxis::T;
  for (double t : {0.0, 1.0, 0.5}) {
    doc.set_time(t);
    scene.sync(doc, s);
    REQUIRE(scene.display_vertex_count() == 6);
  }
}

// Issue 38 (6): "Frame all" fits the handles too (the default scene's ear points lie outside the
// surface), and the Transform panel reports the pose on display, not the last edited one.
TEST_CASE("scene view: framing covers the handles; the shown pose follows the animation", "[editor][scene_view]") {
  Document doc;
  make_bound(doc);
  doc.add_point(Vector3d(0.0, 3.0, 0.5));  // far above the octahedron (|y| <= 1)
  MockRenderBackend gpu;
  SceneView scene(gpu);
  const ViewSettings s;
  scene.sync(doc, s);
  REQUIRE_FALSE(scene.surface_bounds().contains(Vector3d(0.0, 3.0, 0.5)));
  REQUIRE(scene.framing_bounds().contains(Vector3d(0.0, 3.0, 0.5)));
  REQUIRE(scene.framing_bounds().contains(scene.surface_bounds()));

  Document anim;
  make_bound(anim);
  anim.set_key(0.0);
  anim.rotate_handle(0, Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4, Vector3d::UnitZ())));
  anim.set_key(1.0);
  SceneView view(gpu);
  anim.set_time(0.5);
  view.sync(anim, s);
  REQUIRE(view.showing_slice());
  const double shown = Eigen::AngleAxisd(view.shown_pose(anim).transforms[0].linear()).angle();
  const double edited = Eigen::AngleAxisd(anim.pose().transforms[0].linear()).angle();
  REQUIRE(shown * 180 / M_PI == Approx(22.5).epsilon(1e-9));
  REQUIRE(edited * 180 / M_PI == Approx(45.0).epsilon(1e-9));
  // Editing the pose shows it (and the panel then reports it).
  anim.translate_handle(1, Vector3d(0, 0, 0.1));
  view.sync(anim, s);
  REQUIRE_FALSE(view.showing_slice());
  REQUIRE(Eigen::AngleAxisd(view.shown_pose(anim).transforms[0].linear()).angle() * 180 / M_PI == Approx(45.0));
}

// Issue 38 (7): an empty document (a file that failed to open at start-up) still draws the grid.
TEST_CASE("scene view: the grid shows without a surface", "[editor][scene_view]") {
  Document doc;
  MockRenderBackend gpu;
  SceneView scene(gpu);
  const ViewSettings s;
  scene.sync(doc, s);
  scene.draw(doc, view::Camera{}, s);
  REQUIRE_FALSE(gpu.lines.empty());
  REQUIRE(gpu.lines.front().depth_test);
  REQUIRE(gpu.lines.front().vertices.size() > 8);
  // ...and framing fits that grid (the floor of the 2-unit box about the origin).
  REQUIRE(scene.framing_bounds().contains(Vector3d(0.9, 0, -0.9)));
  REQUIRE(scene.framing_bounds().contains(Vector3d(-0.9, 0, 0.9)));
}

TEST_CASE("pose tool on a bone: a drag on its twist ring twists it, one undo step; the skin takes the bind's endpoint weights",
          "[editor][scene_view][stbs]") {
  Document doc;
  doc.set_surface(test::octahedron(), "octahedron");
  doc.add_bone_chain({Vector3d(-0.5, 0, 0), Vector3d(0.5, 0, 0)});
  Eigen::MatrixXd E(6, 1);
  E << 0.9, 0.1, 0.5, 0.5, 0.5, 0.5;  // octahedron vertices: +x, -x, then the four around the axis
  doc.set_weights(Eigen::MatrixXd::Ones(6, 1), BindStats{}, E);
  doc.set_selection(Selection{{0}});
  MockRenderBackend gpu;
  SceneView scene(gpu);
  scene.sync(doc, ViewSettings{});
  REQUIRE(gpu.skins.size() == 1);
  CHECK(gpu.skins[0]->binding.endpoints == E);  // one influence a vertex: E in influence order is E

  view::Camera cam;
  cam.width = 800, cam.height = 600;
  cam.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(-0.6, Vector3d::UnitY()));  // the bone not edge-on
  editor::PoseTool tool;
  editor::PoseTool::Input in;
  in.rotate = true;
  in.rig_shown = true;
  REQUIRE(tool.update(doc, scene, cam, in));
  REQUIRE(tool.has_shape());
  const editor::GizmoShape& g = tool.shape();
  REQUIRE(g.has_bone);
  const Vector3d mid(0, 0, 0), u(1, 0, 0);
  const Vector3d from = g.twist_ring[0];
  const int steps = doc.undo_depth();
  in.mouse = view::project_to_pixel(cam, from).head<2>();
  in.clicked = true;
  REQUIRE(tool.update(doc, scene, cam, in));
  CHECK(tool.dragging());
  in.clicked = false;
  for (int k = 1; k <= 6; ++k) {  // in steps along the ring, as a mouse moves
    in.mouse = view::project_to_pixel(cam, mid + Eigen::AngleAxisd(M_PI / 2 * k / 6, u) * (from - mid)).head<2>();
    in.released = k == 6;
    tool.update(doc, scene, cam, in);
  }
  CHECK_FALSE(tool.dragging());
  CHECK(doc.pose_params().bone_twist_stretch[0].twist == Approx(M_PI / 2).margin(0.05));
  CHECK(doc.undo_depth() == steps + 1);
}

TEST_CASE("paint tool on weights: a stroke is paint-weights lines, one undo step, and the lines repeat it exactly",
          "[editor][scene_view][weights]") {
  // A flat square of 2 x 2 cells in z = 0 facing +z, two point handles.
  auto make = [](Document& doc) {
    TriMesh m;
    m.V.resize(25, 3);
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i) m.V.row(i + 5 * j) << 0.25 * i - 0.5, 0.25 * j - 0.5, 0;
    m.F.resize(32, 3);
    for (int j = 0, f = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        const int a = i + 5 * j;
        m.F.row(f++) << a, a + 1, a + 6;
        m.F.row(f++) << a, a + 6, a + 5;
      }
    doc.set_surface(m, "square");
    doc.add_point(Vector3d(-0.5, 0, 0));
    doc.add_point(Vector3d(0.5, 0, 0));
    Eigen::MatrixXd W(25, 2);
    for (int v = 0; v < 25; ++v) W(v, 1) = 0.2 + 0.6 * (m.V(v, 0) + 0.5), W(v, 0) = 1 - W(v, 1);
    doc.set_weights(W, BindStats{});
    doc.set_selection(Selection{{0}});
  };
  Document doc;
  make(doc);
  MockRenderBackend gpu;
  SceneView scene(gpu);
  scene.sync(doc, ViewSettings{});
  view::Camera cam;
  cam.width = 800, cam.height = 600;
  view::frame_box(cam, Vector3d(-0.5, -0.5, 0), Vector3d(0.5, 0.5, 0));
  REQUIRE(camera_forward(cam).z() < -0.9);  // looking at the square's front

  editor::PaintTool tool;
  tool.set_target(editor::PaintTarget::Weights);
  tool.set_brush(0.3, 0.4, 0.5);  // radius a fraction of the diagonal
  tool.set_weight_brush(WeightPaintMode::Add, 1, true, false);
  std::vector<CommandWords> lines;
  const editor::PaintTool::Run run = [&](const CommandWords& w) {
    lines.push_back(w);
    run_command(doc, w);
    return true;
  };
  const Eigen::MatrixXd before = doc.weights();
  const int depth = doc.undo_depth();
  editor::PaintTool::Input in;
  in.hovered = true;
  for (int k = 0; k <= 4; ++k) {
    in.mouse = view::project_to_pixel(cam, Vector3d(-0.3 + 0.15 * k, 0.05, 0)).head<2>();
    in.clicked = k == 0, in.down = true, in.released = k == 4;
    tool.update(doc, scene, cam, in, run);
  }
  CHECK_FALSE(tool.painting());
  REQUIRE(lines.size() == 5);
  CHECK(lines[0][0] == "paint-weights");
  CHECK(lines[0][2] == "add");
  CHECK(doc.undo_depth() == depth + 1);
  const Eigen::MatrixXd after = doc.weights();
  CHECK(after != before);
  CHECK((after.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-12);

  // The lines as a script on a fresh document: the same weights, bit for bit.
  Document replay;
  make(replay);
  std::string text;
  for (const CommandWords& w : lines) {
    for (size_t i = 0; i < w.size(); ++i) text += (i ? " " : "") + w[i];
    text += "\n";
  }
  run_script(replay, parse_script(text, "stroke.txt"), "stroke.txt");
  CHECK(replay.weights() == after);
  doc.undo();
  CHECK(doc.weights() == before);

  // Held Ctrl subtracts; with no handle selected nothing is painted.
  in.erase = true;
  in.mouse = view::project_to_pixel(cam, Vector3d(0, 0, 0)).head<2>();
  in.clicked = true, in.released = true;
  tool.update(doc, scene, cam, in, run);
  CHECK(lines.back()[2] == "subtract");
  doc.set_selection(Selection{});
  const size_t n = lines.size();
  tool.update(doc, scene, cam, in, run);
  CHECK(lines.size() == n);
}

// Issue 37: the Sculpt tool's strokes and drags are script lines that repeat it; the view shows the
// session's result (with the tool's heat map) until it is keyed or discarded.
TEST_CASE("sculpt tool: region stroke, handle drag and key are lines a script repeats; the view shows the result",
          "[editor][scene_view][sculpt]") {
  const TriMesh sphere = test::icosphere(Vector3d::Zero(), 1.0, 2);  // 162 vertices
  Document doc;
  doc.set_surface(sphere, "sphere");
  MockRenderBackend gpu;
  SceneView scene(gpu);
  ViewSettings vs;
  vs.sculpt_colors = true;
  scene.sync(doc, vs);
  view::Camera cam;
  cam.width = 800, cam.height = 600;
  view::frame_box(cam, Vector3d(-1, -1, -1), Vector3d(1, 1, 1));
  REQUIRE(camera_forward(cam).z() < -0.9);  // looking at the +z side

  editor::SculptTool tool;
  tool.set_brush(0.15, 0.06, 0.5, 0.5);  // fractions of the diagonal (3.46): region 0.52, handle 0.21
  std::vector<CommandWords> lines;
  const editor::SculptTool::Run run = [&](const CommandWords& w) {
    lines.push_back(w);
    run_command(doc, w);
    return true;
  };
  const int depth = doc.undo_depth();
  editor::SculptTool::Input in;
  in.hovered = true;
  for (int k = 0; k <= 2; ++k) {  // a short stroke across the front
    in.mouse = view::project_to_pixel(cam, Vector3d(-0.2 + 0.2 * k, 0, 0.98)).head<2>();
    in.clicked = k == 0, in.down = true, in.released = k == 2;
    tool.update(doc, scene, cam, in, run);
    scene.sync(doc, vs);
  }
  REQUIRE(doc.sculpt());
  CHECK(lines.size() == 3);
  CHECK(lines[0][0] == "sculpt-region");
  tool.set_mode(editor::SculptMode::Handle);
  const Eigen::Vector2d at = view::project_to_pixel(cam, Vector3d(0, 0, 1)).head<2>();
  for (int k = 0; k <= 3; ++k) {  // click the handle, drag it up 30 pixels
    in.mouse = at - Eigen::Vector2d(0, 10.0 * k);
    in.clicked = k == 0, in.down = k < 3, in.released = k == 3;
    tool.update(doc, scene, cam, in, run);
    scene.sync(doc, vs);
  }
  CHECK_FALSE(tool.busy());
  REQUIRE(lines.size() == 6);
  CHECK(lines[3][0] == "sculpt-handle");
  CHECK(lines[4][0] == "sculpt-move");
  const SculptSession& s = *doc.sculpt();
  CHECK(s.move.y() > 0.05);  // up on screen is +y
  CHECK(doc.undo_depth() == depth);  // the session is tool state

  // The view shows the result, with fixed 0, free 0.55 and handle 1 as the heat map.
  CHECK(scene.showing_preview());
  CHECK(scene.display_vertices() == s.result);
  REQUIRE(gpu.data.size() == static_cast<size_t>(sphere.V.rows()));
  for (int v = 0; v < sphere.V.rows(); ++v) {
    const bool handle = std::count(s.handle.begin(), s.handle.end(), v) > 0;
    CHECK(gpu.data[v].x() == (handle ? 1.0f : s.region[v] ? 0.55f : 0.0f));
  }
  scene.clear_preview();  // another panel's clear keeps the session's result
  scene.sync(doc, vs);
  CHECK(scene.display_vertices() == s.result);

  // The lines on a fresh document: the same surface, bit for bit.
  Document replay;
  replay.set_surface(sphere, "sphere");
  std::string text;
  for (const CommandWords& w : lines) {
    for (size_t i = 0; i < w.size(); ++i) text += (i ? " " : "") + w[i];
    text += "\n";
  }
  run_script(replay, parse_script(text, "sculpt.txt"), "sculpt.txt");
  REQUIRE(replay.sculpt());
  CHECK(replay.sculpt()->result == s.result);

  // Key this shape: one undo step; the view goes back to the document's surface.
  const Eigen::MatrixXd result = s.result;
  CHECK(run(command_words("sculpt-key", {1.0})));
  CHECK(doc.undo_depth() == depth + 1);
  REQUIRE(doc.keys().size() == 1);
  CHECK(doc.keys()[0].mesh.V == result);
  scene.sync(doc, vs);
  CHECK_FALSE(scene.showing_preview());
  CHECK(scene.display_vertices() == sphere.V);
}

TEST_CASE("sculpt tool: a transition dab on an in-between is measured on the interval's first key", "[editor][sculpt]") {
  const TriMesh a = test::icosphere(Vector3d::Zero(), 1.0, 1);
  TriMesh b = a;
  b.V *= 1.5;
  Document doc;
  doc.set_surface(a, "a");
  doc.key_mesh(a, "a.obj", 0);
  doc.key_mesh(b, "b.obj", 1);
  doc.set_time(0.5);
  const Vector3d bary(0.2, 0.3, 0.5);
  Vector3d on_b = Vector3d::Zero(), on_a = Vector3d::Zero();
  for (int j = 0; j < 3; ++j) on_b += bary[j] * b.V.row(b.F(4, j)).transpose(), on_a += bary[j] * a.V.row(a.F(4, j)).transpose();
  const CommandWords w = editor::SculptTool::transition_line(doc, a.F, 4, bary, on_b, 0.3, 0.5, 0.25);
  REQUIRE(w.size() == 8);
  CHECK(w[0] == "transition-state");
  CHECK(std::strtod(w[1].c_str(), nullptr) == 0.5);
  CHECK((Vector3d(std::strtod(w[3].c_str(), nullptr), std::strtod(w[4].c_str(), nullptr), std::strtod(w[5].c_str(), nullptr)) -
         on_a).norm() < 1e-15);
  run_command(doc, w);
  CHECK((doc.keys()[0].transition_to_next.array() > 0).count() > 0);
  // No interval for a local transition (a single key): no line, and why.
  Document one;
  one.set_surface(a, "a");
  one.key_mesh(a, "a.obj", 0);
  std::string why;
  CHECK(editor::SculptTool::transition_line(one, a.F, 4, bary, on_a, 0.3, 0.5, 0, &why).empty());
  CHECK(why.find("two keys") != std::string::npos);
}

TEST_CASE("manifold builder: the document's space-time edits replayed onto the viewport's manifold, a drag frame "
          "without a rebuild, undo back to the keys' manifold", "[editor][scene_view][space-time]") {
  Document doc;
  test::make_keyed(doc);
  ManifoldBuilder b;
  REQUIRE(b.update(doc));
  const MatrixX4dRow keys_V = b.manifold().V;
  const MatrixX4iRow keys_T = b.manifold().T;
  SpaceTimeEdit e;
  e.region = {Vector3d(2, 0, 0), 1.2, 0.8, 1.9};  // short of the last key: a retime may move it
  e.handle = {Vector3d(2, 0, 0), 1.2};
  doc.set_time(1.2);
  const TriMesh mid = posed_surface(doc);
  int h = 0;  // the frame's vertex nearest the +x tip: the handle
  for (int i = 1; i < mid.V.rows(); ++i)
    if ((mid.V.row(i) - Eigen::RowVector3d(2, 0.4, 0)).norm() < (mid.V.row(h) - Eigen::RowVector3d(2, 0.4, 0)).norm()) h = i;
  e.handle.point = mid.V.row(h).transpose();
  doc.begin_gesture();
  doc.add_space_time_edit(e);
  b.update(doc);
  REQUIRE(b.manifold().V == keys_V);  // a still edit changes nothing
  std::shared_ptr<const AnimationManifold> held;  // a frame the view (or its prefetch worker) still reads
  MatrixX4dRow held_V;
  for (int f = 1; f <= 5; ++f) {
    e.move = Vector3d(0, 0, 0.1 * f);
    doc.set_space_time_edit(0, e);
    REQUIRE(b.update(doc));
    REQUIRE(b.edit_notes().empty());
    // The same bits as the saves' manifold (document_manifold replays without the cache).
    REQUIRE(b.manifold().V == document_manifold(doc).V);
    REQUIRE(*b.normals() == manifold_vertex_normals(b.manifold()));  // the window's rows recomputed only
    REQUIRE(b.positions_only());  // the first drag frame too: the still edit showed the keys' manifold
    REQUIRE(b.manifold().T == keys_T);
    // The builder rewrites manifolds in turn, never one somebody still holds.
    if (held) REQUIRE(held->V == held_V);
    if (f == 2) held = b.shared_manifold(), held_V = held->V;
  }
  REQUIRE(held->V != b.manifold().V);
  // A retime makes new slabs: not positions only, and none after it either (other tetrahedra before).
  e.retime = 0.05;
  doc.set_space_time_edit(0, e);
  REQUIRE(b.update(doc));
  REQUIRE_FALSE(b.positions_only());
  REQUIRE(b.manifold().V == document_manifold(doc).V);
  e.retime = 0;
  doc.set_space_time_edit(0, e);
  REQUIRE(b.update(doc));
  REQUIRE_FALSE(b.positions_only());
  REQUIRE(b.manifold().V == document_manifold(doc).V);
  REQUIRE(b.manifold().T == keys_T);
  doc.end_gesture();
  REQUIRE(doc.undo_name() == "space-time edit");  // add + the drag frames: one step
  REQUIRE((b.manifold().V - keys_V).cwiseAbs().maxCoeff() > 0.2);
  doc.undo();
  REQUIRE(b.update(doc));
  REQUIRE(b.manifold().V == keys_V);
  REQUIRE(*b.normals() == manifold_vertex_normals(b.manifold()));
}

TEST_CASE("scene view: a space-time drag frame keeps the interval's topology and shows the edited slice",
          "[editor][scene_view][space-time]") {
  Document doc;
  test::make_keyed(doc);
  MockRenderBackend gpu;
  SceneView scene(gpu);
  ViewSettings s;
  doc.set_time(1.2);
  scene.sync(doc, s);
  REQUIRE(scene.showing_slice());
  REQUIRE(scene.slice_from_cache());
  const Eigen::VectorXd test_keys_t = document_manifold(doc).V.col(3);
  const int built = scene.intervals_built();
  REQUIRE(built >= 1);
  SpaceTimeEdit e;
  e.region = {Vector3d(2, 0, 0), 1.2, 0.8, 1.9};  // short of the last key: a retime may move it
  e.handle = {Vector3d(2, 0.4, 0), 1.2};
  doc.begin_gesture();
  doc.add_space_time_edit(e);
  for (int f = 1; f <= 3; ++f) {
    e.move = Vector3d(0, 0, 0.1 * f);
    doc.set_space_time_edit(0, e);
    scene.sync(doc, s);
    REQUIRE(scene.slice_from_cache());
    // No new topology (the tetrahedra and times are the keys'), the positions are the edit's.
    REQUIRE(scene.intervals_built() == built);
    REQUIRE(gpu.slicers[0]->uploads == 1);  // the tetrahedra once
    REQUIRE(gpu.slicers[0]->vertex_uploads == 0);  // the general pass is not drawn: not uploaded
    const TriMesh want = manifold_frame(document_manifold(doc), 1.2).mesh;
    const Eigen::MatrixXd& shown = scene.display_vertices();
    REQUIRE(shown.rows() == want.V.rows());
    REQUIRE((shown - want.V).cwiseAbs().maxCoeff() < 1e-6);  // read back as floats; the drag moves 0.1-0.3
  }
  doc.end_gesture();
  // The sweep (the general pass) then takes the drag's last positions, once, and shows the edited manifold.
  s.slice_axis = SliceAxis::X;
  const AnimationManifold m = document_manifold(doc);
  const double lo = m.V.col(0).minCoeff(), hi = m.V.col(0).maxCoeff();
  for (double x : {1.6, 1.85}) {  // through the region (its centre at x = 2, the tip)
    const double f = (x - lo) / (hi - lo);
    s.sweep_value = f;
    scene.sync(doc, s);
    const ManifoldSlice want = slice_manifold(m, SliceAxis::X, lo + f * (hi - lo));
    REQUIRE(want.mesh.num_faces() > 0);
    REQUIRE(scene.display_face_count() == want.mesh.num_faces());
    Eigen::RowVector3d corners = Eigen::RowVector3d::Zero();  // the soup's corners, summed
    for (int t = 0; t < want.mesh.num_faces(); ++t)
      for (int c = 0; c < 3; ++c) corners += want.mesh.V.row(want.mesh.F(t, c));
    REQUIRE((scene.display_vertices().colwise().sum() - corners).norm() < 1e-5 * want.mesh.num_faces());
    REQUIRE(gpu.slicers[0]->uploads == 1);
    REQUIRE(gpu.slicers[0]->vertex_uploads == 1);
  }
  s.slice_axis = SliceAxis::T;
  // A retime changes the times: the intervals are cut again (more distinct vertex times).
  const int times_before = scene.vertex_time_count();
  e.retime = 0.05;
  doc.set_space_time_edit(0, e);
  scene.sync(doc, s);
  REQUIRE(scene.showing_slice());
  REQUIRE(document_manifold(doc).V.col(3) != test_keys_t);
  REQUIRE(scene.vertex_time_count() > times_before);
}

// The keyed bar at t = 1 in a mock-GL view, showing its slice, seen from the +z side (the Space-time
// tool's tests).
struct SpaceTimeView {
  Document doc;
  MockRenderBackend gpu;
  SceneView scene{gpu};
  ViewSettings vs;
  view::Camera cam;
  SpaceTimeView() {
    test::make_keyed(doc);
    doc.set_time(1.0);
    scene.sync(doc, vs);
    REQUIRE(scene.showing_slice());
    cam.width = 800, cam.height = 600;
    view::frame_box(cam, Vector3d(-2, -1, -1), Vector3d(2, 1.6, 1));
  }
};

TEST_CASE("space-time tool: the panel's setup goes on the region line; a Ctrl-drag retimes (the viewport's width the "
          "window) in one undo step, a refused retime keeps the last accepted one", "[editor][scene_view][space-time]") {
  SpaceTimeView f;
  Document& doc = f.doc;
  SceneView& scene = f.scene;
  ViewSettings& vs = f.vs;
  const view::Camera& cam = f.cam;
  REQUIRE(camera_forward(cam).z() < -0.9);  // looking at the +z side
  // A point on the +x end's front at t = 1 (in the lifted part), picked where it shows.
  const TriMesh frame = posed_surface(doc);
  const Eigen::RowVector3d front(1.6, 0.3, 0.6);
  int v = 0;
  for (int i = 1; i < frame.V.rows(); ++i)
    if ((frame.V.row(i) - front).norm() < (frame.V.row(v) - front).norm()) v = i;
  const Eigen::Vector2d at = view::project_to_pixel(cam, frame.V.row(v).transpose()).head<2>();

  editor::SpaceTimeTool tool;
  tool.set_region(0.25, 0.4, 1.6);
  tool.set_setup(LaplacianWeights::Equal, 2.0, false);
  std::vector<CommandWords> lines;
  const editor::SpaceTimeTool::Run run = [&](const CommandWords& w) {
    lines.push_back(w);
    run_command(doc, w);
    return true;
  };
  editor::SpaceTimeTool::Input in;
  in.hovered = true;
  in.mouse = at;
  in.clicked = true, in.new_region = true;
  CHECK(tool.update(doc, scene, cam, in, run).empty());
  REQUIRE(lines.size() == 1);
  REQUIRE(lines[0].size() == 9);
  CHECK(lines[0][0] == "edit-region");
  CHECK(lines[0][7] == "weights=equal");
  CHECK(lines[0][8] == "time-scale=2");
  REQUIRE(doc.space_time_edits().size() == 1);
  CHECK(doc.space_time_edits()[0].weights == LaplacianWeights::Equal);
  CHECK(doc.space_time_edits()[0].time_scale == 2);
  const int depth = doc.undo_depth();
  scene.sync(doc, vs);

  // Ctrl-press on the same point, then right 40 pixels: 40 / 800 of the window (1.2) later.
  in.new_region = false, in.retime = true;
  CHECK(tool.update(doc, scene, cam, in, run).empty());
  REQUIRE(tool.dragging());
  REQUIRE(lines.size() == 2);
  CHECK(lines[1][0] == "edit-drag");
  in.clicked = false, in.retime = false;  // Ctrl counts at the press only
  std::string status;
  for (int k = 1; k <= 4; ++k) {
    in.mouse = at + Eigen::Vector2d(10.0 * k, 3.0 * k);  // vertical motion does nothing
    status = tool.update(doc, scene, cam, in, run);
    scene.sync(doc, vs);
    CHECK(status.empty());
    CHECK(scene.last_error().empty());
  }
  const double dt = 40.0 / 800 * 1.2;
  REQUIRE(doc.space_time_edits().size() == 1);
  const SpaceTimeEdit e = doc.space_time_edits()[0];
  CHECK(std::abs(e.retime - dt) < 1e-12);
  CHECK(e.move == Vector3d::Zero());
  std::vector<std::string> notes;
  const AnimationManifold m = document_manifold(doc, nullptr, {}, &notes);
  CHECK(notes.empty());
  Document keys_only;
  test::make_keyed(keys_only);
  const AnimationManifold k = document_manifold(keys_only);
  CHECK((m.V.rows() != k.V.rows() || m.V.col(3) != k.V.col(3)));  // the times moved

  // Far right: past the window's end the slab would fold back in time. Refused: the status says so,
  // the document keeps the last accepted retime and the view replays it without a skipped edit.
  in.mouse = at + Eigen::Vector2d(600, 0);
  status = tool.update(doc, scene, cam, in, run);
  INFO(status);
  CHECK(status.find("refused") != std::string::npos);
  CHECK(status.find("folds the manifold in time") != std::string::npos);
  CHECK(doc.space_time_edits()[0] == e);
  scene.sync(doc, vs);
  CHECK(scene.last_error().empty());
  CHECK(tool.update(doc, scene, cam, in, run).empty());  // the same refusal is said once

  // Release: one undo step for the press and every frame; the lines repeat it with edit-drag's DT.
  in.released = true;
  status = tool.update(doc, scene, cam, in, run);
  CHECK(status.find("space-time retime by") == 0);
  CHECK_FALSE(tool.dragging());
  CHECK(doc.undo_depth() == depth + 1);
  Document replay;
  test::make_keyed(replay);
  replay.set_time(1.0);
  run_command(replay, lines[0]);
  CommandWords drag = lines[1];
  drag.push_back(CommandArg(e.retime).word);
  run_command(replay, drag);
  CHECK(replay.space_time_edits() == doc.space_time_edits());
  doc.undo();
  REQUIRE(doc.space_time_edits().size() == 1);
  CHECK(doc.space_time_edits()[0].retime == 0);
}

TEST_CASE("space-time tool: a Shift stroke brushes the region (a ball each half radius, one undo step with the region)",
          "[editor][scene_view][space-time]") {
  SpaceTimeView f;
  Document& doc = f.doc;
  SceneView& scene = f.scene;
  const view::Camera& cam = f.cam;
  // Two points on the bar's front at t = 1, picked where they show: the stroke goes from one to the other.
  const TriMesh frame = posed_surface(doc);
  auto pixel_near = [&](const Eigen::RowVector3d& p) {
    int v = 0;
    for (int i = 1; i < frame.V.rows(); ++i)
      if ((frame.V.row(i) - p).norm() < (frame.V.row(v) - p).norm()) v = i;
    return Eigen::Vector2d(view::project_to_pixel(cam, frame.V.row(v).transpose()).head<2>());
  };
  const Eigen::Vector2d from = pixel_near({-1.2, 0.0, 0.6}), to = pixel_near({0.8, 0.0, 0.6});
  editor::SpaceTimeTool tool;
  tool.set_region(0.05, 0.4, 1.6);
  std::vector<CommandWords> lines;
  const editor::SpaceTimeTool::Run run = [&](const CommandWords& w) {
    lines.push_back(w);
    run_command(doc, w);
    return true;
  };
  const int depth = doc.undo_depth();
  editor::SpaceTimeTool::Input in;
  in.hovered = true;
  in.mouse = from;
  in.clicked = true, in.new_region = true;
  CHECK(tool.update(doc, scene, cam, in, run).empty());
  REQUIRE(lines.size() == 1);
  CHECK(lines[0][0] == "edit-region");
  CHECK(tool.dragging());  // the stroke holds the view (no orbit)
  in.clicked = false;
  for (int k = 1; k <= 20; ++k) {
    in.mouse = from + (to - from) * (k / 20.0);
    CHECK(tool.update(doc, scene, cam, in, run).empty());
  }
  in.released = true;
  const std::string status = tool.update(doc, scene, cam, in, run);
  CHECK(!tool.dragging());
  REQUIRE(doc.space_time_edits().size() == 1);
  const EditRegionSpec& r = doc.space_time_edits()[0].region;
  INFO(status << "; " << lines.size() << " lines");
  CHECK(status.find("space-time region: " + std::to_string(r.dabs.size() + 1) + " ball(s)") == 0);
  // About one ball each half radius along the 2.0-long stroke (more where the stroke's pixels run ahead).
  CHECK(r.dabs.size() >= 2.0 / r.radius - 2);
  CHECK(lines.size() == r.dabs.size() + 1);
  for (size_t i = 1; i < lines.size(); ++i) CHECK(lines[i][0] == "edit-brush");
  // Consecutive balls half a radius to a radius apart: the brushed region has no gap.
  Eigen::Vector3d last = r.center;
  for (const Eigen::Vector3d& d : r.dabs) {
    CHECK((d - last).norm() > 0.5 * r.radius);
    CHECK((d - last).norm() < r.radius);
    last = d;
  }
  CHECK(doc.undo_depth() == depth + 1);  // the region and its stroke: one step
  doc.undo();
  CHECK(doc.space_time_edits().empty());
}

TEST_CASE("the timeline's Space-time band: a dragged edge snaps to whole frames and keeps the band a frame wide",
          "[editor][space-time]") {
  using editor::dragged_band;
  const std::pair<double, double> band{0.4, 1.6};
  CHECK(dragged_band(band, 0, 0.52, 24) == std::pair<double, double>{12.0 / 24, 1.6});  // 12.48 frames -> 12
  CHECK(dragged_band(band, 1, 1.23, 24) == std::pair<double, double>{0.4, 30.0 / 24});  // 29.52 -> 30
  // Past the other edge: stops a frame short of it.
  CHECK(dragged_band(band, 0, 1.9, 24) == std::pair<double, double>{1.6 - 1.0 / 24, 1.6});
  CHECK(dragged_band(band, 1, 0.1, 24) == std::pair<double, double>{0.4, 0.4 + 1.0 / 24});
}
