#include "core/view/camera.h"

#include <algorithm>
#include <cmath>

namespace dfm::view {
namespace {
constexpr double kPi = 3.14159265358979323846;

// Shoemake: the pixel mapped onto a unit sphere that fills the smaller viewport side; outside it,
// the nearest point of its silhouette circle. Camera-space coordinates (y up).
Eigen::Vector3d arcball_point(const Camera& c, const Eigen::Vector2d& px) {
  const double r = 0.5 * std::min(c.width, c.height);
  Eigen::Vector3d p((px.x() - 0.5 * c.width) / r, (0.5 * c.height - px.y()) / r, 0.0);
  const double d2 = p.x() * p.x() + p.y() * p.y();
  if (d2 <= 1.0)
    p.z() = std::sqrt(1.0 - d2);
  else
    p /= std::sqrt(d2);
  return p;
}
}  // namespace

Eigen::Vector3d camera_forward(const Camera& c) { return c.orientation * Eigen::Vector3d(0, 0, -1); }
Eigen::Vector3d camera_right(const Camera& c) { return c.orientation * Eigen::Vector3d(1, 0, 0); }
Eigen::Vector3d camera_up(const Camera& c) { return c.orientation * Eigen::Vector3d(0, 1, 0); }
Eigen::Vector3d camera_eye(const Camera& c) { return c.target - c.distance * camera_forward(c); }

double half_height_at_target(const Camera& c) {
  return c.distance * std::tan(0.5 * c.fov_y_deg * kPi / 180.0);
}

double near_plane(const Camera& c) {
  if (c.orthographic) return -4.0 * c.scene_radius;  // ortho: the eye may sit inside the scene
  return std::max(1e-4 * c.distance, std::min(0.05 * c.distance, c.distance - 2.0 * c.scene_radius));
}

double far_plane(const Camera& c) { return c.distance + 4.0 * c.scene_radius + c.distance; }

Eigen::Matrix4d view_matrix(const Camera& c) {
  const Eigen::Matrix3d Rt = c.orientation.toRotationMatrix().transpose();
  Eigen::Matrix4d V = Eigen::Matrix4d::Identity();
  V.topLeftCorner<3, 3>() = Rt;
  V.topRightCorner<3, 1>() = -Rt * camera_eye(c);
  return V;
}

Eigen::Matrix4d projection_matrix(const Camera& c) {
  const double aspect = c.width / std::max(1.0, c.height);
  const double n = near_plane(c), f = far_plane(c);
  Eigen::Matrix4d P = Eigen::Matrix4d::Zero();
  if (c.orthographic) {
    const double t = half_height_at_target(c), r = t * aspect;
    P(0, 0) = 1.0 / r;
    P(1, 1) = 1.0 / t;
    P(2, 2) = -2.0 / (f - n);
    P(2, 3) = -(f + n) / (f - n);
    P(3, 3) = 1.0;
  } else {
    const double t = std::tan(0.5 * c.fov_y_deg * kPi / 180.0);
    P(0, 0) = 1.0 / (t * aspect);
    P(1, 1) = 1.0 / t;
    P(2, 2) = -(f + n) / (f - n);
    P(2, 3) = -2.0 * f * n / (f - n);
    P(3, 2) = -1.0;
  }
  return P;
}

Eigen::Vector3d project_to_pixel(const Camera& c, const Eigen::Vector3d& p) {
  const Eigen::Vector4d clip = projection_matrix(c) * view_matrix(c) * p.homogeneous();
  const Eigen::Vector3d ndc = clip.head<3>() / clip.w();
  return {(ndc.x() + 1.0) * 0.5 * c.width, (1.0 - ndc.y()) * 0.5 * c.height, ndc.z()};
}

Ray pixel_ray(const Camera& c, double px, double py) {
  // Offsets on the target plane, in camera units.
  const double h = half_height_at_target(c);
  const double sx = (2.0 * px / c.width - 1.0) * h * (c.width / std::max(1.0, c.height));
  const double sy = (1.0 - 2.0 * py / c.height) * h;
  const Eigen::Vector3d on_plane = c.target + sx * camera_right(c) + sy * camera_up(c);
  Ray ray;
  if (c.orthographic) {
    ray.direction = camera_forward(c);
    ray.origin = on_plane - (c.distance + 2.0 * c.scene_radius) * ray.direction;
  } else {
    ray.origin = camera_eye(c);
    ray.direction = (on_plane - ray.origin).normalized();
  }
  return ray;
}

Eigen::Vector3d pixel_on_target_plane(const Camera& c, double px, double py) {
  return pixel_on_plane_through(c, c.target, px, py);
}

Eigen::Vector3d pixel_on_plane_through(const Camera& c, const Eigen::Vector3d& p, double px, double py) {
  const Eigen::Vector3d f = camera_forward(c);
  if (!c.orthographic && (p - camera_eye(c)).dot(f) <= 1e-9) return p;
  const Ray r = pixel_ray(c, px, py);
  return r.origin + (p - r.origin).dot(f) / r.direction.dot(f) * r.direction;
}

void arcball_orbit(Camera& c, const Eigen::Vector2d& from_px, const Eigen::Vector2d& to_px) {
  const Eigen::Vector3d a = arcball_point(c, from_px), b = arcball_point(c, to_px);
  if ((a - b).squaredNorm() < 1e-18) return;
  // The scene turns by q (camera space) = the camera turns by q^-1 about the target.
  const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(a, b);
  c.orientation = (c.orientation * q.conjugate()).normalized();
}

void turntable_orbit(Camera& c, double yaw, double pitch) {
  const Eigen::Quaterniond qy(Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitY()));
  const Eigen::Quaterniond qp(Eigen::AngleAxisd(-pitch, camera_right(c)));
  c.orientation = (qy * qp * c.orientation).normalized();
}

void pan(Camera& c, const Eigen::Vector2d& delta_px) {
  const double world_per_px = 2.0 * half_height_at_target(c) / std::max(1.0, c.height);
  c.target -= world_per_px * (delta_px.x() * camera_right(c) - delta_px.y() * camera_up(c));
}

void zoom_to_cursor(Camera& c, double factor, const Eigen::Vector2d& cursor_px) {
  if (!(factor > 0)) return;
  // Scaling the whole camera about the point p under the cursor keeps p's image fixed (a homothety
  // centred at p with unchanged orientation and field of view).
  const Eigen::Vector3d p = pixel_on_target_plane(c, cursor_px.x(), cursor_px.y());
  const double d = std::clamp(c.distance * factor, 1e-4 * c.scene_radius, 1e3 * c.scene_radius);
  const double k = d / c.distance;
  c.target = p + k * (c.target - p);
  c.distance = d;
}

void frame_sphere(Camera& c, const Eigen::Vector3d& center, double radius) {
  radius = std::max(radius, 1e-9);
  const double half_fov_y = 0.5 * c.fov_y_deg * kPi / 180.0;
  const double aspect = c.width / std::max(1.0, c.height);
  const double half_fov_x = std::atan(std::tan(half_fov_y) * aspect);
  const double half_fov = std::min(half_fov_y, half_fov_x);
  c.target = center;
  // 8% margin; the ortho view shows half_height_at_target, which then also covers the sphere.
  c.distance = 1.08 * radius / std::sin(half_fov);
  c.scene_radius = std::max(c.scene_radius, radius);
}

void frame_box(Camera& c, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  frame_sphere(c, 0.5 * (lo + hi), 0.5 * (hi - lo).norm());
}

void set_view_preset(Camera& c, ViewPreset preset) {
  using Q = Eigen::Quaterniond;
  using AA = Eigen::AngleAxisd;
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY();
  switch (preset) {
    case ViewPreset::Front: c.orientation = Q::Identity(); break;                    // looks down -z
    case ViewPreset::Back: c.orientation = Q(AA(kPi, Y)); break;
    case ViewPreset::Right: c.orientation = Q(AA(0.5 * kPi, Y)); break;              // looks down -x
    case ViewPreset::Left: c.orientation = Q(AA(-0.5 * kPi, Y)); break;
    case ViewPreset::Top: c.orientation = Q(AA(-0.5 * kPi, X)); break;               // looks down -y
    case ViewPreset::Bottom: c.orientation = Q(AA(0.5 * kPi, X)); break;
    case ViewPreset::Iso: c.orientation = Q(AA(kPi / 6, Y)) * Q(AA(-kPi / 9, X)); break;
  }
}

const char* view_preset_name(ViewPreset preset) {
  switch (preset) {
    case ViewPreset::Front: return "Front";
    case ViewPreset::Back: return "Back";
    case ViewPreset::Left: return "Left";
    case ViewPreset::Right: return "Right";
    case ViewPreset::Top: return "Top";
    case ViewPreset::Bottom: return "Bottom";
    case ViewPreset::Iso: return "Iso";
  }
  return "?";
}

}  // namespace dfm::view
