// CPU picking: rays against triangles, inside points, and screen-space handle picking.
#include <catch2/catch.hpp>

#include "core/view/camera.h"
#include "core/view/picking.h"

using namespace dfm::view;
using Eigen::Vector2d;
using Eigen::Vector3d;

// Unit cube [0,1]^3, outward triangles.
static void cube(Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
  V.resize(8, 3);
  for (int k = 0; k < 8; ++k) V.row(k) << (k & 1), (k >> 1) & 1, (k >> 2) & 1;
  F.resize(12, 3);
  F << 0, 2, 1, 1, 2, 3,  // z=0
      4, 5, 6, 5, 7, 6,   // z=1
      0, 1, 4, 1, 5, 4,   // y=0
      2, 6, 3, 3, 6, 7,   // y=1
      0, 4, 2, 2, 4, 6,   // x=0
      1, 3, 5, 3, 7, 5;   // x=1
}

TEST_CASE("ray_triangle: hit point equals barycentric combination; misses outside", "[picking]") {
  const Vector3d a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  Ray r{Vector3d(0.5, 0.25, 3), Vector3d(0, 0, -1)};
  double t, u, v;
  REQUIRE(ray_triangle(r, a, b, c, t, u, v));
  REQUIRE(t == Approx(3));
  const Vector3d p = (1 - u - v) * a + u * b + v * c;
  REQUIRE((p - Vector3d(0.5, 0.25, 0)).norm() < 1e-12);
  r.origin = Vector3d(1.5, 1.5, 3);  // outside the hypotenuse
  REQUIRE_FALSE(ray_triangle(r, a, b, c, t, u, v));
  r.origin = Vector3d(0.5, 0.25, -3);  // triangle behind the ray
  REQUIRE_FALSE(ray_triangle(r, a, b, c, t, u, v));
}

TEST_CASE("pick_surface finds the nearest face of a cube and its nearest corner", "[picking]") {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  cube(V, F);
  const Ray r{Vector3d(0.9, 0.8, 5), Vector3d(0, 0, -1)};
  const SurfaceHit h = pick_surface(r, V, F);
  REQUIRE(h.hit());
  REQUIRE(h.t == Approx(4.0));
  REQUIRE(h.point.z() == Approx(1.0));
  REQUIRE(h.face >= 2);
  REQUIRE(h.face <= 3);  // a z=1 face
  REQUIRE(h.nearest_vertex == 7);  // corner (1,1,1)
  const Ray miss{Vector3d(2, 2, 5), Vector3d(0, 0, -1)};
  REQUIRE_FALSE(pick_surface(miss, V, F).hit());
}

TEST_CASE("pick_inside_point lands midway through the volume", "[picking]") {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  cube(V, F);
  const Ray r{Vector3d(0.3, 0.6, 5), Vector3d(0, 0, -1)};
  Vector3d p;
  REQUIRE(pick_inside_point(r, V, F, p));
  REQUIRE((p - Vector3d(0.3, 0.6, 0.5)).norm() < 1e-12);
  // Through the shared diagonal edge of two triangles: still the midpoint, not the edge twice.
  const Ray diag{Vector3d(0.5, 0.5, 5), Vector3d(0, 0, -1)};
  REQUIRE(pick_inside_point(diag, V, F, p));
  REQUIRE(p.z() == Approx(0.5));
}

TEST_CASE("screen-space picking of points and segments through the camera", "[picking]") {
  Camera c;
  c.width = 640;
  c.height = 480;
  c.distance = 5;
  Eigen::MatrixXd P(3, 3);
  P << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  const Vector3d s1 = project_to_pixel(c, P.row(1).transpose());
  REQUIRE(pick_projected_point(c, P, s1.head<2>() + Vector2d(3, -2), 8) == 1);
  REQUIRE(pick_projected_point(c, P, s1.head<2>() + Vector2d(30, 0), 8) == -1);
  // The midpoint of segment (0,2) picks that segment.
  const Vector3d m = project_to_pixel(c, Vector3d(0, 0.5, 0));
  std::vector<std::pair<int, int>> segs{{0, 1}, {0, 2}};
  REQUIRE(pick_projected_segment(c, P, segs, m.head<2>() + Vector2d(2, 0), 6) == 1);
  REQUIRE(pick_projected_segment(c, P, segs, Vector2d(5, 5), 6) == -1);
}

TEST_CASE("vertices_within returns exactly the vertices inside the brush", "[picking]") {
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 2, 0, 0.5, 0.5, 0;
  auto in = vertices_within(V, Vector3d::Zero(), 1.0);
  REQUIRE(in.size() == 3);
  for (auto& [i, d] : in) REQUIRE(d <= 1.0);
}
