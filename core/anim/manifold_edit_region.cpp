#include "core/anim/manifold_edit_region.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/util/error.h"

namespace dfm {

namespace {

std::string range_text(double a, double b) {
  std::ostringstream s;
  s << "[" << a << ", " << b << "]";
  return s.str();
}

}  // namespace

std::vector<int> region_anchors(const AnimationManifold& m, const std::vector<int>& region) {
  std::vector<char> in(m.num_vertices(), 0), anchor(m.num_vertices(), 0);
  for (int v : region) in[v] = 1;
  // Any two vertices of a tetrahedron share one of its edges.
  for (int k = 0; k < m.num_tets(); ++k) {
    bool touches = false;
    for (int j = 0; j < 4; ++j) touches = touches || in[m.T(k, j)];
    if (!touches) continue;
    for (int j = 0; j < 4; ++j)
      if (!in[m.T(k, j)]) anchor[m.T(k, j)] = 1;
  }
  std::vector<int> out;
  for (int v = 0; v < m.num_vertices(); ++v)
    if (anchor[v]) out.push_back(v);
  return out;
}

bool in_region_balls(const EditRegionSpec& r, const Eigen::Vector3d& p) {
  if ((p - r.center).norm() <= r.radius) return true;
  for (const Eigen::Vector3d& d : r.dabs)
    if ((p - d).norm() <= r.radius) return true;
  return false;
}

EditRegion select_edit_region(const AnimationManifold& m, const EditRegionSpec& r, const EditHandleSpec& h) {
  if (!(r.radius > 0) || !std::isfinite(r.radius)) throw Error("edit region: the radius must be positive and finite");
  if (!(r.t0 < r.t1)) throw Error("edit region: the time window " + range_text(r.t0, r.t1) + " is empty (t0 must be < t1)");
  if (m.num_layers() < 2) throw Error("edit region: the manifold has no animation");
  const double first = m.times.front(), last = m.times.back();
  if (r.t1 <= first || r.t0 >= last)
    throw Error("edit region: the time window " + range_text(r.t0, r.t1) + " is outside the animation " +
                range_text(first, last));
  if (!(h.time >= r.t0 && h.time <= r.t1))
    throw Error("edit handle: its time " + std::to_string(h.time) + " is outside the window " + range_text(r.t0, r.t1));

  const int n = m.num_vertices();
  // A vertex whose star leaves the window: it sits in a tetrahedron with a vertex outside [t0, t1].
  std::vector<char> star_out(n, 0);
  for (int k = 0; k < m.num_tets(); ++k) {
    bool out = false;
    for (int j = 0; j < 4; ++j) {
      const double t = m.V(m.T(k, j), 3);
      out = out || t < r.t0 || t > r.t1;
    }
    if (out)
      for (int j = 0; j < 4; ++j) star_out[m.T(k, j)] = 1;
  }
  EditRegion e;
  for (int v = 0; v < n; ++v) {
    const double t = m.V(v, 3);
    if (star_out[v] || t < r.t0 || t > r.t1) continue;
    if (in_region_balls(r, m.V.row(v).head<3>().transpose())) e.region.push_back(v);
  }
  if (e.region.empty())
    throw Error("edit region: no manifold vertex lies within " + std::to_string(r.radius) +
                " of the centre with its neighbourhood inside the window " + range_text(r.t0, r.t1));
  e.anchors = region_anchors(m, e.region);
  if (e.anchors.empty()) throw Error("edit region: it covers a whole piece of the manifold, so no vertex anchors it");

  // The layer times bracketing the handle's time.
  double lo = h.time, hi = h.time;
  const auto it = std::lower_bound(m.times.begin(), m.times.end(), h.time);
  if (it != m.times.end() && *it != h.time && it != m.times.begin()) {
    lo = *(it - 1);
    hi = *it;
  }
  const double reach = r.radius / 4;
  for (int v : e.region) {
    const double t = m.V(v, 3);
    if (t != lo && t != hi && t != h.time) continue;
    if ((m.V.row(v).head<3>().transpose() - h.point).norm() <= reach) e.handle.push_back(v);
  }
  if (e.handle.empty())
    throw Error("edit handle: no region vertex within " + std::to_string(reach) + " (radius / 4) of the handle point at t = " +
                std::to_string(h.time) + " (the handle must lie in the region, on the layers around its time)");
  return e;
}

}  // namespace dfm
