#pragma once
// The posing gizmo's geometry, all CPU: one layout (GizmoShape) that the Pose tool both draws and
// picks, which part is under the cursor, and what a drag means (translation along an axis or in a
// plane, rotation by a trackball ring). Sized in pixels so it looks the same at any zoom.
#include <array>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/view/camera.h"
#include "render/overlay_geometry.h"

namespace dfm::editor {

enum class GizmoPart { None, AxisX, AxisY, AxisZ, PlaneYZ, PlaneXZ, PlaneXY, Ring, Trackball, TwistRing, Stretch };

struct GizmoLayout {
  double axis_px = 90;    // arrow length on screen
  double plane_px = 26;   // plane squares span [0.25, 0.25 + plane/axis] of the arrow
  double ring_px = 110;   // rotation ring radius
  double pick_px = 8;     // tolerance
  double twist_px = 40;   // a bone's twist ring radius
  double stretch_px = 8;  // half the diagonal of a bone's stretch handle
};

// A selected bone, posed: its joints as shown and its rest length (Jacobson 2013 ch. 6's twist and
// stretch get their own gizmo parts).
struct GizmoBone {
  Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
  double rest_length = 1;
};

// World length that appears `px` pixels long at `p`.
double world_per_pixels(const view::Camera& cam, const Eigen::Vector3d& p, double px);

// The gizmo at one origin for one camera, in world space: what is drawn and what is picked.
struct GizmoShape {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  bool rotate = false;  // rotate mode: the ring and its disc; else the axes and plane squares
  // Translate: axis k from the origin to axis_end[k]; the square in the plane normal to axis k (between
  // the other two axes u = k+1, v = k+2) has corners plane[k] = (a,a), (b,a), (b,b), (a,b) in (u, v).
  std::array<Eigen::Vector3d, 3> axis_end;
  std::array<std::array<Eigen::Vector3d, 4>, 3> plane;
  // Rotate: the ring about the view axis, its radius in pixels (picking) and in world units (drawing).
  Eigen::Vector3d ring_normal = Eigen::Vector3d::UnitZ();
  double ring_px = 0, ring_radius = 0;
  double pick_px = 8;  // picking tolerance
  // A bone's parts: rotate mode the twist ring about its axis at its middle (a closed polyline,
  // drawn and picked alike), translate mode the stretch handle at its end, dragged along it.
  bool has_bone = false;
  GizmoBone bone;
  std::vector<Eigen::Vector3d> twist_ring;
  std::array<Eigen::Vector3d, 4> stretch_handle;  // a diamond around the bone's end, in a plane through it
};
GizmoShape gizmo_shape(const view::Camera& cam, const Eigen::Vector3d& origin, bool rotate_mode,
                       const GizmoLayout& layout = {}, const GizmoBone* bone = nullptr);
// The part of `shape` under the cursor. Translate mode offers a bone's stretch handle, then axes and
// planes (planes first: their squares sit between the axes); rotate mode a bone's twist ring, then the
// view ring (turn about the view axis) and the disc inside it (trackball).
GizmoPart gizmo_hit(const view::Camera& cam, const GizmoShape& shape, const Eigen::Vector2d& px);
GizmoPart gizmo_hit(const view::Camera& cam, const Eigen::Vector3d& origin, bool rotate_mode,
                    const Eigen::Vector2d& px, const GizmoLayout& layout = {});
// The line list the Pose tool draws for `shape`, the `hover` part highlighted: per axis its line and
// its plane square (translate), or the ring and the disc's rim (rotate).
std::vector<gl::OverlayVertex> gizmo_lines(const GizmoShape& shape, GizmoPart hover);
// The highlight colour of the part under the cursor or being dragged.
Eigen::Vector4f gizmo_hover_color();
// World translation for a drag from one pixel to another on the given part (axis: along it only;
// plane: within it). Zero for parts that do not translate.
Eigen::Vector3d gizmo_translation(const view::Camera& cam, const Eigen::Vector3d& origin, GizmoPart part,
                                  const Eigen::Vector2d& from_px, const Eigen::Vector2d& to_px);
// Rotation for a drag on the ring (about the view axis, by the angle swept around the origin's image)
// or on the trackball disc (arcball centred on the origin's image).
Eigen::Quaterniond gizmo_rotation(const view::Camera& cam, const Eigen::Vector3d& origin, GizmoPart part,
                                  const Eigen::Vector2d& from_px, const Eigen::Vector2d& to_px,
                                  const GizmoLayout& layout = {});
// Twist (radians, right-handed about the bone's b - a) for a drag on its twist ring: the angle swept
// about the ring centre's image.
double gizmo_twist(const view::Camera& cam, const GizmoShape& shape, const Eigen::Vector2d& from_px,
                   const Eigen::Vector2d& to_px);
// Change of the bone's stretch for a drag of its stretch handle: the motion along the bone's posed
// axis over its rest length.
double gizmo_stretch(const view::Camera& cam, const GizmoShape& shape, const Eigen::Vector2d& from_px,
                     const Eigen::Vector2d& to_px);

}  // namespace dfm::editor
