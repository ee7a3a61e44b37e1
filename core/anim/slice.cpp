#include "core/anim/slice.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <string>

#include "core/anim/manifold_normals.h"
#include "core/anim/slice_table.h"
#include "core/util/error.h"

namespace dfm {

SliceAxis parse_slice_axis(const std::string& name) {
  std::string n = name;
  for (char& ch : n) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (n == "x") return SliceAxis::X;
  if (n == "y") return SliceAxis::Y;
  if (n == "z") return SliceAxis::Z;
  if (n == "t") return SliceAxis::T;
  throw Error("unknown slice axis '" + name + "' (expected t, x, y or z)");
}

const char* slice_axis_name(SliceAxis axis) {
  static const char* names[] = {"x", "y", "z", "t"};
  return names[static_cast<int>(axis)];
}

std::pair<int, int> slice_tet_range(const AnimationManifold& M, SliceAxis axis, double c) {
  if (axis != SliceAxis::T || M.num_layers() < 2) return {0, M.num_tets()};
  const auto& t = M.times;
  const int slabs = M.num_slabs();
  int lo = 0;
  while (lo < slabs && t[lo + 1] < c) ++lo;  // first slab ending at or after c
  int hi = slabs - 1;
  while (hi >= 0 && t[hi] > c) --hi;  // last slab starting at or before c
  if (lo > hi) return {0, 0};
  return {M.slab_offsets[lo], M.slab_offsets[hi + 1]};
}

std::pair<int, int> normal_tet_range(const AnimationManifold& M, SliceAxis axis, double c) {
  if (axis != SliceAxis::T || M.num_layers() < 2) return {0, M.num_tets()};
  const auto& t = M.times;
  const int slabs = M.num_slabs();
  int lo = 0;
  while (lo < slabs && t[lo + 1] < c) ++lo;
  int hi = slabs - 1;
  while (hi >= 0 && t[hi] > c) --hi;
  if (lo > hi) return {0, 0};
  return {M.slab_offsets[std::max(lo - 1, 0)], M.slab_offsets[std::min(hi + 2, slabs)]};
}

bool slice_on_plane_is_above(const AnimationManifold& M, SliceAxis axis, double c) {
  const int k = static_cast<int>(axis);
  double lowest;
  if (axis == SliceAxis::T && !M.times.empty())
    lowest = M.times.front();
  else if (M.num_vertices() > 0)
    lowest = M.V.col(k).minCoeff();
  else
    return true;
  return c > lowest;
}

namespace {

inline std::uint64_t key_of(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}

// The slice's triangles before the weld, each as the weld keys of its 3 corners (the manifold edge,
// or vertex, each corner lies on); triangles the weld collapses are skipped. f(std::uint64_t key[3]).
template <class F>
void for_each_slice_triangle(const AnimationManifold& M, SliceAxis axis_e, double c, F&& f) {
  const int axis = static_cast<int>(axis_e);
  const bool on_plane_above = slice_on_plane_is_above(M, axis_e, c);
  const auto [first, last] = slice_tet_range(M, axis_e, c);
  const auto& table = slice_table();
  const double* V = M.V.data();
  const int* T = M.T.data();
  for (int k = first; k < last; ++k) {
    int g[4];
    double s[4];
    int mask = 0;
    for (int i = 0; i < 4; ++i) {
      g[i] = T[4 * k + i];
      s[i] = V[4 * g[i] + axis] - c;
      const bool above = on_plane_above ? s[i] >= 0.0 : s[i] > 0.0;
      mask |= above << i;
    }
    if (mask == 0 || mask == 15) continue;
    const SliceCase& sc = table[mask];
    for (int tri = 0; tri < sc.num_triangles; ++tri) {
      std::uint64_t key[3];
      for (int j = 0; j < 3; ++j) {
        const auto& e = kSliceEdges[sc.triangles[tri][j]];
        const int a = e[0], b = e[1];
        // A crossing point on a vertex is that vertex (so key time slices are the layer exactly).
        key[j] = s[a] == 0.0 ? key_of(g[a], g[a]) : s[b] == 0.0 ? key_of(g[b], g[b]) : key_of(g[a], g[b]);
      }
      if (key[0] == key[1] || key[1] == key[2] || key[0] == key[2]) continue;  // collapsed by the weld
      f(key);
    }
  }
}

// The weld: the distinct corner keys in increasing order (the slice's vertices), and per corner its
// vertex. An open-addressing table gives each distinct key a first-seen id; the ids are then renumbered
// in key order so the vertex order is deterministic (a layer's own order at key times).
void weld_corners(const std::vector<std::uint64_t>& corners, std::vector<std::uint64_t>& keys,
                  std::vector<int>& corner_vertex) {
  size_t cap = 16;
  while (cap < corners.size()) cap <<= 1;
  cap <<= 1;  // load factor <= 1/2
  constexpr std::uint64_t kEmpty = ~std::uint64_t(0);
  std::vector<std::uint64_t> slot_key(cap, kEmpty);
  std::vector<int> slot_id(cap);
  keys.clear();  // by first-seen id, then sorted
  std::vector<int> corner_id(corners.size());
  for (size_t i = 0; i < corners.size(); ++i) {
    const std::uint64_t k = corners[i];
    size_t h = static_cast<size_t>((k * 0x9E3779B97F4A7C15ull) >> 20) & (cap - 1);
    while (slot_key[h] != kEmpty && slot_key[h] != k) h = (h + 1) & (cap - 1);
    if (slot_key[h] == kEmpty) {
      slot_key[h] = k;
      slot_id[h] = static_cast<int>(keys.size());
      keys.push_back(k);
    }
    corner_id[i] = slot_id[h];
  }
  std::vector<int> order(keys.size()), rank(keys.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return keys[a] < keys[b]; });
  for (size_t i = 0; i < order.size(); ++i) rank[order[i]] = static_cast<int>(i);
  {
    std::vector<std::uint64_t> sorted(keys.size());
    for (size_t i = 0; i < order.size(); ++i) sorted[i] = keys[order[i]];
    keys.swap(sorted);
  }
  corner_vertex.resize(corners.size());
  for (size_t i = 0; i < corners.size(); ++i) corner_vertex[i] = rank[corner_id[i]];
}

}  // namespace

int welded_slice_vertex_count(const AnimationManifold& M, SliceAxis axis, double value) {
  if (static_cast<int>(axis) < 0 || static_cast<int>(axis) > 3) throw Error("slice axis out of range");
  std::vector<std::uint64_t> keys;
  for_each_slice_triangle(M, axis, value, [&](const std::uint64_t* key) { keys.insert(keys.end(), key, key + 3); });
  std::sort(keys.begin(), keys.end());
  return static_cast<int>(std::unique(keys.begin(), keys.end()) - keys.begin());
}

ManifoldSlice slice_manifold(const AnimationManifold& M, SliceAxis axis_e, double c,
                             const Eigen::MatrixXd* vertex_normals4) {
  const int axis = static_cast<int>(axis_e);
  if (axis < 0 || axis > 3) throw Error("slice axis out of range");
  const bool flip = slice_flips_winding(axis);
  const double* V = M.V.data();

  // Pass 1: per triangle, the weld keys of its 3 corners.
  std::vector<std::uint64_t> corners;
  for_each_slice_triangle(M, axis_e, c, [&](std::uint64_t* key) {
    if (flip) std::swap(key[1], key[2]);
    corners.insert(corners.end(), key, key + 3);
  });

  // Pass 2: weld.
  std::vector<std::uint64_t> keys;
  std::vector<int> corner_vertex;
  weld_corners(corners, keys, corner_vertex);

  ManifoldSlice out;
  const int nv = static_cast<int>(keys.size());
  out.mesh.V.resize(nv, 3);
  out.mesh.N.resize(nv, 3);
  out.edges.resize(nv);
  int keep[3], nk = 0;
  for (int d = 0; d < 4; ++d)
    if (d != axis) keep[nk++] = d;
  const auto [nfirst, nlast] = nv > 0 ? normal_tet_range(M, axis_e, c) : std::pair<int, int>{0, 0};
  const VertexNormalSource normal4(M, vertex_normals4, nfirst, nlast);
  for (int v = 0; v < nv; ++v) {
    const int a = static_cast<int>(keys[v] >> 32), b = static_cast<int>(keys[v] & 0xffffffffu);
    out.edges[v] = {a, b};
    if (a == b) {
      for (int d = 0; d < 3; ++d) out.mesh.V(v, d) = V[4 * a + keep[d]];
      out.mesh.N.row(v) = slice_normal3(normal4(a), axis_e).transpose();
      continue;
    }
    // Interpolate from the above endpoint; the formula depends on the edge only, never on the tet.
    int up = a, dn = b;
    if (V[4 * a + axis] - c < 0.0) std::swap(up, dn);
    const double su = V[4 * up + axis] - c, sd = V[4 * dn + axis] - c;
    const double mu = su / (su - sd);
    for (int d = 0; d < 3; ++d) {
      const double pu = V[4 * up + keep[d]], pd = V[4 * dn + keep[d]];
      out.mesh.V(v, d) = pu + mu * (pd - pu);
    }
    const Eigen::Vector3d nu = slice_normal3(normal4(up), axis_e), nd = slice_normal3(normal4(dn), axis_e);
    const Eigen::Vector3d n = nu + mu * (nd - nu);
    const double len = n.norm();
    out.mesh.N.row(v) = len > 0 ? Eigen::RowVector3d(n.transpose() / len) : Eigen::RowVector3d::Zero();
  }
  const int nf = static_cast<int>(corners.size() / 3);
  out.mesh.F.resize(nf, 3);
  for (int f = 0; f < nf; ++f)
    for (int j = 0; j < 3; ++j)
      out.mesh.F(f, j) = corner_vertex[3 * f + j];

  return out;
}

}  // namespace dfm
