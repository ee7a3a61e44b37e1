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

GizmoShape gizmo_shape(const view::Camera& cam, const Eigen::Vector3d& origin, bool rotate_mode,
                       const GizmoLayout& L, const GizmoBone* bone) {
  GizmoShape g;
  if (bone && (bone->b - bone->a).norm() > 0) {
    g.has_bone = true;
    g.bone = *bone;
    const Eigen::Vector3d mid = 0.5 * (bone->a + bone->b), u = (bone->b - bone->a).normalized();
    const Eigen::Vector3d e1 = u.unitOrthogonal(), e2 = u.cross(e1);
    const Eigen::Vector3d side = u.cross(view::camera_forward(cam));
    const Eigen::Vector3d n = side.norm() > 1e-9 ? side.normalized() : e1;  // across the bone on screen
    const double s = world_per_pixels(cam, bone->b, L.stretch_px);
    g.stretch_handle = {bone->b + s * n, bone->b + s * u, bone->b - s * n, bone->b - s * u};
    const double r = world_per_pixels(cam, mid, L.twist_px);
    for (int i = 0; i < 48; ++i) {
      const double t = 2 * M_PI * i / 48;
      g.twist_ring.push_back(mid + r * (std::cos(t) * e1 + std::sin(t) * e2));
    }
  }
  g.origin = origin;
  g.rotate = rotate_mode;
  g.pick_px = L.pick_px;
  g.ring_normal = -view::camera_forward(cam);
  g.ring_px = L.ring_px;
  g.ring_radius = world_per_pixels(cam, origin, L.ring_px);
  const double len = world_per_pixels(cam, origin, L.axis_px);
  const double a = 0.25 * len, b = a + len * L.plane_px / L.axis_px;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d u = Eigen::Vector3d::Unit((k + 1) % 3), v = Eigen::Vector3d::Unit((k + 2) % 3);
    g.axis_end[k] = origin + len * Eigen::Vector3d::Unit(k);
    g.plane[k] = {origin + a * u + a * v, origin + b * u + a * v, origin + b * u + b * v, origin + a * u + b * v};
  }
  return g;
}

// The bone's part under the cursor, if any (twist ring in rotate mode, stretch handle else).
GizmoPart bone_hit(const view::Camera& cam, const GizmoShape& g, const Eigen::Vector2d& px) {
  if (!g.has_bone) return GizmoPart::None;
  if (!g.rotate) {  // within the diamond's image, or pick_px of its edges
    const Eigen::Vector2d c = image(cam, g.bone.b);
    double reach = 0;
    for (const Eigen::Vector3d& p : g.stretch_handle) reach = std::max(reach, (image(cam, p) - c).norm());
    return (px - c).norm() <= reach + g.pick_px ? GizmoPart::Stretch : GizmoPart::None;
  }
  const size_t n = g.twist_ring.size();
  for (size_t i = 0; i < n; ++i)
    if (segment_distance(image(cam, g.twist_ring[i]), image(cam, g.twist_ring[(i + 1) % n]), px) <= g.pick_px)
      return GizmoPart::TwistRing;
  return GizmoPart::None;
}

GizmoPart gizmo_hit(const view::Camera& cam, const GizmoShape& g, const Eigen::Vector2d& px) {
  const Eigen::Vector2d o = image(cam, g.origin);
  if (const GizmoPart b = bone_hit(cam, g, px); b != GizmoPart::None) return b;
  if (g.rotate) {
    const double r = (px - o).norm();
    if (std::abs(r - g.ring_px) <= g.pick_px) return GizmoPart::Ring;
    if (r < g.ring_px) return GizmoPart::Trackball;
    return GizmoPart::None;
  }
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d u = Eigen::Vector3d::Unit((k + 1) % 3), v = Eigen::Vector3d::Unit((k + 2) % 3);
    // Point in the plane under the cursor, in (u, v) coordinates, against the square's corners.
    Eigen::Vector3d hit;
    if (!plane_point(view::pixel_ray(cam, px.x(), px.y()), g.origin, Eigen::Vector3d::Unit(k), hit)) continue;
    const double a = (hit - g.origin).dot(u), b = (hit - g.origin).dot(v);
    const double lo = (g.plane[k][0] - g.origin).dot(u), hi = (g.plane[k][2] - g.origin).dot(u);
    if (a >= lo && a <= hi && b >= lo && b <= hi) return static_cast<GizmoPart>(int(GizmoPart::PlaneYZ) + k);
  }
  GizmoPart best = GizmoPart::None;
  double best_d = g.pick_px;
  for (int k = 0; k < 3; ++k) {
    const double d = segment_distance(o, image(cam, g.axis_end[k]), px);
    if (d <= best_d) {
      best_d = d;
      best = static_cast<GizmoPart>(int(GizmoPart::AxisX) + k);
    }
  }
  return best;
}

GizmoPart gizmo_hit(const view::Camera& cam, const Eigen::Vector3d& origin, bool rotate_mode,
                    const Eigen::Vector2d& px, const GizmoLayout& L) {
  return gizmo_hit(cam, gizmo_shape(cam, origin, rotate_mode, L), px);
}

Eigen::Vector4f gizmo_hover_color() { return {1.0f, 0.9f, 0.3f, 1.0f}; }

// The bone's twist ring, or its stretch handle: a diamond at its end in a plane through the bone.
void add_bone_lines(const GizmoShape& g, GizmoPart hover, std::vector<gl::OverlayVertex>& l) {
  if (!g.has_bone) return;
  const Eigen::Vector4f orange(1.0f, 0.55f, 0.15f, 1.0f);
  if (g.rotate) {
    const Eigen::Vector4f c = hover == GizmoPart::TwistRing ? gizmo_hover_color() : orange;
    for (size_t i = 0; i < g.twist_ring.size(); ++i) {
      l.push_back(gl::overlay_vertex(g.twist_ring[i], c));
      l.push_back(gl::overlay_vertex(g.twist_ring[(i + 1) % g.twist_ring.size()], c));
    }
    return;
  }
  const Eigen::Vector4f c = hover == GizmoPart::Stretch ? gizmo_hover_color() : orange;
  for (int e = 0; e < 4; ++e) {
    l.push_back(gl::overlay_vertex(g.stretch_handle[e], c));
    l.push_back(gl::overlay_vertex(g.stretch_handle[(e + 1) % 4], c));
  }
}

std::vector<gl::OverlayVertex> gizmo_lines(const GizmoShape& g, GizmoPart hover) {
  auto hl = [&](GizmoPart p, const Eigen::Vector4f& c) { return hover == p ? gizmo_hover_color() : c; };
  std::vector<gl::OverlayVertex> l;
  if (g.rotate) {
    l = gl::circle_lines(g.origin, g.ring_normal, g.ring_radius, hl(GizmoPart::Ring, {0.95f, 0.95f, 1.0f, 1.0f}), 72);
    const Eigen::Vector4f disc = hover == GizmoPart::Trackball ? Eigen::Vector4f(1, 0.9f, 0.3f, 0.35f)
                                                               : Eigen::Vector4f(1, 1, 1, 0.12f);
    for (const auto& v : gl::circle_lines(g.origin, g.ring_normal, 0.98 * g.ring_radius, disc, 72)) l.push_back(v);
    add_bone_lines(g, hover, l);  // over the disc
    return l;
  }
  const Eigen::Vector4f ax[3] = {{0.95f, 0.3f, 0.3f, 1.0f}, {0.4f, 0.9f, 0.35f, 1.0f}, {0.35f, 0.55f, 1.0f, 1.0f}};
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector4f c = hl(GizmoPart(int(GizmoPart::AxisX) + k), ax[k]);
    l.push_back(gl::overlay_vertex(g.origin, c));
    l.push_back(gl::overlay_vertex(g.axis_end[k], c));
    const Eigen::Vector4f pc = hl(GizmoPart(int(GizmoPart::PlaneYZ) + k), {ax[k].x(), ax[k].y(), ax[k].z(), 0.7f});
    for (int e = 0; e < 4; ++e) {
      l.push_back(gl::overlay_vertex(g.plane[k][e], pc));
      l.push_back(gl::overlay_vertex(g.plane[k][(e + 1) % 4], pc));
    }
  }
  add_bone_lines(g, hover, l);
  return l;
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

double gizmo_twist(const view::Camera& cam, const GizmoShape& g, const Eigen::Vector2d& from_px,
                   const Eigen::Vector2d& to_px) {
  if (!g.has_bone) return 0;
  const Eigen::Vector2d o = image(cam, 0.5 * (g.bone.a + g.bone.b));
  const Eigen::Vector2d a = from_px - o, b = to_px - o;
  if (a.norm() < 1e-9 || b.norm() < 1e-9) return 0;
  // As the view ring: counter-clockwise on screen (y down) turns positively about the axis toward the
  // viewer; the bone's axis turns the same way where it points at the viewer, the other way else.
  const double angle = -std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
  const Eigen::Vector3d u = (g.bone.b - g.bone.a).normalized();
  return u.dot(-view::camera_forward(cam)) >= 0 ? angle : -angle;
}

double gizmo_stretch(const view::Camera& cam, const GizmoShape& g, const Eigen::Vector2d& from_px,
                     const Eigen::Vector2d& to_px) {
  if (!g.has_bone || !(g.bone.rest_length > 0)) return 0;
  const Eigen::Vector3d u = (g.bone.b - g.bone.a).normalized();
  const view::Ray r0 = view::pixel_ray(cam, from_px.x(), from_px.y());
  const view::Ray r1 = view::pixel_ray(cam, to_px.x(), to_px.y());
  return (axis_parameter(r1, g.bone.b, u) - axis_parameter(r0, g.bone.b, u)) / g.bone.rest_length;
}

}  // namespace dfm::editor
