#include "core/anim/manifold_frame.h"

#include <string>

#include "core/anim/manifold_normals.h"
#include "core/util/error.h"

namespace dfm {

int prism_slab_at(const AnimationManifold& m, double t) {
  if (m.prism_slabs.empty()) return -1;
  for (int i = 0; i < m.num_slabs(); ++i)
    if (m.prism_slabs[i].is_prism() && m.times[i] <= t && t <= m.times[i + 1]) return i;
  return -1;
}

ManifoldSlice prism_frame(const AnimationManifold& m, int slab, double t, const Eigen::MatrixXd* vertex_normals4) {
  if (slab < 0 || slab >= static_cast<int>(m.prism_slabs.size()) || !m.prism_slabs[slab].is_prism())
    throw Error("frame: slab " + std::to_string(slab) + " was not made by the prism build");
  const double t_dn = m.times[slab], t_up = m.times[slab + 1];
  if (!(t_dn <= t && t <= t_up))
    throw Error("frame: t = " + std::to_string(t) + " is outside prism slab " + std::to_string(slab) + " [" +
                std::to_string(t_dn) + ", " + std::to_string(t_up) + "]");
  const PrismSlab& p = m.prism_slabs[slab];
  const auto [first, last] = normal_tet_range(m, SliceAxis::T, t);
  const VertexNormalSource normal4(m, vertex_normals4, first, last);
  ManifoldSlice out;
  out.mesh.F = m.layer_faces[p.faces];
  out.mesh.V.resize(p.count, 3);
  out.mesh.N.resize(p.count, 3);
  out.edges.resize(p.count);
  // slice.h's rule on the edge (up, dn): a point on a vertex is that vertex, else from the above end.
  const double su = t_up - t, sd = t_dn - t;
  const double mu = su / (su - sd);
  for (int v = 0; v < p.count; ++v) {
    const int up = p.upper + v, dn = p.lower + v;
    if (su == 0.0 || sd == 0.0) {
      const int at = su == 0.0 ? up : dn;
      out.edges[v] = {at, at};
      out.mesh.V.row(v) = m.V.block<1, 3>(at, 0);
      out.mesh.N.row(v) = slice_normal3(normal4(at), SliceAxis::T).transpose();
      continue;
    }
    out.edges[v] = {dn, up};
    for (int d = 0; d < 3; ++d) {
      const double pu = m.V(up, d), pd = m.V(dn, d);
      out.mesh.V(v, d) = pu + mu * (pd - pu);
    }
    const Eigen::Vector3d nu = slice_normal3(normal4(up), SliceAxis::T), nd = slice_normal3(normal4(dn), SliceAxis::T);
    const Eigen::Vector3d n = nu + mu * (nd - nu);
    const double len = n.norm();
    out.mesh.N.row(v) = len > 0 ? Eigen::RowVector3d(n.transpose() / len) : Eigen::RowVector3d::Zero();
  }
  return out;
}

int key_layer_at(const AnimationManifold& m, double t) {
  for (size_t i = 0; i < m.key_layers.size(); ++i)
    if (m.key_layers[i].time == t) return static_cast<int>(i);
  return -1;
}

ManifoldSlice key_frame(const AnimationManifold& m, int layer, const Eigen::MatrixXd* vertex_normals4) {
  if (layer < 0 || layer >= static_cast<int>(m.key_layers.size()))
    throw Error("frame: no key layer " + std::to_string(layer));
  const ManifoldKey& k = m.key_layers[layer];
  const auto [first, last] = normal_tet_range(m, SliceAxis::T, k.time);
  const VertexNormalSource normal4(m, vertex_normals4, first, last);
  const int n = static_cast<int>(k.vertices.size());
  ManifoldSlice out;
  out.mesh.F = m.layer_faces[k.faces];
  out.mesh.V.resize(n, 3);
  out.mesh.N.resize(n, 3);
  out.edges.resize(n);
  for (int v = 0; v < n; ++v) {
    const int at = k.vertices[v];
    out.edges[v] = {at, at};
    out.mesh.V.row(v) = m.V.block<1, 3>(at, 0);
    out.mesh.N.row(v) = slice_normal3(normal4(at), SliceAxis::T).transpose();
  }
  return out;
}

ManifoldSlice manifold_frame(const AnimationManifold& m, double t, const Eigen::MatrixXd* vertex_normals4) {
  const int slab = prism_slab_at(m, t);
  if (slab >= 0) return prism_frame(m, slab, t, vertex_normals4);
  const int key = key_layer_at(m, t);
  if (key >= 0) return key_frame(m, key, vertex_normals4);
  return slice_manifold(m, SliceAxis::T, t, vertex_normals4);
}

}  // namespace dfm
