#include "core/bind/outside_handles.h"

#include <vector>

#include <Eigen/Geometry>

#include "core/bind/closest_surface_point.h"
#include "core/mesh/mesh_info.h"

namespace dfm {
namespace {

// Per face, +1 or -1: the sign that makes its piece's enclosed volume positive (outward normals).
std::vector<double> outward_sign(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  const Eigen::VectorXi comp = face_components(F);
  std::vector<double> vol(comp.size() ? comp.maxCoeff() + 1 : 0, 0.0);
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    vol[comp(f)] += a.dot(b.cross(c));
  }
  std::vector<double> s(F.rows());
  for (int f = 0; f < F.rows(); ++f) s[f] = vol[comp(f)] < 0 ? -1.0 : 1.0;
  return s;
}

}  // namespace

std::vector<int> glue_outside_points(const Eigen::MatrixXd& SV, const Eigen::MatrixXi& SF,
                                     const Eigen::VectorXi& surface_to_tet, const Eigen::MatrixXd& X,
                                     double reach, TetMesh& mesh) {
  std::vector<int> out(X.rows(), -1);
  if (X.rows() == 0) return out;
  const SurfaceLocator locator(SV, SF, reach);
  const std::vector<double> sign = outward_sign(SV, SF);
  std::vector<std::vector<int>> faces_of(SV.rows());
  for (int f = 0; f < SF.rows(); ++f)
    for (int k = 0; k < 3; ++k) faces_of[SF(f, k)].push_back(f);
  std::vector<Eigen::Vector3d> new_v;
  std::vector<Eigen::RowVector4i> new_t;
  for (int i = 0; i < X.rows(); ++i) {
    const Eigen::Vector3d x = X.row(i).transpose();
    const SurfaceSample s = locator.closest(x);
    if (!s.found()) continue;
    // The facets around the closest point (its facet, or those sharing its edge or vertex).
    int best = -1;
    double best_d = 1e300;
    for (int v : s.vertex)
      for (int f : faces_of[v]) {
        const Eigen::Vector3d a = SV.row(SF(f, 0)), b = SV.row(SF(f, 1)), c = SV.row(SF(f, 2));
        const Eigen::Vector3d n = sign[f] * (b - a).cross(c - a);
        if (!(n.norm() > 0) || surface_to_tet(SF(f, 0)) < 0 || surface_to_tet(SF(f, 1)) < 0 || surface_to_tet(SF(f, 2)) < 0)
          continue;
        const Eigen::Vector3d w = closest_point_barycentric(x, a, b, c);
        const double d = (w(0) * a + w(1) * b + w(2) * c - x).norm();
        if ((x - a).dot(n.normalized()) > 0.1 * d && d < best_d) best_d = d, best = f;
      }
    if (best < 0) continue;
    const int nv = static_cast<int>(mesh.V.rows() + new_v.size());
    Eigen::RowVector4i t(surface_to_tet(SF(best, 0)), surface_to_tet(SF(best, 1)), surface_to_tet(SF(best, 2)), nv);
    if (sign[best] < 0) std::swap(t(1), t(2));  // (a, b, c, x) positive with outward (a, b, c)
    new_v.push_back(x);
    new_t.push_back(t);
    out[i] = nv;
  }
  const Eigen::Index v0 = mesh.V.rows(), t0 = mesh.T.rows();
  mesh.V.conservativeResize(v0 + static_cast<Eigen::Index>(new_v.size()), 3);
  for (size_t i = 0; i < new_v.size(); ++i) mesh.V.row(v0 + static_cast<Eigen::Index>(i)) = new_v[i].transpose();
  mesh.T.conservativeResize(t0 + static_cast<Eigen::Index>(new_t.size()), 4);
  for (size_t i = 0; i < new_t.size(); ++i) mesh.T.row(t0 + static_cast<Eigen::Index>(i)) = new_t[i];
  return out;
}

}  // namespace dfm
