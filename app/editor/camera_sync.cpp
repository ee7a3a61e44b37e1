#include "app/editor/camera_sync.h"

#include <cmath>

namespace dfm::editor {

dfm::Camera to_document_camera(const view::Camera& c) {
  dfm::Camera d;
  d.position = view::camera_eye(c);
  d.target = c.target;
  d.up = view::camera_up(c);
  d.fov_deg = c.fov_y_deg;
  d.ortho = c.orthographic;
  return d;
}

void from_document_camera(const dfm::Camera& d, view::Camera& c) {
  Eigen::Vector3d back = d.position - d.target;
  const double dist = back.norm();
  if (!(dist > 0) || !std::isfinite(dist)) return;  // degenerate: keep the current view
  back /= dist;
  Eigen::Vector3d right = d.up.cross(back);
  if (right.norm() < 1e-9) right = back.unitOrthogonal();  // up parallel to the view direction
  right.normalize();
  const Eigen::Vector3d up = back.cross(right);
  Eigen::Matrix3d R;
  R.col(0) = right;
  R.col(1) = up;
  R.col(2) = back;  // camera looks down -z
  c.orientation = Eigen::Quaterniond(R).normalized();
  c.target = d.target;
  c.distance = dist;
  if (d.fov_deg > 1 && d.fov_deg < 170) c.fov_y_deg = d.fov_deg;
  c.orthographic = d.ortho;
}

}  // namespace dfm::editor
