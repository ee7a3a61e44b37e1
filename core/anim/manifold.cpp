#include "core/anim/manifold.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include <Eigen/LU>

#include "core/util/error.h"

namespace dfm {

std::vector<Eigen::Vector4i> prism_tets(const Eigen::Vector3i& f, int lower_offset, int stride) {
  // Parametric prism: the triangle's corners in its own (outward) order sit at (0,0), (1,0), (0,1);
  // the lower layer at tau = 0, the upper at tau = 1. A tetrahedron with positive parametric volume
  // has an outward 4D normal (the map (u,v,tau) -> (x(u,v,tau), tau) keeps the orientation).
  static const double kRef[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  std::array<int, 3> order = {0, 1, 2};  // corners sorted by vertex index
  std::sort(order.begin(), order.end(), [&](int i, int j) { return f[i] < f[j]; });
  // The staircase sequence: corner (0..2) and layer (0 lower, 1 upper) of [v0 v1 v2 v0' v1' v2'].
  std::array<int, 6> corner, layer;
  for (int k = 0; k < 6; ++k) {
    corner[k] = order[k % 3];
    layer[k] = k / 3;
  }
  std::vector<Eigen::Vector4i> tets;
  for (int s = 0; s < 3; ++s) {
    std::array<int, 4> idx = {s, s + 1, s + 2, s + 3};
    Eigen::Matrix3d E;
    for (int r = 1; r < 4; ++r)
      for (int c = 0; c < 3; ++c) {
        auto coord = [&](int k) {
          return c < 2 ? kRef[corner[idx[k]]][c] : static_cast<double>(layer[idx[k]]);
        };
        E(c, r - 1) = coord(r) - coord(0);
      }
    if (E.determinant() < 0) std::swap(idx[2], idx[3]);
    Eigen::Vector4i t;
    for (int k = 0; k < 4; ++k) t[k] = lower_offset + layer[idx[k]] * stride + f[corner[idx[k]]];
    tets.push_back(t);
  }
  return tets;
}

AnimationManifold build_manifold(const std::vector<Eigen::MatrixXd>& layers, const Eigen::MatrixXi& F,
                                 const std::vector<double>& times) {
  const int m = static_cast<int>(layers.size());
  if (m < 2) throw Error("an animation manifold needs at least 2 layers, got " + std::to_string(m));
  if (static_cast<int>(times.size()) != m)
    throw Error("manifold: " + std::to_string(m) + " layers but " + std::to_string(times.size()) + " times");
  const long n = layers[0].rows();
  for (int i = 0; i < m; ++i) {
    if (layers[i].rows() != n || layers[i].cols() != 3)
      throw Error("manifold: layer " + std::to_string(i) + " has " + std::to_string(layers[i].rows()) + " x " +
                  std::to_string(layers[i].cols()) + " positions, layer 0 has " + std::to_string(n) + " x 3");
    if (!std::isfinite(times[i]) || (i > 0 && !(times[i] > times[i - 1])))
      throw Error("manifold: layer times must be finite and strictly increasing (time " + std::to_string(i) +
                  " = " + std::to_string(times[i]) + ")");
  }
  if (F.cols() != 3) throw Error("manifold: triangles must have 3 columns");
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3i t = F.row(f);
    if (t.minCoeff() < 0 || t.maxCoeff() >= n)
      throw Error("manifold: triangle " + std::to_string(f) + " has a vertex index outside [0, " +
                  std::to_string(n) + ")");
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      throw Error("manifold: triangle " + std::to_string(f) + " repeats a vertex");
  }
  if (static_cast<long long>(n) * m > 2000000000LL || 3LL * F.rows() * (m - 1) > 2000000000LL)
    throw Error("manifold: too large for 32-bit indices");

  AnimationManifold M;
  M.times = times;
  M.V.resize(n * m, 4);
  for (int i = 0; i < m; ++i) {
    M.V.block(i * n, 0, n, 3) = layers[i];
    M.V.block(i * n, 3, n, 1).setConstant(times[i]);
  }
  // Every slab repeats slab 0's pattern shifted by one layer, so build the pattern once.
  const int l = static_cast<int>(F.rows());
  MatrixX4iRow pattern(3 * l, 4);
  for (int f = 0; f < l; ++f) {
    const auto tets = prism_tets(F.row(f).transpose(), 0, static_cast<int>(n));
    for (int k = 0; k < 3; ++k) pattern.row(3 * f + k) = tets[k].transpose();
  }
  M.T.resize(3L * l * (m - 1), 4);
  M.slab_offsets.resize(m);
  for (int i = 0; i + 1 < m; ++i) {
    M.slab_offsets[i] = 3 * l * i;
    M.T.block(3L * l * i, 0, 3L * l, 4) = pattern.array() + static_cast<int>(i * n);
  }
  M.slab_offsets[m - 1] = 3 * l * (m - 1);
  M.layer_faces.push_back(F);
  M.prism_slabs.resize(m - 1);
  for (int i = 0; i + 1 < m; ++i)
    M.prism_slabs[i] = PrismSlab{0, static_cast<int>(i * n), static_cast<int>((i + 1) * n), static_cast<int>(n)};
  return M;
}

AnimationManifold build_manifold(const BakedLayers& layers, const Eigen::MatrixXi& F) {
  return build_manifold(layers.positions, F, layers.times);
}

namespace {

// A prism slab's layers are vertex ranges at the slab's two times, and its triangles index them.
void validate_prism_slabs(const AnimationManifold& M, const std::string& what) {
  if (M.prism_slabs.empty()) return;
  if (static_cast<int>(M.prism_slabs.size()) != M.num_slabs())
    throw Error(what + ": " + std::to_string(M.prism_slabs.size()) + " prism slab entries for " +
                std::to_string(M.num_slabs()) + " slabs");
  const int nv = M.num_vertices();
  for (int i = 0; i < M.num_slabs(); ++i) {
    const PrismSlab& p = M.prism_slabs[i];
    if (!p.is_prism()) continue;
    const std::string slab = what + ": prism slab " + std::to_string(i);
    if (p.faces >= static_cast<int>(M.layer_faces.size())) throw Error(slab + " names a missing triangle list");
    if (p.count < 1 || p.lower < 0 || p.upper < 0 || p.lower > nv - p.count || p.upper > nv - p.count)
      throw Error(slab + " has a layer outside the vertices");
    for (int v = 0; v < p.count; ++v)
      if (M.V(p.lower + v, 3) != M.times[i] || M.V(p.upper + v, 3) != M.times[i + 1])
        throw Error(slab + ": layer vertex " + std::to_string(v) + " is not at the slab's times");
    const Eigen::MatrixXi& F = M.layer_faces[p.faces];
    if (F.cols() != 3 || (F.size() > 0 && (F.minCoeff() < 0 || F.maxCoeff() >= p.count)))
      throw Error(slab + ": a triangle has a vertex index outside [0, " + std::to_string(p.count) + ")");
  }
}

void validate_key_layers(const AnimationManifold& M, const std::string& what) {
  const int nv = M.num_vertices();
  for (size_t i = 0; i < M.key_layers.size(); ++i) {
    const ManifoldKey& k = M.key_layers[i];
    const std::string key = what + ": key layer " + std::to_string(i);
    if (k.faces < 0 || k.faces >= static_cast<int>(M.layer_faces.size())) throw Error(key + " names a missing triangle list");
    for (int v : k.vertices)
      if (v < 0 || v >= nv || M.V(v, 3) != k.time) throw Error(key + ": a vertex is missing or not at its time");
    const Eigen::MatrixXi& F = M.layer_faces[k.faces];
    const int n = static_cast<int>(k.vertices.size());
    if (F.cols() != 3 || (F.size() > 0 && (F.minCoeff() < 0 || F.maxCoeff() >= n)))
      throw Error(key + ": a triangle has a vertex index outside [0, " + std::to_string(n) + ")");
  }
}

}  // namespace

void validate_manifold(const AnimationManifold& M, const std::string& what) {
  const int m = M.num_layers();
  if (m < 2) throw Error(what + ": needs at least 2 layer times, has " + std::to_string(m));
  for (int i = 0; i < m; ++i)
    if (!std::isfinite(M.times[i]) || (i > 0 && !(M.times[i] > M.times[i - 1])))
      throw Error(what + ": layer times must be finite and strictly increasing (time " + std::to_string(i) + ")");
  if (static_cast<int>(M.slab_offsets.size()) != m)
    throw Error(what + ": " + std::to_string(M.slab_offsets.size()) + " slab offsets for " + std::to_string(m) +
                " layers");
  if (M.slab_offsets.front() != 0 || M.slab_offsets.back() != M.num_tets())
    throw Error(what + ": slab offsets must start at 0 and end at the tetrahedron count");
  for (int i = 0; i + 1 < m; ++i)
    if (M.slab_offsets[i + 1] < M.slab_offsets[i]) throw Error(what + ": slab offsets decrease at " + std::to_string(i));
  if (!M.V.allFinite()) throw Error(what + ": a vertex coordinate is not finite");
  const int nv = M.num_vertices();
  for (int i = 0; i + 1 < m; ++i) {
    for (int k = M.slab_offsets[i]; k < M.slab_offsets[i + 1]; ++k) {
      for (int c = 0; c < 4; ++c) {
        const int v = M.T(k, c);
        if (v < 0 || v >= nv)
          throw Error(what + ": tetrahedron " + std::to_string(k) + " has vertex index " + std::to_string(v) +
                      " outside [0, " + std::to_string(nv) + ")");
        const double t = M.V(v, 3);
        if (t < M.times[i] || t > M.times[i + 1])
          throw Error(what + ": tetrahedron " + std::to_string(k) + " of slab " + std::to_string(i) +
                      " has a vertex at t = " + std::to_string(t) + " outside the slab [" +
                      std::to_string(M.times[i]) + ", " + std::to_string(M.times[i + 1]) + "]");
      }
    }
  }
  validate_prism_slabs(M, what);
  validate_key_layers(M, what);
}

}  // namespace dfm
