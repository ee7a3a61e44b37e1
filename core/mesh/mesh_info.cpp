#include "core/mesh/mesh_info.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <numeric>
#include <unordered_map>
#include <vector>

#include <Eigen/Geometry>

namespace dfm {
namespace {

// Directed half-edges keyed by their undirected edge, sorted so equal edges are adjacent.
struct HalfEdge {
  int lo, hi;
  bool forward;  // lo -> hi
  bool operator<(const HalfEdge& o) const { return lo != o.lo ? lo < o.lo : hi != o.hi ? hi < o.hi : forward < o.forward; }
};

std::vector<HalfEdge> sorted_half_edges(const Eigen::MatrixXi& F) {
  std::vector<HalfEdge> h;
  h.reserve(3 * F.rows());
  for (int f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      int a = F(f, c), b = F(f, (c + 1) % 3);
      if (a == b) continue;  // a collapsed edge of a degenerate face is no edge
      h.push_back({std::min(a, b), std::max(a, b), a < b});
    }
  std::sort(h.begin(), h.end());
  return h;
}

// Calls visit(first, count) for each run of half-edges on one undirected edge.
template <class Visit>
void for_each_edge(const std::vector<HalfEdge>& h, Visit visit) {
  for (size_t i = 0; i < h.size();) {
    size_t j = i;
    while (j < h.size() && h[j].lo == h[i].lo && h[j].hi == h[i].hi) ++j;
    visit(i, j - i);
    i = j;
  }
}

int find(std::vector<int>& p, int x) {
  while (p[x] != x) x = p[x] = p[p[x]];
  return x;
}

}  // namespace

BoundingBox bounding_box(const Eigen::MatrixXd& V) {
  BoundingBox b;
  if (V.rows() == 0) return b;
  b.min = V.colwise().minCoeff().transpose();
  b.max = V.colwise().maxCoeff().transpose();
  return b;
}

std::vector<std::vector<int>> vertex_neighbours(const Eigen::MatrixXi& elements, int num_vertices) {
  std::vector<std::vector<int>> nb(num_vertices);
  for (Eigen::Index e = 0; e < elements.rows(); ++e)
    for (Eigen::Index a = 0; a < elements.cols(); ++a)
      for (Eigen::Index c = 0; c < elements.cols(); ++c)
        if (a != c) nb[elements(e, a)].push_back(elements(e, c));
  for (auto& n : nb) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  return nb;
}

Eigen::VectorXi face_components(const Eigen::MatrixXi& F) {
  const int nv = F.size() ? F.maxCoeff() + 1 : 0;
  std::vector<int> parent(nv);
  std::iota(parent.begin(), parent.end(), 0);
  for (int f = 0; f < F.rows(); ++f)
    for (int c = 1; c < 3; ++c) parent[find(parent, F(f, c))] = find(parent, F(f, 0));
  std::unordered_map<int, int> id;
  Eigen::VectorXi comp(F.rows());
  for (int f = 0; f < F.rows(); ++f) comp(f) = id.emplace(find(parent, F(f, 0)), static_cast<int>(id.size())).first->second;
  return comp;
}

int connected_component_count(const Eigen::MatrixXi& F) {
  Eigen::VectorXi c = face_components(F);
  return c.size() ? c.maxCoeff() + 1 : 0;
}

int unreferenced_vertex_count(int num_vertices, const Eigen::MatrixXi& F) {
  std::vector<char> used(num_vertices, 0);
  for (int i = 0; i < F.size(); ++i)
    if (F.data()[i] >= 0 && F.data()[i] < num_vertices) used[F.data()[i]] = 1;
  return static_cast<int>(std::count(used.begin(), used.end(), 0));
}

int boundary_edge_count(const Eigen::MatrixXi& F) {
  int n = 0;
  for_each_edge(sorted_half_edges(F), [&](size_t, size_t k) { n += k == 1; });
  return n;
}

int non_manifold_edge_count(const Eigen::MatrixXi& F) {
  int n = 0;
  for_each_edge(sorted_half_edges(F), [&](size_t, size_t k) { n += k > 2; });
  return n;
}

int inconsistent_edge_count(const Eigen::MatrixXi& F) {
  auto h = sorted_half_edges(F);
  int n = 0;
  for_each_edge(h, [&](size_t i, size_t k) { n += k == 2 && h[i].forward == h[i + 1].forward; });
  return n;
}

// Linear time (half-edges bucketed by their first vertex, instead of sorted): the viewport checks
// every playback interval's slice with it.
bool is_closed(const Eigen::MatrixXi& F) {
  if (F.rows() == 0 || F.minCoeff() < 0) return false;
  const int nv = F.maxCoeff() + 1;
  std::vector<int> start(nv + 1, 0);
  for (Eigen::Index i = 0; i < F.size(); ++i) ++start[F.data()[i] + 1];  // each vertex starts 1 half-edge per corner
  for (int v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<int> to(start.back()), fill(start.begin(), start.end() - 1);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      if (a == b) return false;  // a degenerate face: its edge (a, a) has no partner
      to[fill[a]++] = b;
    }
  auto count = [&](int a, int b) { return std::count(to.begin() + start[a], to.begin() + start[a + 1], b); };
  // Each half-edge a -> b is the only one from a to b, and exactly one goes back from b to a.
  for (int a = 0; a < nv; ++a)
    for (int i = start[a]; i < start[a + 1]; ++i)
      if (count(a, to[i]) != 1 || count(to[i], a) != 1) return false;
  return true;
}

int duplicate_vertex_count(const Eigen::MatrixXd& V, double tol) {
  // Hash grid with cells of size tol (exact coordinates when tol == 0); a vertex is a duplicate when a
  // vertex before it lies within tol, searched in the 27 neighbouring cells.
  struct H {
    size_t operator()(const std::array<long long, 3>& k) const {
      const uint64_t x = uint64_t(k[0]) * 73856093u, y = uint64_t(k[1]) * 19349663u, z = uint64_t(k[2]) * 83492791u;
      return std::hash<uint64_t>()(x ^ y ^ z);  // unsigned: wraps instead of overflowing
    }
  };
  struct HD {
    size_t operator()(const std::array<double, 3>& k) const {
      return std::hash<double>()(k[0]) ^ (std::hash<double>()(k[1]) << 1) ^ (std::hash<double>()(k[2]) << 2);
    }
  };
  int dups = 0;
  if (tol <= 0) {
    std::unordered_map<std::array<double, 3>, int, HD> seen;
    for (int i = 0; i < V.rows(); ++i) dups += !seen.emplace(std::array<double, 3>{V(i, 0) + 0.0, V(i, 1) + 0.0, V(i, 2) + 0.0}, i).second;
    return dups;
  }
  std::unordered_map<std::array<long long, 3>, std::vector<int>, H> grid;
  for (int i = 0; i < V.rows(); ++i) {
    std::array<long long, 3> k;
    for (int c = 0; c < 3; ++c)  // clamped: huge coordinates / tiny tol must not overflow the cast
      k[c] = static_cast<long long>(std::clamp(std::floor(V(i, c) / tol), -1e15, 1e15));
    bool dup = false;
    for (int dx = -1; dx <= 1 && !dup; ++dx)
      for (int dy = -1; dy <= 1 && !dup; ++dy)
        for (int dz = -1; dz <= 1 && !dup; ++dz) {
          auto it = grid.find({k[0] + dx, k[1] + dy, k[2] + dz});
          if (it == grid.end()) continue;
          for (int j : it->second)
            if ((V.row(i) - V.row(j)).norm() <= tol) dup = true;
        }
    dups += dup;
    grid[k].push_back(i);
  }
  return dups;
}

int degenerate_face_count(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, double rel_eps) {
  const double d = bounding_box(V).diagonal().norm();
  int n = 0;
  for (int f = 0; f < F.rows(); ++f) {
    const int a = F(f, 0), b = F(f, 1), c = F(f, 2);
    if (a == b || b == c || a == c) {
      ++n;
      continue;
    }
    Eigen::Vector3d e1 = V.row(b) - V.row(a), e2 = V.row(c) - V.row(a);
    n += 0.5 * e1.cross(e2).norm() <= rel_eps * d * d;
  }
  return n;
}

double signed_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  double vol = 0;
  for (int f = 0; f < F.rows(); ++f) {
    Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    vol += a.dot(b.cross(c));
  }
  return vol / 6.0;
}

bool is_closed_outward(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  return is_closed(F) && signed_volume(V, F) > 0;
}

Eigen::MatrixXi tet_boundary_faces(const Eigen::MatrixXi& T) {
  // Faces of a positively oriented tet (0,1,2,3), each counter-clockwise seen from outside.
  static const int face[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  if (T.rows() == 0) return Eigen::MatrixXi(0, 3);
  // Faces bucketed by their smallest vertex (a counting sort), then matched inside each small bucket:
  // linear time, where one sort of all 4 #T faces dominates on large meshes. The output is in the order
  // of the sorted vertex triples.
  const long lo = T.minCoeff(), n = static_cast<long>(T.maxCoeff()) - lo + 1;
  const long nf = 4 * static_cast<long>(T.rows());
  struct Face {
    int b, c;  // the two larger vertices of the sorted triple
    long id;   // 4 * tet + face
  };
  std::vector<long> start(n + 1, 0);
  auto sorted_key = [&](long id) {
    std::array<int, 3> k = {T(id / 4, face[id % 4][0]), T(id / 4, face[id % 4][1]), T(id / 4, face[id % 4][2])};
    if (k[0] > k[1]) std::swap(k[0], k[1]);
    if (k[1] > k[2]) std::swap(k[1], k[2]);
    if (k[0] > k[1]) std::swap(k[0], k[1]);
    return k;
  };
  for (long id = 0; id < nf; ++id) ++start[sorted_key(id)[0] - lo + 1];
  for (long v = 0; v < n; ++v) start[v + 1] += start[v];
  std::vector<Face> faces(nf);
  std::vector<long> fill(start.begin(), start.end() - 1);
  for (long id = 0; id < nf; ++id) {
    const std::array<int, 3> k = sorted_key(id);
    faces[fill[k[0] - lo]++] = {k[1], k[2], id};
  }
  std::vector<std::array<int, 3>> out;
  for (long v = 0; v < n; ++v) {
    const auto first = faces.begin() + start[v], last = faces.begin() + start[v + 1];
    std::sort(first, last, [](const Face& x, const Face& y) { return x.b != y.b ? x.b < y.b : x.c < y.c; });
    for (auto i = first; i != last;) {
      auto j = i;
      while (j != last && j->b == i->b && j->c == i->c) ++j;
      if (j - i == 1) {
        const long t = i->id / 4, f = i->id % 4;
        out.push_back({T(t, face[f][0]), T(t, face[f][1]), T(t, face[f][2])});
      }
      i = j;
    }
  }
  Eigen::MatrixXi B(out.size(), 3);
  for (size_t i = 0; i < out.size(); ++i) B.row(i) << out[i][0], out[i][1], out[i][2];
  return B;
}

TriMesh tet_boundary_surface(const TetMesh& tets, Eigen::VectorXi* to_tet) {
  Eigen::MatrixXi F = tet_boundary_faces(tets.T);
  std::vector<int> remap(tets.num_vertices(), -1), back;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      int& v = F(f, k);
      if (remap[v] < 0) remap[v] = static_cast<int>(back.size()), back.push_back(v);
      v = remap[v];
    }
  TriMesh m;
  m.V.resize(back.size(), 3);
  for (size_t i = 0; i < back.size(); ++i) m.V.row(i) = tets.V.row(back[i]);
  m.F = F;
  if (to_tet) *to_tet = Eigen::Map<Eigen::VectorXi>(back.data(), back.size());
  return m;
}

static double tet_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, int t) {
  Eigen::Vector3d a = V.row(T(t, 0)), b = V.row(T(t, 1)), c = V.row(T(t, 2)), d = V.row(T(t, 3));
  return (b - a).cross(c - a).dot(d - a) / 6.0;
}

int non_positive_tet_count(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  int n = 0;
  for (int t = 0; t < T.rows(); ++t) n += tet_volume(V, T, t) <= 0;
  return n;
}

double tet_mesh_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  double v = 0;
  for (int t = 0; t < T.rows(); ++t) v += tet_volume(V, T, t);
  return v;
}

}  // namespace dfm
