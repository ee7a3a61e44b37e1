#include "core/anim/interval_slice.h"

#include <algorithm>
#include <string>

#include "core/anim/manifold_frame.h"
#include "core/anim/manifold_normals.h"
#include "core/anim/slice.h"
#include "core/mesh/mesh_info.h"
#include "core/util/error.h"

namespace dfm {

std::vector<double> manifold_vertex_times(const AnimationManifold& m) {
  std::vector<double> t(m.V.rows());
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) t[i] = m.V(i, 3);
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

int open_interval_of(const std::vector<double>& times, double t) {
  const auto it = std::upper_bound(times.begin(), times.end(), t);  // first time > t
  if (it == times.begin() || it == times.end()) return -1;
  const int i = static_cast<int>(it - times.begin()) - 1;
  return times[i] < t ? i : -1;
}

IntervalSlice build_interval_slice(const AnimationManifold& m, const Eigen::MatrixXd& vertex_normals4,
                                   double t_lo, double t_hi) {
  if (!(t_lo < t_hi))
    throw Error("interval slice: empty interval (" + std::to_string(t_lo) + ", " + std::to_string(t_hi) + ")");
  const double mid = t_lo + 0.5 * (t_hi - t_lo);
  ManifoldSlice s = manifold_frame(m, mid, &vertex_normals4);
  IntervalSlice out;
  out.t_lo = t_lo;
  out.t_hi = t_hi;
  out.closed_outward = is_closed_outward(s.mesh.V, s.mesh.F);
  out.F = std::move(s.mesh.F);
  out.edges.resize(s.edges.size());
  for (size_t v = 0; v < s.edges.size(); ++v) {
    int a = s.edges[v][0], b = s.edges[v][1];
    if (a == b)
      throw Error("interval slice: vertex " + std::to_string(a) + " at t = " + std::to_string(m.V(a, 3)) +
                  " lies inside (" + std::to_string(t_lo) + ", " + std::to_string(t_hi) + ")");
    if (m.V(a, 3) < m.V(b, 3)) std::swap(a, b);
    if (!(m.V(a, 3) >= t_hi && m.V(b, 3) <= t_lo))
      throw Error("interval slice: edge (" + std::to_string(a) + ", " + std::to_string(b) +
                  ") does not span (" + std::to_string(t_lo) + ", " + std::to_string(t_hi) + ")");
    out.edges[v] = {a, b};
  }
  return out;
}

TriMesh evaluate_interval_slice(const IntervalSlice& s, const AnimationManifold& m,
                                const Eigen::MatrixXd& vertex_normals4, double t) {
  if (!s.reaches(t))
    throw Error("interval slice: t = " + std::to_string(t) + " is outside [" + std::to_string(s.t_lo) + ", " +
                std::to_string(s.t_hi) + "]");
  TriMesh out;
  const int nv = s.num_vertices();
  out.V.resize(nv, 3);
  out.N.resize(nv, 3);
  out.F = s.F;
  for (int v = 0; v < nv; ++v) {
    const int up = s.edges[v][0], dn = s.edges[v][1];
    // The same operations as slice_manifold and prism_frame, so the same bits.
    const double su = m.V(up, 3) - t, sd = m.V(dn, 3) - t;
    const double mu = su / (su - sd);
    for (int d = 0; d < 3; ++d) {
      const double pu = m.V(up, d), pd = m.V(dn, d);
      out.V(v, d) = pu + mu * (pd - pu);
    }
    const Eigen::Vector3d nu = slice_normal3(vertex_normals4.row(up).transpose(), SliceAxis::T),
                          nd = slice_normal3(vertex_normals4.row(dn).transpose(), SliceAxis::T);
    const Eigen::Vector3d n = nu + mu * (nd - nu);
    const double len = n.norm();
    out.N.row(v) = len > 0 ? Eigen::RowVector3d(n.transpose() / len) : Eigen::RowVector3d::Zero();
  }
  return out;
}

}  // namespace dfm
