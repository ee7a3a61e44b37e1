#include "core/anim/surface_delaunay.h"

#include "core/util/error.h"

namespace dfm {

SurfaceDelaunay surface_delaunay(const ConformingSurface& s) {
  const int n = static_cast<int>(s.V.rows()), ni = static_cast<int>(s.fill.rows());
  std::vector<std::pair<DelaunayKernel::Point_3, int>> pts;
  pts.reserve(n + ni);
  for (int i = 0; i < n; ++i) pts.push_back({DelaunayKernel::Point_3(s.V(i, 0), s.V(i, 1), s.V(i, 2)), i});
  for (int i = 0; i < ni; ++i) pts.push_back({DelaunayKernel::Point_3(s.fill(i, 0), s.fill(i, 1), s.fill(i, 2)), n + i});
  SurfaceDelaunay d;
  d.dt.insert(pts.begin(), pts.end());
  d.vertex.resize(n + ni);
  int found = 0;
  for (auto v = d.dt.finite_vertices_begin(); v != d.dt.finite_vertices_end(); ++v, ++found) d.vertex[v->info()] = v;
  if (found != n + ni) throw Error("two surface or fill points are at the same position");
  return d;
}

}  // namespace dfm
