// The orbit camera's gestures, checked through projection (independent of how they are implemented).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/view/camera.h"
#include "core/view/colormap.h"

using namespace dfm::view;
using Eigen::Vector2d;
using Eigen::Vector3d;

static Camera sample_camera(bool ortho) {
  Camera c;
  c.width = 800;
  c.height = 600;
  c.target = Vector3d(0.3, -0.2, 0.5);
  c.distance = 4.0;
  c.orthographic = ortho;
  c.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Vector3d(1, 2, 0.5).normalized()));
  return c;
}

TEST_CASE("target projects to the viewport centre; eye is distance away", "[camera]") {
  for (bool ortho : {false, true}) {
    Camera c = sample_camera(ortho);
    const Vector3d s = project_to_pixel(c, c.target);
    REQUIRE(s.x() == Approx(400).margin(1e-9));
    REQUIRE(s.y() == Approx(300).margin(1e-9));
    REQUIRE((camera_eye(c) - c.target).norm() == Approx(4.0));
    REQUIRE(s.z() > -1.0);
    REQUIRE(s.z() < 1.0);
  }
}

TEST_CASE("view matrix is a rigid transform mapping the eye to the origin", "[camera]") {
  Camera c = sample_camera(false);
  const Eigen::Matrix4d V = view_matrix(c);
  const Eigen::Matrix3d R = V.topLeftCorner<3, 3>();
  REQUIRE((R * R.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-12);
  REQUIRE(R.determinant() == Approx(1.0));
  REQUIRE((V * camera_eye(c).homogeneous()).head<3>().norm() < 1e-12);
  // The target sits on the -z axis of camera space.
  const Vector3d t = (V * c.target.homogeneous()).head<3>();
  REQUIRE(t.x() == Approx(0).margin(1e-12));
  REQUIRE(t.y() == Approx(0).margin(1e-12));
  REQUIRE(t.z() == Approx(-4.0));
}

TEST_CASE("pixel rays pass through the points that project to that pixel", "[camera]") {
  for (bool ortho : {false, true}) {
    Camera c = sample_camera(ortho);
    const Vector3d p(0.7, 0.1, 0.2);
    const Vector3d s = project_to_pixel(c, p);
    const Ray r = pixel_ray(c, s.x(), s.y());
    REQUIRE(r.direction.norm() == Approx(1.0));
    // distance of p from the ray line
    const Vector3d w = p - r.origin;
    REQUIRE((w - w.dot(r.direction) * r.direction).norm() < 1e-9);
    REQUIRE(w.dot(r.direction) > 0);  // p is in front of the ray origin
  }
}

TEST_CASE("arcball keeps the distance, turns the front of the scene with the cursor, and undoes", "[camera]") {
  Camera c = sample_camera(false);
  const Camera c0 = c;
  const Vector3d front = c.target - 0.5 * camera_forward(c);  // between target and eye
  const double x0 = project_to_pixel(c, front).x();
  arcball_orbit(c, Vector2d(400, 300), Vector2d(500, 300));
  REQUIRE((camera_eye(c) - c.target).norm() == Approx(4.0));
  REQUIRE((c.target - c0.target).norm() < 1e-12);
  REQUIRE(project_to_pixel(c, front).x() > x0 + 1.0);  // dragging right drags the near side right
  REQUIRE(std::abs(c.orientation.norm() - 1.0) < 1e-12);
  arcball_orbit(c, Vector2d(500, 300), Vector2d(400, 300));
  REQUIRE(c.orientation.angularDistance(c0.orientation) < 1e-9);
}

TEST_CASE("arcball: a drag across the whole ball at the centre turns by 90 degrees", "[camera]") {
  Camera c = sample_camera(false);
  const Camera c0 = c;
  // From the centre to the silhouette (radius = half the smaller side) is a quarter turn.
  arcball_orbit(c, Vector2d(400, 300), Vector2d(400, 0));
  REQUIRE(c.orientation.angularDistance(c0.orientation) == Approx(M_PI / 2).epsilon(1e-9));
}

TEST_CASE("pan moves the target's image by exactly the cursor motion", "[camera]") {
  for (bool ortho : {false, true}) {
    Camera c = sample_camera(ortho);
    const Vector3d p = c.target;  // a world point at the target's depth
    pan(c, Vector2d(37, -12));
    const Vector3d s = project_to_pixel(c, p);
    REQUIRE(s.x() == Approx(400 + 37).margin(1e-6));
    REQUIRE(s.y() == Approx(300 - 12).margin(1e-6));
    REQUIRE(c.distance == Approx(4.0));
  }
}

TEST_CASE("zoom to cursor keeps the point under the cursor fixed", "[camera]") {
  for (bool ortho : {false, true}) {
    Camera c = sample_camera(ortho);
    const Vector2d cursor(620, 130);
    const Vector3d p = pixel_on_target_plane(c, cursor.x(), cursor.y());
    zoom_to_cursor(c, 0.5, cursor);
    REQUIRE(c.distance == Approx(2.0));
    const Vector3d s = project_to_pixel(c, p);
    REQUIRE(s.x() == Approx(cursor.x()).margin(1e-6));
    REQUIRE(s.y() == Approx(cursor.y()).margin(1e-6));
    // And things near the cursor spread apart (it is a zoom in).
    const Vector3d q = p + 0.1 * camera_right(c);
    REQUIRE(project_to_pixel(c, q).x() - cursor.x() > 0);
  }
}

TEST_CASE("pixel_on_plane_through: the point under the cursor at p's depth, off the view axis too", "[camera]") {
  for (bool ortho : {false, true}) {
    const Camera c = sample_camera(ortho);
    const Vector3d p = c.target + 0.7 * camera_right(c) - 0.4 * camera_up(c) + 0.5 * camera_forward(c);
    const Vector3d at = project_to_pixel(c, p);
    CHECK((pixel_on_plane_through(c, p, at.x(), at.y()) - p).norm() < 1e-9);  // under its own pixel: p
    const Vector2d cursor(at.x() + 75, at.y() - 40);
    const Vector3d q = pixel_on_plane_through(c, p, cursor.x(), cursor.y());
    const Vector3d s = project_to_pixel(c, q);
    CHECK(s.x() == Approx(cursor.x()).margin(1e-6));
    CHECK(s.y() == Approx(cursor.y()).margin(1e-6));
    CHECK(std::abs((q - p).dot(camera_forward(c))) < 1e-9);
  }
  const Camera c = sample_camera(false);  // behind the eye: p stays
  const Vector3d behind = camera_eye(c) - camera_forward(c);
  CHECK(pixel_on_plane_through(c, behind, 10, 10) == behind);
}

TEST_CASE("frame fits every corner of the box inside the viewport, perspective and ortho", "[camera]") {
  for (bool ortho : {false, true}) {
    Camera c = sample_camera(ortho);
    const Vector3d lo(-3, 10, 2), hi(5, 12, 9);
    frame_box(c, lo, hi);
    REQUIRE((c.target - 0.5 * (lo + hi)).norm() < 1e-12);
    double max_extent = 0;
    for (int k = 0; k < 8; ++k) {
      const Vector3d corner((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(), (k & 4) ? hi.z() : lo.z());
      const Vector3d s = project_to_pixel(c, corner);
      REQUIRE(s.x() >= 0);
      REQUIRE(s.x() <= 800);
      REQUIRE(s.y() >= 0);
      REQUIRE(s.y() <= 600);
      REQUIRE(s.z() > -1);
      REQUIRE(s.z() < 1);
      max_extent = std::max({max_extent, std::abs(s.x() - 400) / 400, std::abs(s.y() - 300) / 300});
    }
    // ...and not absurdly small: the box fills a good part of the view.
    REQUIRE(max_extent > 0.4);
  }
}

TEST_CASE("view presets look along the expected axes", "[camera]") {
  Camera c;
  set_view_preset(c, ViewPreset::Front);
  REQUIRE((camera_forward(c) - Vector3d(0, 0, -1)).norm() < 1e-12);
  set_view_preset(c, ViewPreset::Top);
  REQUIRE((camera_forward(c) - Vector3d(0, -1, 0)).norm() < 1e-12);
  REQUIRE((camera_up(c) - Vector3d(0, 0, -1)).norm() < 1e-12);
  set_view_preset(c, ViewPreset::Right);
  REQUIRE((camera_forward(c) - Vector3d(-1, 0, 0)).norm() < 1e-12);
  set_view_preset(c, ViewPreset::Left);
  REQUIRE((camera_forward(c) - Vector3d(1, 0, 0)).norm() < 1e-12);
  set_view_preset(c, ViewPreset::Back);
  REQUIRE((camera_forward(c) - Vector3d(0, 0, 1)).norm() < 1e-12);
  set_view_preset(c, ViewPreset::Iso);
  REQUIRE(camera_up(c).y() > 0.5);  // upright
  REQUIRE(camera_forward(c).y() < 0);  // looking down a little
}

TEST_CASE("turntable yaw keeps the world up axis in the vertical plane", "[camera]") {
  Camera c;
  set_view_preset(c, ViewPreset::Front);
  turntable_orbit(c, 0.7, 0.2);
  // Right axis stays horizontal: no roll.
  REQUIRE(std::abs(camera_right(c).y()) < 1e-12);
  REQUIRE((camera_eye(c) - c.target).norm() == Approx(c.distance));
}

TEST_CASE("projection depth is monotone and inside the clip range for the scene sphere", "[camera]") {
  for (bool ortho : {false, true}) {
    Camera c = sample_camera(ortho);
    c.scene_radius = 1.5;
    const Vector3d f = camera_forward(c);
    const double zn = project_to_pixel(c, c.target - 1.4 * f).z();
    const double z0 = project_to_pixel(c, c.target).z();
    const double zf = project_to_pixel(c, c.target + 1.4 * f).z();
    REQUIRE(zn < z0);
    REQUIRE(z0 < zf);
    REQUIRE(zn > -1);
    REQUIRE(zf < 1);
  }
}

// The colour map: the shader's formula, evaluated here from the #define text it receives, gives the
// legend's colours (one copy of the coefficients), blue for low weights, green in the middle, red for high.
TEST_CASE("turbo: the shader defines evaluate to the legend's colours", "[view]") {
  const std::vector<std::string> defs = dfm::view::turbo_shader_defines();
  REQUIRE(defs.size() == 6);
  auto numbers = [](const std::string& d) {
    std::vector<double> v;
    const char* p = d.c_str() + d.find('(') + 1;
    char* end = nullptr;
    for (double x = std::strtod(p, &end); end != p; x = std::strtod(p, &end)) {
      v.push_back(x);
      p = end;
      while (*p == ',' || *p == ' ') ++p;
    }
    return v;
  };
  for (double x : {0.0, 0.1, 0.37, 0.5, 0.81, 1.0}) {
    const Eigen::Vector3d c = dfm::view::turbo(x);
    for (int ch = 0; ch < 3; ++ch) {
      const std::vector<double> lo = numbers(defs[2 * ch]), hi = numbers(defs[2 * ch + 1]);
      REQUIRE(lo.size() == 4);
      REQUIRE(hi.size() == 2);
      const double shader = lo[0] + lo[1] * x + lo[2] * x * x + lo[3] * x * x * x + hi[0] * std::pow(x, 4) + hi[1] * std::pow(x, 5);
      CHECK(c[ch] == Approx(shader).margin(1e-9));
    }
  }
  CHECK(defs[0].rfind("TURBO_R vec4(", 0) == 0);
  CHECK(defs[5].rfind("TURBO_B2 vec2(", 0) == 0);
  const Eigen::Vector3d lo = dfm::view::turbo(-1), hi = dfm::view::turbo(2);  // clamped
  CHECK(lo == dfm::view::turbo(0));
  const Eigen::Vector3d blue = dfm::view::turbo(0.1), green = dfm::view::turbo(0.5), red = dfm::view::turbo(0.9);
  CHECK(blue.z() > std::max(blue.x(), blue.y()));  // low weights blue, middle green, high red
  CHECK(green.y() > std::max(green.x(), green.z()));
  CHECK(red.x() > std::max(red.y(), red.z()));
  CHECK(hi.x() > hi.z());
}
