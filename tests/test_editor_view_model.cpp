// app/editor/view_model: what the panels show, as plain data (issue 38, items 4 to 7): the panels'
// layout at small windows, the toolbar's wrapping, the in-between shown for a transition interval,
// the rig overlays' fade where the surface is not the rigged mesh, outliner numbers, fields without
// "-0.000", time as frames, and what the editor can open. Expected values are worked out here.
#include <cmath>
#include <string>

#include <catch2/catch.hpp>

#include "core/scene/scene_import.h"

#include "app/editor/view_model.h"
#include "core/scene/document.h"
#include "core/scene/key_pairs.h"
#include "tests/key_mesh_test_meshes.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;
using namespace dfm::editor;
using Eigen::Vector3d;

namespace {

bool overlaps(const Rect& a, const Rect& b) {
  return a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h;
}

// The octahedron with one point handle keyed at 0 (a pose key) and a torus keyed at 1 (a mesh key of
// other triangles: a transition joins them), as the teddy and key-torus.obj.
void pose_then_torus(Document& doc) {
  doc.set_surface(test::octahedron(), "octahedron");
  doc.add_point(Vector3d(0.2, 0, 0), "tip");
  doc.set_key(0.0);
  doc.key_mesh(test::torus(Vector3d::Zero(), 1.0, 0.35, 12, 8), "key-torus.obj", 1.0);
}

}  // namespace

TEST_CASE("view model: the panels never cover the viewport, down to small windows", "[editor][view_model]") {
  for (const auto& [W, H] : {std::pair<double, double>{1280, 800}, {900, 700}, {640, 480}, {1920, 1080}}) {
    INFO(W << " x " << H);
    const PanelLayout l = layout_panels(W, H, 21, 118);
    // Left panel | viewport over the timeline | right panel, edge to edge across the window.
    CHECK(l.left.x == 0);
    CHECK(l.viewport.x == Approx(l.left.w));
    CHECK(l.right.x == Approx(l.viewport.x + l.viewport.w));
    CHECK(l.right.x + l.right.w == Approx(W));
    CHECK(l.viewport.y == 21);
    CHECK(l.timeline.y == Approx(l.viewport.y + l.viewport.h));
    CHECK(l.timeline.y + l.timeline.h == Approx(H));
    CHECK(l.timeline.x == l.viewport.x);
    CHECK(l.timeline.w == l.viewport.w);
    for (const Rect* r : {&l.left, &l.right, &l.timeline}) CHECK_FALSE(overlaps(*r, l.viewport));
    CHECK_FALSE(overlaps(l.left, l.right));
    CHECK(l.viewport.w >= 0.4 * W - 1e-9);  // the viewport keeps a usable share
  }
  // Wide windows keep the full panels; 900 px still gives the right panel room for its widgets.
  const PanelLayout wide = layout_panels(1920, 1080, 21, 118);
  CHECK(wide.left.w == 250);
  CHECK(wide.right.w == 320);
  const PanelLayout small = layout_panels(900, 700, 21, 118);
  CHECK(small.right.w >= 270);
  CHECK(small.left.w >= 200);
  // A scaled UI (HiDPI) scales the panels' minimum widths.
  CHECK(layout_panels(1800, 1400, 42, 236, 2.0).right.w == 540);
}

TEST_CASE("view model: toolbar items wrap to rows that fit", "[editor][view_model]") {
  // 100 px rows, 10 px apart: 40 + 10 + 40 = 90 fits, the third 40 would reach 140.
  CHECK(flow_rows({40, 40, 40, 40, 40}, 100, 10) == std::vector<int>{0, 0, 1, 1, 2});
  // An item wider than a row gets its own row; a first item never wraps.
  CHECK(flow_rows({150, 20, 20}, 100, 10) == std::vector<int>{0, 1, 1});
  CHECK(flow_rows({30, 150}, 100, 10) == std::vector<int>{0, 1});
  // Exactly filling the row stays on it.
  CHECK(flow_rows({45, 45}, 100, 10) == std::vector<int>{0, 0});
  CHECK(flow_rows({}, 100, 10).empty());
  // Every row's items with their spacing fit the width (unless a single item is wider).
  const std::vector<double> w = {60, 48, 62, 85, 80, 86, 96, 45, 64, 56, 90, 50};
  for (double avail : {300.0, 500.0, 730.0, 1400.0}) {
    const std::vector<int> rows = flow_rows(w, avail, 8);
    std::vector<double> used(rows.back() + 1, -8.0);
    for (size_t i = 0; i < w.size(); ++i) used[rows[i]] += 8.0 + w[i];
    for (double u : used) CHECK(u <= avail);
    for (size_t i = 1; i < rows.size(); ++i) CHECK((rows[i] == rows[i - 1] || rows[i] == rows[i - 1] + 1));
  }
}

TEST_CASE("view model: a transition interval shows the transition, not an in-between method", "[editor][view_model]") {
  Document doc;
  pose_then_torus(doc);
  REQUIRE(doc.keys().size() == 2);
  CHECK(interval_join(doc, 0) == IntervalJoin::Transition);
  CHECK(std::string(interval_join_label(IntervalJoin::Transition)) == "transition (different meshes)");
  // Setting the method does not change what joins different meshes.
  doc.set_key_inbetween(0, InbetweenMethod::Arap);
  CHECK(interval_join(doc, 0) == IntervalJoin::Transition);
  CHECK(interval_at(doc, 0.0) == 0);
  CHECK(interval_at(doc, 0.5) == 0);
  CHECK(interval_at(doc, 1.0) == 0);
  CHECK(interval_at(doc, 1.5) == -1);

  // Two pose keys (one triangle list): the interval's method.
  Document poses;
  poses.set_surface(test::octahedron(), "octahedron");
  poses.add_point(Vector3d(0.2, 0, 0));
  poses.set_key(0.0);
  poses.set_key(1.0);
  CHECK(interval_join(poses, 0) == IntervalJoin::Handles);
  CHECK(std::string(interval_join_label(IntervalJoin::Handles)) == "handles");
  poses.set_key_inbetween(0, InbetweenMethod::Linear);
  CHECK(interval_join(poses, 0) == IntervalJoin::Linear);
  // A mesh key with the surface's own triangles (a reshaped octahedron): no transition either.
  TriMesh squashed = test::octahedron();
  squashed.V.col(1) *= 0.5;
  poses.key_mesh(squashed, "squashed.obj", 2.0);
  CHECK(interval_join(poses, 1) == IntervalJoin::Handles);
  CHECK(key_is_rigged(poses, 2));
}

TEST_CASE("view model: rig overlays fade over a transition and hide on a mesh of other triangles", "[editor][view_model]") {
  Document doc;
  pose_then_torus(doc);
  CHECK_FALSE(key_is_rigged(doc, 1));
  CHECK(key_is_rigged(doc, 0));
  CHECK(rig_overlay_opacity(doc, 0.0) == 1.0f);   // the rigged key
  CHECK(rig_overlay_opacity(doc, 1.0) == 0.0f);   // the torus: no rig over it
  CHECK(rig_overlay_opacity(doc, 2.0) == 0.0f);   // past the last key the slice is the torus
  CHECK(rig_overlay_opacity(doc, -1.0) == 1.0f);  // before the first, the rigged key
  // In between: linear from the rigged end, never above the share of the rigged key.
  CHECK(rig_overlay_opacity(doc, 0.25) == Approx(0.75));
  CHECK(rig_overlay_opacity(doc, 0.5) == Approx(0.5));
  CHECK(rig_overlay_opacity(doc, 0.9) == Approx(0.1));
  for (double t = 0.05; t < 1.0; t += 0.05) CHECK(rig_overlay_opacity(doc, t) < 1.0f);

  // Pose keys only: the rig always applies. No animation: likewise.
  Document poses;
  poses.set_surface(test::octahedron(), "octahedron");
  poses.add_point(Vector3d(0.2, 0, 0));
  CHECK(rig_overlay_opacity(poses, 0.5) == 1.0f);
  poses.set_key(0.0);
  poses.set_key(1.0);
  for (double t : {0.0, 0.3, 1.0, 4.0}) CHECK(rig_overlay_opacity(poses, t) == 1.0f);
}

TEST_CASE("view model: the outliner numbers its handles as scripts address them", "[editor][view_model]") {
  Document doc;
  doc.set_surface(test::octahedron(), "octahedron");
  doc.add_point(Vector3d(0.2, 0, 0), "l_ear");
  doc.add_point(Vector3d(-0.2, 0, 0), "r_ear");
  doc.add_bone_chain({Vector3d(0, -0.5, 0), Vector3d(0, 0, 0), Vector3d(0, 0.5, 0)});
  CHECK(outliner_label(doc, 0) == "0  l_ear");
  CHECK(outliner_label(doc, 1) == "1  r_ear");
  // Bones come after the points: their number is their global handle index.
  CHECK(outliner_label(doc, 3).rfind("3  ", 0) == 0);
  CHECK(outliner_label(doc, 3).size() > 3);
  // With FAST on, each row also says how FAST treats the handle (defaults: points position, bones pinned).
  PosingSettings p = doc.posing();
  p.fast = true;
  doc.set_posing(p);
  CHECK(outliner_label(doc, 0) == "0  l_ear  [position]");
  CHECK(outliner_label(doc, 2).find("[pinned]") != std::string::npos);
  CHECK(outliner_label(doc, 2, false).find('[') == std::string::npos);  // a narrow row: number and name
  CHECK(outliner_label(doc, 0, false) == "0  l_ear");
}

TEST_CASE("view model: fields show rounded values without negative zero; time as frames", "[editor][view_model]") {
  for (double v : {-0.0, -1e-7, -0.0004, -0.0004999}) {
    const double d = display_value(v, 3);
    CHECK(d == 0.0);
    CHECK_FALSE(std::signbit(d));
  }
  CHECK(display_value(-0.0006, 3) == Approx(-0.001));
  CHECK(display_value(1.23456, 3) == Approx(1.235));
  CHECK(display_value(44.96, 1) == Approx(45.0));
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", display_value(-0.0001, 3));
  CHECK(std::string(buf) == "0.000");

  CHECK(time_to_frame(0.5, 24) == Approx(12));
  CHECK(format_time(0.5, 24) == "frame 12  (0.500 s)");
  CHECK(format_time(0.0, 30) == "frame 0  (0.000 s)");
  CHECK(format_time(1.0, 30) == "frame 30  (1.000 s)");
  CHECK(format_time(0.51, 24) == "frame 12.2  (0.510 s)");
}

TEST_CASE("view model: opening a format the editor cannot read lists the ones it can", "[editor][view_model]") {
  for (const char* ok : {"a.scene.json", "a.obj", "b.OFF", "c.ply", "d.stl", "e.mesh", "f.node", "g.ele", "h.tgf"})
    CHECK(unopenable_reason(ok).empty());
  const std::string fbx = unopenable_reason("character.blend");  // the test registers no importer
  CHECK(fbx.find(".blend") != std::string::npos);
  for (const char* listed : {".scene.json", ".glb", ".obj", ".off", ".ply", ".stl", ".mesh", ".tgf"})
    CHECK(fbx.find(listed) != std::string::npos);
  // A format some module imports as a scene (scene_import.h; the editor registers rigged glTF).
  CHECK_FALSE(unopenable_reason("character.xyzscene").empty());
  register_scene_importer("xyzscene", [](const std::string&, std::string&) { return SceneData{}; });
  CHECK(unopenable_reason("character.xyzscene").empty());
  CHECK(unopenable_reason("noext").find("no file extension") != std::string::npos);
}

TEST_CASE("view model: picked pairs are numbered beside both of their points and where they are now",
          "[editor][view_model]") {
  Document doc;
  doc.key_mesh(test::icosphere(Vector3d::Zero(), 0.45, 2), "sphere.obj", 0);
  doc.key_mesh(test::torus(Vector3d::Zero(), 0.32, 0.12, 24, 12), "torus.obj", 1);
  CHECK(pair_labels(doc, view::Camera{}, nullptr).empty());
  add_key_pair(doc, 0, (Eigen::Matrix<double, 1, 6>() << 0.45, 0, 0, 0.44, 0, 0).finished());
  add_key_pair(doc, 0, (Eigen::Matrix<double, 1, 6>() << 0, 0.45, 0, 0, 0.44, 0).finished());
  // Orthographic, looking down -z at the origin: a point (x, y, 0) is at pixel
  // (W / 2 + x H / (2 h), H / 2 - y H / (2 h)), h = distance tan(fov / 2) the half height shown.
  view::Camera cam;
  cam.orthographic = true;
  cam.width = 800, cam.height = 600;
  const double h = cam.distance * std::tan(cam.fov_y_deg * M_PI / 360), k = cam.height / (2 * h);
  const std::vector<ViewportLabel> labels = pair_labels(doc, cam, nullptr, 6);
  REQUIRE(labels.size() == 4);
  const double want[4][2] = {{400 + 0.45 * k, 300}, {400 + 0.44 * k, 300}, {400, 300 - 0.45 * k}, {400, 300 - 0.44 * k}};
  for (int i = 0; i < 4; ++i) {
    CHECK(labels[i].text == (i < 2 ? "1" : "2"));
    CHECK(labels[i].x == Approx(want[i][0] + 6).margin(1e-6));
    CHECK(labels[i].y == Approx(want[i][1] - 6).margin(1e-6));
  }
  // At t = 0 nobody travels yet; inside the interval, with a placement, where each pair is now: a
  // placement that only moves (by (1, 0, 0)) takes each pair along its chord, at t = 0.5
  // x0 + 0.5 ((x1 - (1, 0, 0)) - x0) + 0.5 (1, 0, 0), the midpoint (test_transition_align turns).
  KeyPlacement moved;
  moved.c1 = Vector3d(1, 0, 0);
  CHECK(pair_labels(doc, cam, &moved, 6).size() == 4);
  doc.set_time(0.5);
  const std::vector<ViewportLabel> travelling = pair_labels(doc, cam, &moved, 6);
  REQUIRE(travelling.size() == 6);
  CHECK(travelling[2].text == "1");
  CHECK(travelling[2].x == Approx(400 + 0.445 * k + 6).margin(1e-6));
  CHECK(travelling[2].y == Approx(300 - 6).margin(1e-6));
  CHECK(travelling[5].text == "2");
  CHECK(travelling[5].x == Approx(400 + 6).margin(1e-6));
  CHECK(travelling[5].y == Approx(300 - 0.445 * k - 6).margin(1e-6));
  // Behind the eye (at z = -2, looking down -z at a target at z = -5): no labels.
  cam.orthographic = false;
  cam.target = Vector3d(0, 0, -5);
  CHECK(pair_labels(doc, cam, &moved).empty());
}
