#include "render/interval_records.h"

#include <string>

#include "core/anim/manifold_normals.h"
#include "core/util/error.h"

namespace dfm::gl {

IntervalRecords interval_records(const IntervalSlice& s, const AnimationManifold& m,
                                 const Eigen::MatrixXd& vertex_normals4) {
  if (vertex_normals4.rows() != m.num_vertices() || vertex_normals4.cols() != 4)
    throw Error("interval slice pass: vertex normals must be " + std::to_string(m.num_vertices()) + " x 4");
  const int nv = s.num_vertices();
  IntervalRecords out;
  out.vertices.resize(nv);
  for (int v = 0; v < nv; ++v) {
    const int up = s.edges[v][0], dn = s.edges[v][1];
    if (up < 0 || dn < 0 || up >= m.num_vertices() || dn >= m.num_vertices())
      throw Error("interval slice pass: edge vertex out of range");
    const Eigen::Vector3d nu = slice_normal3(vertex_normals4.row(up).transpose(), SliceAxis::T),
                          nd = slice_normal3(vertex_normals4.row(dn).transpose(), SliceAxis::T);
    IntervalVertex& r = out.vertices[v];
    for (int d = 0; d < 3; ++d) {
      r.up[d] = static_cast<float>(m.V(up, d));
      r.down[d] = static_cast<float>(m.V(dn, d));
      r.n_up[d] = static_cast<float>(nu[d]);
      r.n_down[d] = static_cast<float>(nd[d]);
    }
    const double span = m.V(up, 3) - m.V(dn, 3);  // > 0 (build_interval_slice's edges)
    if (!(span > 0)) throw Error("interval slice pass: an edge does not go forward in time");
    r.mu[0] = static_cast<float>((m.V(up, 3) - s.t_lo) / span);
    r.mu[1] = static_cast<float>(-1.0 / span);
  }
  out.indices.resize(static_cast<size_t>(s.F.size()));
  for (int f = 0; f < s.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      if (s.F(f, c) < 0 || s.F(f, c) >= nv) throw Error("interval slice pass: triangle index out of range");
      out.indices[3 * f + c] = static_cast<std::uint32_t>(s.F(f, c));
    }
  return out;
}

}  // namespace dfm::gl
