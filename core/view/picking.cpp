#include "core/view/picking.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dfm::view {

bool ray_triangle(const Ray& ray, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                  const Eigen::Vector3d& c, double& t, double& u, double& v) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a;
  const Eigen::Vector3d p = ray.direction.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-14 * e1.norm() * e2.norm()) return false;
  const double inv = 1.0 / det;
  const Eigen::Vector3d s = ray.origin - a;
  u = s.dot(p) * inv;
  if (u < 0.0 || u > 1.0) return false;
  const Eigen::Vector3d q = s.cross(e1);
  v = ray.direction.dot(q) * inv;
  if (v < 0.0 || u + v > 1.0) return false;
  t = e2.dot(q) * inv;
  return t > 0.0;
}

namespace {
SurfaceHit make_hit(const Ray& ray, const Eigen::MatrixXi& F, int f, double t, double u, double v) {
  SurfaceHit h;
  h.face = f;
  h.t = t;
  h.point = ray.origin + t * ray.direction;
  h.bary = Eigen::Vector3d(1.0 - u - v, u, v);
  int corner = 0;
  h.bary.maxCoeff(&corner);
  h.nearest_vertex = F(f, corner);
  return h;
}
}  // namespace

SurfaceHit pick_surface(const Ray& ray, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  SurfaceHit best;
  double best_t = std::numeric_limits<double>::infinity();
  for (int f = 0; f < F.rows(); ++f) {
    double t, u, v;
    if (ray_triangle(ray, V.row(F(f, 0)), V.row(F(f, 1)), V.row(F(f, 2)), t, u, v) && t < best_t) {
      best_t = t;
      best = make_hit(ray, F, f, t, u, v);
    }
  }
  return best;
}

std::vector<SurfaceHit> pick_surface_all(const Ray& ray, const Eigen::MatrixXd& V,
                                         const Eigen::MatrixXi& F) {
  std::vector<SurfaceHit> hits;
  for (int f = 0; f < F.rows(); ++f) {
    double t, u, v;
    if (ray_triangle(ray, V.row(F(f, 0)), V.row(F(f, 1)), V.row(F(f, 2)), t, u, v))
      hits.push_back(make_hit(ray, F, f, t, u, v));
  }
  std::sort(hits.begin(), hits.end(), [](const SurfaceHit& a, const SurfaceHit& b) { return a.t < b.t; });
  return hits;
}

bool pick_inside_point(const Ray& ray, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                       Eigen::Vector3d& out) {
  const std::vector<SurfaceHit> hits = pick_surface_all(ray, V, F);
  if (hits.empty()) return false;
  // Skip hits at (numerically) the same t: a ray through a shared edge reports both faces.
  const double eps = 1e-9 * (1.0 + std::abs(hits[0].t));
  for (size_t i = 1; i < hits.size(); ++i) {
    if (hits[i].t - hits[0].t > eps) {
      out = 0.5 * (hits[0].point + hits[i].point);
      return true;
    }
  }
  out = hits[0].point;
  return true;
}

int pick_projected_point(const Camera& cam, const Eigen::MatrixXd& P, const Eigen::Vector2d& px,
                         double max_px) {
  int best = -1;
  double best_d = max_px;
  for (int i = 0; i < P.rows(); ++i) {
    const Eigen::Vector3d s = project_to_pixel(cam, P.row(i).transpose());
    if (s.z() < -1.0 || s.z() > 1.0) continue;  // clipped
    const double d = (s.head<2>() - px).norm();
    if (d <= best_d) {
      best_d = d;
      best = i;
    }
  }
  return best;
}

int pick_projected_segment(const Camera& cam, const Eigen::MatrixXd& P,
                           const std::vector<std::pair<int, int>>& segments,
                           const Eigen::Vector2d& px, double max_px) {
  int best = -1;
  double best_d = max_px;
  for (size_t i = 0; i < segments.size(); ++i) {
    const Eigen::Vector3d a3 = project_to_pixel(cam, P.row(segments[i].first).transpose());
    const Eigen::Vector3d b3 = project_to_pixel(cam, P.row(segments[i].second).transpose());
    if (a3.z() < -1.0 || a3.z() > 1.0 || b3.z() < -1.0 || b3.z() > 1.0) continue;
    const Eigen::Vector2d a = a3.head<2>(), b = b3.head<2>(), ab = b - a;
    const double len2 = ab.squaredNorm();
    const double s = len2 > 0 ? std::clamp((px - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    const double d = (a + s * ab - px).norm();
    if (d <= best_d) {
      best_d = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

std::vector<std::pair<int, double>> vertices_within(const Eigen::MatrixXd& V,
                                                    const Eigen::Vector3d& center, double radius) {
  std::vector<std::pair<int, double>> out;
  const double r2 = radius * radius;
  for (int i = 0; i < V.rows(); ++i) {
    const double d2 = (V.row(i).transpose() - center).squaredNorm();
    if (d2 <= r2) out.emplace_back(i, std::sqrt(d2));
  }
  return out;
}

}  // namespace dfm::view
