#pragma once
// The posing gizmo's geometry, all CPU: which part is under the cursor, and what a drag means
// (translation along an axis or in a plane, rotation by a trackball ring). Sized in pixels so it
// looks the same at any zoom.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/view/camera.h"

namespace dfm::editor {

enum class GizmoPart { None, AxisX, AxisY, AxisZ, PlaneYZ, PlaneXZ, PlaneXY, Ring, Trackball };

struct GizmoLayout {
  double axis_px = 90;    // arrow length on screen
  double plane_px = 26;   // plane squares span [0.25, 0.25 + plane/axis] of the arrow
  double ring_px = 110;   // rotation ring radius
  double pick_px = 8;     // tolerance
};

// World length that appears `px` pixels long at `p`.
double world_per_pixels(const view::Camera& cam, const Eigen::Vector3d& p, double px);
// The part under the cursor. Translate mode offers axes and planes; rotate mode the view ring
// (turn about the view axis) and the disc inside it (trackball).
GizmoPart gizmo_hit(const view::Camera& cam, const Eigen::Vector3d& origin, bool rotate_mode,
                    const Eigen::Vector2d& px, const GizmoLayout& layout = {});
// World translation for a drag from one pixel to another on the given part (axis: along it only;
// plane: within it). Zero for parts that do not translate.
Eigen::Vector3d gizmo_translation(const view::Camera& cam, const Eigen::Vector3d& origin, GizmoPart part,
                                  const Eigen::Vector2d& from_px, const Eigen::Vector2d& to_px);
// Rotation for a drag on the ring (about the view axis, by the angle swept around the origin's image)
// or on the trackball disc (arcball centred on the origin's image).
Eigen::Quaterniond gizmo_rotation(const view::Camera& cam, const Eigen::Vector3d& origin, GizmoPart part,
                                  const Eigen::Vector2d& from_px, const Eigen::Vector2d& to_px,
                                  const GizmoLayout& layout = {});

}  // namespace dfm::editor
