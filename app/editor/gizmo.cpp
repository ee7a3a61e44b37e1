#include "app/editor/gizmo.h"

#include <algorithm>
#include <cmath>

namespace dfm::editor {
namespace {

Eigen::Vector2d image(const view::Camera& cam, const Eigen::Vector3d& p) {
  return view::project_to_pixel(cam, p).head<2>();
}

double segment_distance(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  const Eigen::Vector2d ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

// Closest point on the line origin + s*axis to the ray: the parameter s.
double axis_parameter(const view::Ray& r, const Eigen::Vector3d& origin, const Eigen::Vector3d& axis) {
  const Eigen::Vector3d w = origin - r.origin;
  const double b = axis.dot(r.direction), d = axis.dot(w), e = r.direction.dot(w);
  const double denom = 1.0 - b * b;  // both unit
  if (denom < 1e-9) return 0.0;       // axis points at the viewer: no motion
  return (b * e - d) / denom;
}

bool plane_point(const view::Ray& r, const Eigen::Vector3d& origin, const Eigen::Vector3d& n,
                 Eigen::Vector3d& out) {
  const double dn = r.direction.dot(n);
  if (std::abs(dn) < 1e-9) return false;
  out = r.origin + ((origin - r.origin).dot(n) / dn) * r.direction;
  return true;
}

}  // namespace

double world_per_pixels(const view::Camera& cam, const Eigen::Vector3d& p, double px) {
  double depth = cam.distance;
  if (!cam.orthographic) depth = std::max(1e-9, (p - view::camera_eye(cam)).dot(view::camera_forward(cam)));
  const double half_h = depth * std::tan(0.5 * cam.fov_y_deg * M_PI / 180.0);
  return px * 2.0 * half_h / std::max(1.0, cam.height);
}

GizmoPart gizmo_hit(const view::Camera& cam, const Eigen::Vector3d& origin, bool rotate_mode,
                    const Eigen::Vector2d& px, const GizmoLayout& L) {
  const Eigen::Vector2d o = image(cam, origin);
  if (rotate_mode) {
    const double r = (px - o).norm();
    if (std::abs(r - L.ring_px) <= L.pick_px) return GizmoPart::Ring;
    if (r < L.ring_px) return GizmoPart::Trackball;
    return GizmoPart::None;
  }
  const double len = world_per_pixels(cam, origin, L.axis_px);
  const Eigen::Vector3d axes[3] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
  // Planes first: their squares sit between the axes.
  const double p0 = 0.25 * len, p1 = p0 + len * L.plane_px / L.axis_px;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d u = axes[(k + 1) % 3], v = axes[(k + 2) % 3];
    // Point in the plane under the cursor, in (u, v) coordinates.
    Eigen::Vector3d hit;
    if (!plane_point(view::pixel_ray(cam, px.x(), px.y()), origin, axes[k], hit)) continue;
    const double a = (hit - origin).dot(u), b = (hit - origin).dot(v);
    if (a >= p0 && a <= p1 && b >= p0 && b <= p1) return static_cast<GizmoPart>(int(GizmoPart::PlaneYZ) + k);
  }
  GizmoPart best = GizmoPart::None;
  double best_d = L.pick_px;
  for (int k = 0; k < 3; ++k) {
    const double d = segment_distance(o, image(cam, origin + len * axes[k]), px);
    if (d <= best_d) {
      best_d = d;
      best = static_cast<GizmoPart>(int(GizmoPart::AxisX) + k);
    }
  }
  return best;
}

Eigen::Vector3d gizmo_translation(const view::Camera& cam, const Eigen::Vector3d& origin, GizmoPart part,
                                  const Eigen::Vector2d& from_px, const Eigen::Vector2d& to_px) {
  const view::Ray r0 = view::pixel_ray(cam, from_px.x(), from_px.y());
  const view::Ray r1 = view::pixel_ray(cam, to_px.x(), to_px.y());
  if (part >= GizmoPart::AxisX && part <= GizmoPart::AxisZ) {
    const Eigen::Vector3d axis = Eigen::Vector3d::Unit(int(part) - int(GizmoPart::AxisX));
    return (axis_parameter(r1, origin, axis) - axis_parameter(r0, origin, axis)) * axis;
  }
  if (part >= GizmoPart::PlaneYZ && part <= GizmoPart::PlaneXY) {
    const Eigen::Vector3d n = Eigen::Vector3d::Unit(int(part) - int(GizmoPart::PlaneYZ));
    Eigen::Vector3d a, b;
    if (plane_point(r0, origin, n, a) && plane_point(r1, origin, n, b)) return b - a;
  }
  return Eigen::Vector3d::Zero();
}

Eigen::Quaterniond gizmo_rotation(const view::Camera& cam, const Eigen::Vector3d& origin, GizmoPart part,
                                  const Eigen::Vector2d& from_px, const Eigen::Vector2d& to_px,
                                  const GizmoLayout& L) {
  const Eigen::Vector2d o = image(cam, origin);
  const Eigen::Vector2d a = from_px - o, b = to_px - o;
  if (part == GizmoPart::Ring) {
    if (a.norm() < 1e-9 || b.norm() < 1e-9) return Eigen::Quaterniond::Identity();
    // Screen y points down: a counter-clockwise turn on screen is a negative cross product here.
    const double angle = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
    // Counter-clockwise on screen = positive about the axis pointing at the viewer.
    return Eigen::Quaterniond(Eigen::AngleAxisd(-angle, -view::camera_forward(cam)));
  }
  if (part == GizmoPart::Trackball) {
    auto sphere = [&](const Eigen::Vector2d& s) {
      Eigen::Vector3d p(s.x() / L.ring_px, -s.y() / L.ring_px, 0.0);
      const double d2 = p.head<2>().squaredNorm();
      if (d2 <= 1.0) p.z() = std::sqrt(1.0 - d2); else p /= std::sqrt(d2);
      return p;
    };
    const Eigen::Vector3d pa = sphere(a), pb = sphere(b);
    if ((pa - pb).norm() < 1e-12) return Eigen::Quaterniond::Identity();
    const Eigen::Quaterniond q_cam = Eigen::Quaterniond::FromTwoVectors(pa, pb);
    // Camera-space rotation -> world: conjugate by the camera orientation.
    return cam.orientation * q_cam * cam.orientation.conjugate();
  }
  return Eigen::Quaterniond::Identity();
}

}  // namespace dfm::editor
