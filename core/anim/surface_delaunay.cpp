#include "core/anim/surface_delaunay.h"

#include <algorithm>

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

namespace {

// Rows of `kept` in `all`, in order, when kept is all without some rows (else empty).
std::optional<std::vector<char>> kept_rows(const Eigen::MatrixXd& all, const Eigen::MatrixXd& kept) {
  std::vector<char> keep(all.rows(), 0);
  Eigen::Index i = 0;
  for (Eigen::Index j = 0; j < all.rows() && i < kept.rows(); ++j)
    if (all.row(j) == kept.row(i)) keep[j] = 1, ++i;
  if (i != kept.rows()) return std::nullopt;
  return keep;
}

}  // namespace

const SurfaceDelaunay& GrowingSurfaceDelaunay::of(const ConformingSurface& s) {
  const Eigen::Index n0 = V_.rows(), n = s.V.rows(), ni = s.fill.rows();
  const bool same_fill = d_ && s.fill.rows() == fill_.rows() && s.fill == fill_;
  const bool grown = same_fill && n >= n0 && s.V.topRows(n0) == V_;
  // Fill points dropped (and no more than a quarter: removing is dearer than inserting).
  std::optional<std::vector<char>> keep;
  if (d_ && !same_fill && n == n0 && s.V == V_ && 4 * (fill_.rows() - ni) <= fill_.rows()) keep = kept_rows(fill_, s.fill);
  if (!grown && !keep) {
    d_.reset();
    d_ = surface_delaunay(s);
  } else if (keep) {
    SurfaceDelaunay& d = *d_;
    std::vector<Delaunay3::Vertex_handle> vertex(d.vertex.begin(), d.vertex.begin() + n);
    for (Eigen::Index j = 0; j < fill_.rows(); ++j)
      if ((*keep)[j]) {
        d.vertex[n + j]->info() = static_cast<int>(vertex.size());
        vertex.push_back(d.vertex[n + j]);
      } else {
        d.dt.remove(d.vertex[n + j]);
      }
    d.vertex.swap(vertex);
  } else if (n > n0) {
    SurfaceDelaunay& d = *d_;
    std::vector<Delaunay3::Vertex_handle> vertex(n + ni);
    std::copy(d.vertex.begin(), d.vertex.begin() + n0, vertex.begin());
    for (Eigen::Index i = 0; i < ni; ++i) {
      vertex[n + i] = d.vertex[n0 + i];
      vertex[n + i]->info() = static_cast<int>(n + i);
    }
    std::vector<std::pair<DelaunayKernel::Point_3, int>> pts;
    for (Eigen::Index i = n0; i < n; ++i)
      pts.push_back({DelaunayKernel::Point_3(s.V(i, 0), s.V(i, 1), s.V(i, 2)), static_cast<int>(i)});
    const auto before = d.dt.number_of_vertices();
    d.dt.insert(pts.begin(), pts.end());
    if (d.dt.number_of_vertices() != before + pts.size()) {
      d_.reset();
      throw Error("two surface or fill points are at the same position");
    }
    // The new vertices' handles, found from the inserted points' infos.
    for (auto v = d.dt.finite_vertices_begin(); v != d.dt.finite_vertices_end(); ++v)
      if (v->info() >= n0 && v->info() < n) vertex[v->info()] = v;
    d.vertex.swap(vertex);
  }
  V_ = s.V;
  fill_ = s.fill;
  return *d_;
}

}  // namespace dfm
