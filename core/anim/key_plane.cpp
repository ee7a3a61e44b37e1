#include "core/anim/key_plane.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cstdlib>
#include <map>
#include <unordered_map>

#include "core/anim/delaunay_3d.h"
#include "core/anim/tet_faces.h"
#include "core/bind/winding_bvh.h"

namespace dfm {

namespace {

using Chain = std::unordered_map<Face, int, FaceHash>;
constexpr int kUnlabelled = INT_MIN;

std::array<int, 4> corners(const Eigen::MatrixXi& T, int t) { return {T(t, 0), T(t, 1), T(t, 2), T(t, 3)}; }

void add(Chain& chain, const Face& f, int sign) {
  const auto [g, s] = canonical(f);
  chain[g] += s * sign;
}

int coefficient(const Chain& chain, const Face& f) {
  const auto [g, s] = canonical(f);
  const auto it = chain.find(g);
  return it == chain.end() ? 0 : it->second * s;
}

// The manifold's vertices in the plane as key points (-1 elsewhere); false if one is at no key point.
bool plane_points(const MatrixX4dRow& V, double time, const KeyTets& key, std::vector<int>& point_of) {
  std::map<std::array<double, 3>, int> point_at;
  for (int p = 0; p < key.points.rows(); ++p) point_at[{key.points(p, 0), key.points(p, 1), key.points(p, 2)}] = p;
  point_of.assign(V.rows(), -1);
  for (int v = 0; v < V.rows(); ++v)
    if (V(v, 3) == time) {
      const auto it = point_at.find({V(v, 0), V(v, 1), V(v, 2)});
      if (it == point_at.end()) return false;
      point_of[v] = it->second;
    }
  return true;
}

// The level set's boundary in the plane as a chain on key points; lids by their sorted corners.
Chain plane_chain(const MatrixX4iRow& T, const std::vector<int>& point_of,
                  std::map<std::array<int, 4>, std::vector<int>>& lids) {
  Chain chain;
  for (int t = 0; t < T.rows(); ++t) {
    std::array<int, 4> p;
    int k = 0, off = -1;
    for (int c = 0; c < 4; ++c)
      if ((p[c] = point_of[T(t, c)]) >= 0) ++k;
      else off = c;
    if (k == 3) add(chain, oriented_face(p, off), 1);
    if (k < 4) continue;
    for (int i = 0; i < 4; ++i) add(chain, oriented_face(p, i), 1);
    std::sort(p.begin(), p.end());
    lids[p].push_back(t);
  }
  return chain;
}

// chain - sigma d(inside), sigma the orientation under which the chain and the key's surface agree on
// most faces (the level set's orientation convention against the tets'). Returns sigma.
int subtract_surface(Chain& chain, const KeyTets& key) {
  Chain surface;
  for (int t = 0; t < key.tets.rows(); ++t)
    if (key.inside[t])
      for (int i = 0; i < 4; ++i) add(surface, oriented_face(corners(key.tets, t), i), 1);
  int agree = 0, disagree = 0;
  for (const auto& [f, s] : surface) {
    const auto it = chain.find(f);
    if (s != 0 && it != chain.end() && it->second != 0) (it->second == s ? agree : disagree) += 1;
  }
  const int sigma = agree >= disagree ? 1 : -1;
  for (const auto& [f, s] : surface) chain[f] -= sigma * s;
  return sigma;
}

// Labels l with d(sum l_t t) = sigma D, by a walk from outside the hull (label 0): across a face
// the label drops by sigma D there (outward from the tet walked from).
std::vector<int> label_tets(const Chain& D, int sigma, const KeyTets& key, int& conflicts) {
  const int n = static_cast<int>(key.tets.rows());
  std::vector<int> label(n, kUnlabelled);
  std::vector<int> queue;
  for (int t = 0; t < n; ++t)
    for (int i = 0; i < 4 && label[t] == kUnlabelled; ++i)
      if (key.neighbours(t, i) < 0) {
        label[t] = sigma * coefficient(D, oriented_face(corners(key.tets, t), i));
        queue.push_back(t);
      }
  for (size_t q = 0; q < queue.size(); ++q) {
    const int a = queue[q];
    for (int i = 0; i < 4; ++i) {
      const int b = key.neighbours(a, i);
      const int want = label[a] - sigma * coefficient(D, oriented_face(corners(key.tets, a), i));
      if (b < 0) {
        conflicts += want != 0;
      } else if (label[b] == kUnlabelled) {
        label[b] = want;
        queue.push_back(b);
      } else {
        conflicts += label[b] != want;
      }
    }
  }
  return label;
}

}  // namespace

KeyTets key_tets(const ConformingSurface& s, const Eigen::VectorXd& fill_values) {
  KeyTets k;
  k.points.resize(s.V.rows() + s.fill.rows(), 3);
  k.points << s.V, s.fill;
  Tetrahedralization d = delaunay_3d(k.points);
  k.tets = std::move(d.tets);
  k.neighbours = std::move(d.neighbours);
  const WindingTree tree = build_winding_tree(s.V, s.F);
  k.inside.resize(k.tets.rows());
  for (Eigen::Index t = 0; t < k.tets.rows(); ++t) {
    Eigen::Vector3d m = Eigen::Vector3d::Zero();
    int fill = -1;
    for (int j = 0; j < 4; ++j) {
      const int p = k.tets(t, j);
      m += k.points.row(p).transpose() / 4;
      if (p >= s.V.rows()) fill = p - static_cast<int>(s.V.rows());
    }
    k.inside[t] = fill >= 0 ? fill_values[fill] < 0 : winding_number(tree, m) > 0.5;
  }
  return k;
}

KeyPlaneStats correct_key_plane(MatrixX4dRow& V, MatrixX4iRow& T, double time, const KeyTets& key) {
  KeyPlaneStats st;
  std::vector<int> point_of;
  if (!plane_points(V, time, key, point_of)) {
    st.conflicts = 1;
    return st;
  }
  std::map<std::array<int, 4>, std::vector<int>> lids;
  Chain D = plane_chain(T, point_of, lids);
  const int sigma = subtract_surface(D, key);
  const std::vector<int> label = label_tets(D, sigma, key, st.conflicts);

  std::vector<int> vertex_of(key.points.rows(), -1);
  for (int v = 0; v < V.rows(); ++v)
    if (point_of[v] >= 0) vertex_of[point_of[v]] = v;
  std::vector<char> drop(T.rows(), 0);
  std::vector<Eigen::RowVector4d> extra_v;
  std::vector<std::array<int, 4>> extra_t;
  auto vertex = [&](int p) {
    if (vertex_of[p] < 0) {
      vertex_of[p] = static_cast<int>(V.rows() + extra_v.size());
      extra_v.push_back(Eigen::RowVector4d(key.points(p, 0), key.points(p, 1), key.points(p, 2), time));
    }
    return vertex_of[p];
  };
  for (int t = 0; t < key.tets.rows(); ++t) {
    const int l = label[t];
    if (l == 0 || l == kUnlabelled) continue;
    if (std::abs(l) > 1) {
      ++st.conflicts;
      continue;
    }
    (key.inside[t] ? st.carved : st.bridges) += 1;
    // The lid whose boundary is -sigma l d(tet).
    std::array<int, 4> w = corners(key.tets, t);
    if (sigma * l > 0) std::swap(w[2], w[3]);
    std::array<int, 4> sorted = w;
    std::sort(sorted.begin(), sorted.end());
    bool cancelled = false;
    if (const auto it = lids.find(sorted); it != lids.end())
      for (int r : it->second) {
        std::array<int, 4> p;
        for (int c = 0; c < 4; ++c) p[c] = point_of[T(r, c)];
        if (!drop[r] && !same_orientation(p, w)) {
          drop[r] = 1;
          cancelled = true;
          break;
        }
      }
    if (cancelled) {
      ++st.cancelled;
      continue;
    }
    extra_t.push_back({vertex(w[0]), vertex(w[1]), vertex(w[2]), vertex(w[3])});
    ++st.added;
  }

  edit_tets(V, T, drop, extra_v, extra_t);
  return st;
}

}  // namespace dfm
