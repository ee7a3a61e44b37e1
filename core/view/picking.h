#pragma once
// CPU picking: rays against the (posed) triangle surface, and screen-space picking of handles.
#include <vector>

#include <Eigen/Core>

#include "core/view/camera.h"

namespace dfm::view {

struct SurfaceHit {
  int face = -1;  // -1: missed
  double t = 0;   // distance along the ray
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();  // weights of the face's three corners
  int nearest_vertex = -1;                         // the face corner closest to the hit
  bool hit() const { return face >= 0; }
};

// Möller-Trumbore, both sides. t in (0, inf); returns false when parallel or behind.
bool ray_triangle(const Ray& ray, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                  const Eigen::Vector3d& c, double& t, double& u, double& v);

// Nearest hit of the ray with the surface (brute force: one click, so O(#F) is fine).
SurfaceHit pick_surface(const Ray& ray, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);
// Every hit along the ray, sorted by t.
std::vector<SurfaceHit> pick_surface_all(const Ray& ray, const Eigen::MatrixXd& V,
                                         const Eigen::MatrixXi& F);
// A point inside the volume under the cursor: halfway between where the ray enters the surface and
// where it next leaves it; the surface hit itself when the ray meets the surface only once.
// Returns false on a miss.
bool pick_inside_point(const Ray& ray, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                       Eigen::Vector3d& out);

// Row of P whose projection lies nearest the pixel, within max_px; -1 if none.
int pick_projected_point(const Camera& cam, const Eigen::MatrixXd& P, const Eigen::Vector2d& px,
                         double max_px);
// Segment (rows a, b of P given as pairs) whose projection passes nearest the pixel; -1 if none.
int pick_projected_segment(const Camera& cam, const Eigen::MatrixXd& P,
                           const std::vector<std::pair<int, int>>& segments,
                           const Eigen::Vector2d& px, double max_px);

// Vertices of V within `radius` of `center` (for the paint brush), with their distances.
std::vector<std::pair<int, double>> vertices_within(const Eigen::MatrixXd& V,
                                                    const Eigen::Vector3d& center, double radius);

}  // namespace dfm::view
