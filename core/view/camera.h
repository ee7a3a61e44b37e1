#pragma once
// The viewport's orbit camera (the editor's, and `deform manifold --strip`'s renders), all on the CPU so
// every gesture is unit-tested without a GPU. The camera looks at `target` from `distance` away;
// `orientation` rotates camera space (x right, y up, looking down -z) into world space. Pixel
// coordinates are GLFW's: origin top-left, y down.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace dfm::view {

struct Camera {
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  double distance = 3.0;
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  double fov_y_deg = 40.0;
  bool orthographic = false;
  double width = 1280, height = 720;  // viewport in pixels
  double scene_radius = 1.0;          // sizes the clip planes so nothing of the scene is cut
};

struct Ray {
  Eigen::Vector3d origin;
  Eigen::Vector3d direction;  // unit length
};

enum class ViewPreset { Front, Back, Left, Right, Top, Bottom, Iso };

Eigen::Vector3d camera_eye(const Camera& c);
Eigen::Vector3d camera_forward(const Camera& c);  // unit, eye -> target
Eigen::Vector3d camera_right(const Camera& c);
Eigen::Vector3d camera_up(const Camera& c);
// Half the visible height at the target's depth (what an orthographic camera shows too, so toggling
// perspective/ortho keeps the framing).
double half_height_at_target(const Camera& c);
double near_plane(const Camera& c);
double far_plane(const Camera& c);

Eigen::Matrix4d view_matrix(const Camera& c);
Eigen::Matrix4d projection_matrix(const Camera& c);

// World point -> (pixel x, pixel y, NDC depth in [-1,1]).
Eigen::Vector3d project_to_pixel(const Camera& c, const Eigen::Vector3d& p);
// The ray through a pixel (for picking and for placing handles).
Ray pixel_ray(const Camera& c, double px, double py);
// Where the pixel's ray meets the plane through `target` facing the camera.
Eigen::Vector3d pixel_on_target_plane(const Camera& c, double px, double py);
// Where the pixel's ray meets the plane through p facing the camera (a dragged point's new place: p
// stays under the cursor at its depth); p itself when p is not in front of a perspective eye.
Eigen::Vector3d pixel_on_plane_through(const Camera& c, const Eigen::Vector3d& p, double px, double py);

// Trackball orbit about the target (Shoemake arcball): dragging from one pixel to another turns the
// scene as if the cursor had dragged a sphere's surface. Distance to the target is preserved.
void arcball_orbit(Camera& c, const Eigen::Vector2d& from_px, const Eigen::Vector2d& to_px);
// Turntable orbit: yaw about world +y, pitch about the camera's right axis (angles in radians).
void turntable_orbit(Camera& c, double yaw, double pitch);
// Slides the camera in its image plane so the target follows the cursor by `delta_px`.
void pan(Camera& c, const Eigen::Vector2d& delta_px);
// Zooms by `factor` (< 1 moves in) about the point under the cursor on the target plane, which
// stays under the cursor.
void zoom_to_cursor(Camera& c, double factor, const Eigen::Vector2d& cursor_px);
// Fits the box (or sphere) in view with a small margin, keeping the orientation.
void frame_box(Camera& c, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);
void frame_sphere(Camera& c, const Eigen::Vector3d& center, double radius);
void set_view_preset(Camera& c, ViewPreset preset);
const char* view_preset_name(ViewPreset preset);

}  // namespace dfm::view
