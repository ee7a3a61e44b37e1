// Gizmo drags, document camera conversion and the recent-files list: the editor's CPU logic.
#include <cmath>

#include <catch2/catch.hpp>

#include "app/editor/camera_sync.h"
#include "app/editor/file_panel.h"
#include "app/editor/gizmo.h"

using namespace dfm;
using namespace dfm::editor;
using Eigen::Vector2d;
using Eigen::Vector3d;

static view::Camera cam(bool ortho) {
  view::Camera c;
  c.width = 900;
  c.height = 700;
  c.distance = 6;
  c.orthographic = ortho;
  c.target = Vector3d(0.2, 0.1, -0.3);
  c.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Vector3d(0.3, 1, 0.2).normalized()));
  return c;
}

static Vector2d px(const view::Camera& c, const Vector3d& p) { return view::project_to_pixel(c, p).head<2>(); }

TEST_CASE("axis drag moves exactly the distance between the projected axis points", "[gizmo]") {
  for (bool ortho : {false, true}) {
    const view::Camera c = cam(ortho);
    const Vector3d o(0.1, 0.2, 0.0);
    for (int k = 0; k < 3; ++k) {
      const Vector3d a = Vector3d::Unit(k);
      const auto part = GizmoPart(int(GizmoPart::AxisX) + k);
      const Vector3d d = gizmo_translation(c, o, part, px(c, o + 0.1 * a), px(c, o + 0.35 * a));
      REQUIRE((d - 0.25 * a).norm() < 1e-6);
    }
  }
}

TEST_CASE("a drag off the axis only moves along the axis", "[gizmo]") {
  const view::Camera c = cam(false);
  const Vector3d o(0, 0, 0);
  const Vector3d d = gizmo_translation(c, o, GizmoPart::AxisY, px(c, o), px(c, o) + Vector2d(40, -30));
  REQUIRE(std::abs(d.x()) < 1e-12);
  REQUIRE(std::abs(d.z()) < 1e-12);
}

TEST_CASE("plane drag follows the cursor within the plane", "[gizmo]") {
  const view::Camera c = cam(false);
  const Vector3d o(0.3, -0.2, 0.1);
  const Vector3d from = o + Vector3d(0.1, 0.05, 0), to = o + Vector3d(-0.2, 0.3, 0);
  const Vector3d d = gizmo_translation(c, o, GizmoPart::PlaneXY, px(c, from), px(c, to));
  REQUIRE((d - (to - from)).norm() < 1e-6);
}

TEST_CASE("ring rotation: the swept screen angle, about the view axis, in the drag's sense", "[gizmo]") {
  const view::Camera c = cam(false);
  const Vector3d o(0, 0, 0);
  const Vector2d s = px(c, o);
  // A quarter turn counter-clockwise on screen (screen y points down): right -> up.
  const Eigen::Quaterniond q = gizmo_rotation(c, o, GizmoPart::Ring, s + Vector2d(100, 0), s + Vector2d(0, -100));
  REQUIRE(q.angularDistance(Eigen::Quaterniond::Identity()) == Approx(M_PI / 2));
  // A point right of the origin on screen moves up on screen.
  const Vector3d p = o + 0.2 * view::camera_right(c);
  const Vector2d moved = px(c, q * p);
  REQUIRE(moved.y() < s.y() - 5);
  REQUIRE(std::abs(moved.x() - s.x()) < 2);
}

TEST_CASE("trackball rotation is identity for no motion and undone by the reverse drag", "[gizmo]") {
  const view::Camera c = cam(false);
  const Vector3d o(0, 0, 0);
  const Vector2d s = px(c, o);
  REQUIRE(gizmo_rotation(c, o, GizmoPart::Trackball, s, s).angularDistance(Eigen::Quaterniond::Identity()) < 1e-12);
  const Eigen::Quaterniond a = gizmo_rotation(c, o, GizmoPart::Trackball, s, s + Vector2d(30, 10));
  const Eigen::Quaterniond b = gizmo_rotation(c, o, GizmoPart::Trackball, s + Vector2d(30, 10), s);
  REQUIRE((b * a).angularDistance(Eigen::Quaterniond::Identity()) < 1e-9);
  REQUIRE(a.angularDistance(Eigen::Quaterniond::Identity()) > 0.05);
}

TEST_CASE("gizmo_hit finds axis tips, plane squares, ring and nothing far away", "[gizmo]") {
  const view::Camera c = cam(false);
  const Vector3d o(0, 0, 0);
  const GizmoLayout L;
  const double len = world_per_pixels(c, o, L.axis_px);
  REQUIRE(gizmo_hit(c, o, false, px(c, o + 0.9 * len * Vector3d::UnitX())) == GizmoPart::AxisX);
  REQUIRE(gizmo_hit(c, o, false, px(c, o + 0.9 * len * Vector3d::UnitZ())) == GizmoPart::AxisZ);
  const double mid = 0.25 * len + 0.5 * len * L.plane_px / L.axis_px;
  REQUIRE(gizmo_hit(c, o, false, px(c, o + Vector3d(mid, mid, 0))) == GizmoPart::PlaneXY);
  REQUIRE(gizmo_hit(c, o, false, px(c, o) + Vector2d(300, 300)) == GizmoPart::None);
  REQUIRE(gizmo_hit(c, o, true, px(c, o) + Vector2d(L.ring_px, 0)) == GizmoPart::Ring);
  REQUIRE(gizmo_hit(c, o, true, px(c, o) + Vector2d(20, 0)) == GizmoPart::Trackball);
}

TEST_CASE("world_per_pixels: that many pixels on screen", "[gizmo]") {
  for (bool ortho : {false, true}) {
    const view::Camera c = cam(ortho);
    const Vector3d p(0.5, 0.2, 0.4);
    const double w = world_per_pixels(c, p, 50);
    const double shown = (px(c, p + w * view::camera_right(c)) - px(c, p)).norm();
    REQUIRE(shown == Approx(50).epsilon(1e-6));
  }
}

TEST_CASE("document camera round trip keeps the view", "[editor]") {
  for (bool ortho : {false, true}) {
    const view::Camera c = cam(ortho);
    view::Camera back;
    back.width = c.width;
    back.height = c.height;
    from_document_camera(to_document_camera(c), back);
    REQUIRE(back.orientation.angularDistance(c.orientation) < 1e-9);
    REQUIRE((back.target - c.target).norm() < 1e-12);
    REQUIRE(back.distance == Approx(c.distance));
    REQUIRE(back.orthographic == ortho);
    const Vector3d p(0.4, -0.3, 0.8);
    REQUIRE((px(back, p) - px(c, p)).norm() < 1e-6);
  }
  // A degenerate camera (eye on target) leaves the view unchanged instead of producing NaN.
  dfm::Camera d;
  d.position = d.target;
  view::Camera c = cam(false);
  from_document_camera(d, c);
  REQUIRE(c.orientation.coeffs().allFinite());
  REQUIRE(c.distance == 6);
}

TEST_CASE("recent files: most recent first, no duplicates, bounded", "[editor]") {
  std::vector<std::string> r;
  r = push_recent(r, "a");
  r = push_recent(r, "b");
  r = push_recent(r, "a");
  REQUIRE(r == std::vector<std::string>{"a", "b"});
  for (int i = 0; i < 20; ++i) r = push_recent(r, std::to_string(i), 5);
  REQUIRE(r.size() == 5);
  REQUIRE(r.front() == "19");
}
