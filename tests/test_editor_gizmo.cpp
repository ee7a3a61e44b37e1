// Gizmo drags, document camera conversion and the recent-files list: the editor's CPU logic.
#include <cmath>
#include <vector>

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

namespace {
Vector3d at(const dfm::gl::OverlayVertex& v) { return Vector3d(v.position[0], v.position[1], v.position[2]); }
bool lit(const dfm::gl::OverlayVertex& v) {
  const Eigen::Vector4f h = gizmo_hover_color();
  return v.color[0] == h[0] && v.color[1] == h[1] && v.color[2] == h[2] && v.color[3] == h[3];
}
}  // namespace

// The Pose tool draws gizmo_lines(shape) and picks gizmo_hit(shape): one layout, checked here without
// a GL context. What is drawn is where it picks, and the part under the cursor is the one lit.
TEST_CASE("gizmo layout: the drawn axes and plane squares are where picking finds them", "[gizmo]") {
  for (bool ortho : {false, true}) {
    const view::Camera c = cam(ortho);
    const Vector3d o(0.1, -0.2, 0.3);
    const GizmoShape g = gizmo_shape(c, o, false);
    const std::vector<dfm::gl::OverlayVertex> lines = gizmo_lines(g, GizmoPart::None);
    REQUIRE(lines.size() == 2 * (3 + 3 * 4));  // per axis: its line and its square's 4 edges
    for (int k = 0; k < 3; ++k) {
      INFO("ortho " << ortho << " axis " << k);
      // The drawn axis runs from the origin to axis_end; near its tip it picks that axis.
      const Vector3d a0 = at(lines[10 * k]), a1 = at(lines[10 * k + 1]);
      REQUIRE((a0 - o).norm() < 1e-6);
      REQUIRE((a1 - g.axis_end[k]).norm() < 1e-6);
      REQUIRE(gizmo_hit(c, g, px(c, o + 0.9 * (a1 - o))) == GizmoPart(int(GizmoPart::AxisX) + k));
      // The drawn square: its 4 edges through the shape's corners, the centre picks the plane, a point
      // just beyond the far corner does not.
      Vector3d centre = Vector3d::Zero();
      for (int e = 0; e < 4; ++e) {
        REQUIRE((at(lines[10 * k + 2 + 2 * e]) - g.plane[k][e]).norm() < 1e-6);
        REQUIRE((at(lines[10 * k + 3 + 2 * e]) - g.plane[k][(e + 1) % 4]).norm() < 1e-6);
        centre += 0.25 * g.plane[k][e];
      }
      REQUIRE(gizmo_hit(c, g, px(c, centre)) == GizmoPart(int(GizmoPart::PlaneYZ) + k));
      REQUIRE(gizmo_hit(c, g, px(c, 0.9 * g.plane[k][0] + 0.1 * centre)) == GizmoPart(int(GizmoPart::PlaneYZ) + k));
      REQUIRE(gizmo_hit(c, g, px(c, g.plane[k][2] + 0.2 * (g.plane[k][2] - centre))) != GizmoPart(int(GizmoPart::PlaneYZ) + k));
      // The plane square lies in the plane normal to axis k.
      for (int e = 0; e < 4; ++e) REQUIRE(std::abs((g.plane[k][e] - o)[k]) < 1e-12);
    }
    // Hovering a part lights exactly its segments.
    for (int p = int(GizmoPart::AxisX); p <= int(GizmoPart::PlaneXY); ++p) {
      const std::vector<dfm::gl::OverlayVertex> l = gizmo_lines(g, GizmoPart(p));
      const bool plane = p >= int(GizmoPart::PlaneYZ);
      const int k = plane ? p - int(GizmoPart::PlaneYZ) : p - int(GizmoPart::AxisX);
      for (size_t i = 0; i < l.size(); ++i) {
        const int owner = int(i) / 10, slot = int(i) % 10;
        const bool expect = owner == k && (plane ? slot >= 2 : slot < 2);
        REQUIRE(lit(l[i]) == expect);
      }
    }
  }
}

TEST_CASE("gizmo layout: the drawn ring is ring_px on screen and picks as the ring; sized in pixels", "[gizmo]") {
  for (bool ortho : {false, true}) {
    view::Camera c = cam(ortho);
    const Vector3d o(0.1, -0.2, 0.3);
    const GizmoShape g = gizmo_shape(c, o, true);
    const std::vector<dfm::gl::OverlayVertex> lines = gizmo_lines(g, GizmoPart::Ring);
    REQUIRE(lines.size() == 4 * 72);  // the ring and the disc's rim, 72 segments each
    for (size_t i = 0; i < lines.size(); ++i) {
      const double r = (px(c, at(lines[i])) - px(c, o)).norm();
      if (i < 2 * 72) {  // the ring: lit, on its pixel radius, and picked as the ring
        REQUIRE(lit(lines[i]));
        REQUIRE(r == Approx(GizmoLayout{}.ring_px).epsilon(1e-4));
        REQUIRE(gizmo_hit(c, g, px(c, at(lines[i]))) == GizmoPart::Ring);
      } else {  // the disc's rim just inside
        REQUIRE_FALSE(lit(lines[i]));
        REQUIRE(r < GizmoLayout{}.ring_px);
      }
    }
    REQUIRE(gizmo_hit(c, g, px(c, o) + Vector2d(0.5 * g.ring_px, 0)) == GizmoPart::Trackball);
    // Zooming out keeps the gizmo's size on screen: the ring's radius, and in ortho the axes' tips.
    const Vector2d tip = px(c, gizmo_shape(c, o, false).axis_end[1]) - px(c, o);
    c.distance *= 7;
    const GizmoShape far = gizmo_shape(c, o, true);
    for (const auto& v : gizmo_lines(far, GizmoPart::None))
      REQUIRE((px(c, at(v)) - px(c, o)).norm() <= GizmoLayout{}.ring_px * (1 + 1e-4));
    REQUIRE((px(c, at(gizmo_lines(far, GizmoPart::None)[0])) - px(c, o)).norm() == Approx(GizmoLayout{}.ring_px).epsilon(1e-4));
    if (ortho) REQUIRE((px(c, gizmo_shape(c, o, false).axis_end[1]) - px(c, o) - tip).norm() < 1e-6);
  }
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

TEST_CASE("bone twist ring: picked where drawn; a drag turns the bone by the swept angle, right-handed about it",
          "[gizmo][stbs]") {
  for (bool ortho : {false, true}) {
    INFO("orthographic " << ortho);
    view::Camera c = cam(ortho);
    GizmoBone bone;
    bone.a = Vector3d(0.1, 0.0, 0.2);
    bone.b = bone.a + 0.8 * view::camera_forward(c) * -1.0 + Vector3d(0.05, 0.02, 0);  // roughly toward the viewer
    bone.rest_length = 0.5;
    const GizmoShape g = gizmo_shape(c, bone.a, true, {}, &bone);
    REQUIRE(g.has_bone);
    REQUIRE(g.twist_ring.size() >= 24);
    const Vector3d u = (bone.b - bone.a).normalized(), mid = 0.5 * (bone.a + bone.b);
    for (const Vector3d& p : g.twist_ring) CHECK(std::abs((p - mid).dot(u)) < 1e-12);  // about the axis
    CHECK(gizmo_hit(c, g, px(c, g.twist_ring[5])) == GizmoPart::TwistRing);
    CHECK(gizmo_hit(c, g, px(c, mid)) != GizmoPart::TwistRing);
    // A quarter turn of the ring's points about the axis, right-handed, is a twist of +90 degrees.
    const Vector3d from = g.twist_ring[0];
    const Vector3d to = mid + Eigen::AngleAxisd(M_PI / 2, u) * (from - mid);
    CHECK(gizmo_twist(c, g, px(c, from), px(c, to)) == Approx(M_PI / 2).margin(0.05));
    CHECK(gizmo_twist(c, g, px(c, to), px(c, from)) == Approx(-M_PI / 2).margin(0.05));
    // The bone pointing away from the viewer: the same world turn, the same twist.
    GizmoBone away = bone;
    std::swap(away.a, away.b);
    const GizmoShape h = gizmo_shape(c, away.a, true, {}, &away);
    const Vector3d w = (away.b - away.a).normalized();
    const Vector3d to_w = mid + Eigen::AngleAxisd(M_PI / 3, w) * (from - mid);
    CHECK(gizmo_twist(c, h, px(c, from), px(c, to_w)) == Approx(M_PI / 3).margin(0.05));
  }
}

TEST_CASE("bone stretch handle: picked at the bone's end; a drag along it changes the stretch by distance over rest length",
          "[gizmo][stbs]") {
  for (bool ortho : {false, true}) {
    INFO("orthographic " << ortho);
    const view::Camera c = cam(ortho);
    GizmoBone bone;
    bone.a = Vector3d(-0.4, 0.1, 0.0);
    bone.b = Vector3d(0.4, 0.3, 0.1);
    bone.rest_length = 0.5;
    const GizmoShape g = gizmo_shape(c, bone.a, false, {}, &bone);
    CHECK(gizmo_hit(c, g, px(c, bone.b)) == GizmoPart::Stretch);
    for (const Vector3d& p : g.stretch_handle) CHECK(gizmo_hit(c, g, px(c, p)) == GizmoPart::Stretch);  // drawn = picked
    CHECK(gizmo_hit(c, g, px(c, bone.a)) != GizmoPart::Stretch);
    const Vector3d u = (bone.b - bone.a).normalized();
    // 0.2 along the bone from its end: +0.4 of a 0.5 rest length; a sideways drag changes nothing.
    CHECK(gizmo_stretch(c, g, px(c, bone.b), px(c, bone.b + 0.2 * u)) == Approx(0.4).margin(1e-6));
    const Vector3d across = u.cross(view::camera_forward(c)).normalized();
    // (Exactly none in orthographic views; in perspective the ray's closest point moves a little.)
    CHECK(std::abs(gizmo_stretch(c, g, px(c, bone.b), px(c, bone.b + 0.2 * across))) < (ortho ? 1e-6 : 0.04));
    // Without a bone the gizmo has neither part.
    const GizmoShape plain = gizmo_shape(c, bone.a, false);
    CHECK(gizmo_hit(c, plain, px(c, bone.b)) != GizmoPart::Stretch);
    CHECK(gizmo_stretch(c, plain, px(c, bone.b), px(c, bone.b + 0.2 * u)) == 0.0);
  }
}
