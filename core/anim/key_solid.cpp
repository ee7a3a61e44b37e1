#include "core/anim/key_solid.h"

#include <unordered_map>

#include "core/bind/winding_bvh.h"

namespace dfm {

SimplexKey simplex_key(const int* v, int count) {
  SimplexKey k = {-1, -1, -1, -1};
  for (int i = 0; i < count && i < 4; ++i) {  // insertion sort of at most 4
    int j = i;
    while (j > 0 && k[j - 1] > v[i]) k[j] = k[j - 1], --j;
    k[j] = v[i];
  }
  return k;
}

namespace {

constexpr int kFace[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
constexpr int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

SimplexKey face_key(const std::array<int, 4>& t, int f) {
  const int tri[3] = {t[kFace[f][0]], t[kFace[f][1]], t[kFace[f][2]]};
  return simplex_key(tri, 3);
}

// Exact inside/outside where every surface triangle is a face of the tets: a flood fill from the
// hull that flips across surface triangles. Empty when a surface triangle is missing or the fill
// contradicts itself.
std::vector<signed char> flood_fill(const std::vector<std::array<int, 4>>& tets, const Eigen::MatrixXi& F) {
  std::unordered_map<SimplexKey, std::array<int, 2>, SimplexKeyHash> around;  // triangle -> its tets
  around.reserve(4 * tets.size());
  for (int t = 0; t < static_cast<int>(tets.size()); ++t)
    for (int f = 0; f < 4; ++f) {
      auto [it, fresh] = around.emplace(face_key(tets[t], f), std::array<int, 2>{t, -1});
      if (!fresh) it->second[1] = t;
    }
  std::unordered_set<SimplexKey, SimplexKeyHash> on_surface;
  for (int f = 0; f < F.rows(); ++f) {
    const int tri[3] = {F(f, 0), F(f, 1), F(f, 2)};
    const SimplexKey k = simplex_key(tri, 3);
    if (!around.count(k)) return {};
    on_surface.insert(k);
  }
  std::vector<signed char> inside(tets.size(), -1);
  std::vector<int> queue;
  for (const auto& [k, ts] : around)
    if (ts[1] < 0 && inside[ts[0]] < 0) {
      inside[ts[0]] = on_surface.count(k) ? 1 : 0;
      queue.push_back(ts[0]);
    }
  for (size_t q = 0; q < queue.size(); ++q) {
    const int t = queue[q];
    for (int f = 0; f < 4; ++f) {
      const SimplexKey k = face_key(tets[t], f);
      const auto& ts = around.at(k);
      const int other = ts[0] == t ? ts[1] : ts[0];
      if (other < 0) continue;
      const signed char side = static_cast<signed char>(inside[t] ^ (on_surface.count(k) ? 1 : 0));
      if (inside[other] < 0) {
        inside[other] = side;
        queue.push_back(other);
      } else if (inside[other] != side) {
        return {};
      }
    }
  }
  return inside;
}

// Where the surface is not conforming: the generalized winding number at each tet's centroid.
std::vector<signed char> by_winding_number(const std::vector<std::array<int, 4>>& tets, const MatrixX4dRow& P,
                                           const TriMesh& surface) {
  Eigen::MatrixXd centroids(tets.size(), 3);
  for (size_t t = 0; t < tets.size(); ++t) {
    Eigen::RowVector3d c = Eigen::RowVector3d::Zero();
    for (int v : tets[t]) c += P.row(v).head<3>();
    centroids.row(static_cast<Eigen::Index>(t)) = c / 4;
  }
  const Eigen::VectorXd w = winding_numbers(build_winding_tree(surface.V, surface.F), centroids);
  std::vector<signed char> inside(tets.size());
  for (size_t t = 0; t < tets.size(); ++t) inside[t] = w[static_cast<Eigen::Index>(t)] >= 0.5;
  return inside;
}

}  // namespace

KeySolid::KeySolid(const std::vector<std::array<int, 4>>& tets, const MatrixX4dRow& P, const TriMesh& surface,
                   const Eigen::MatrixXi& surface_in_P) {
  std::vector<signed char> inside = flood_fill(tets, surface_in_P);
  exact_ = !inside.empty();
  if (!exact_) inside = by_winding_number(tets, P, surface);
  for (size_t t = 0; t < tets.size(); ++t) {
    if (inside[t] != 1) continue;
    ++inside_tets_;
    inside_.insert(simplex_key(tets[t].data(), 4));
    for (int f = 0; f < 4; ++f) inside_.insert(face_key(tets[t], f));
    for (const auto& e : kEdge) {
      const int ed[2] = {tets[t][e[0]], tets[t][e[1]]};
      inside_.insert(simplex_key(ed, 2));
    }
  }
}

bool KeySolid::contains(const int* v, int count) const {
  if (count == 1) return true;
  return inside_.count(simplex_key(v, count)) > 0;
}

}  // namespace dfm
