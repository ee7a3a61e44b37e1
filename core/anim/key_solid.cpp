#include "core/anim/key_solid.h"

#include <algorithm>
#include <unordered_map>

#include "core/util/error.h"

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

KeySolid::KeySolid(const std::vector<std::array<int, 4>>& tets, const Eigen::MatrixXi& surface,
                   const std::string& what, std::vector<int>* missing) {
  static const int kFace[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  // Triangle -> the (one or two) tets on it.
  std::unordered_map<SimplexKey, std::array<int, 2>, SimplexKeyHash> around;
  around.reserve(4 * tets.size());
  for (int t = 0; t < static_cast<int>(tets.size()); ++t)
    for (const auto& f : kFace) {
      const int tri[3] = {tets[t][f[0]], tets[t][f[1]], tets[t][f[2]]};
      auto [it, fresh] = around.emplace(simplex_key(tri, 3), std::array<int, 2>{t, -1});
      if (!fresh) it->second[1] = t;
    }
  std::unordered_set<SimplexKey, SimplexKeyHash>& on_surface = surface_;
  std::vector<int> absent;
  for (int f = 0; f < surface.rows(); ++f) {
    const int tri[3] = {surface(f, 0), surface(f, 1), surface(f, 2)};
    const SimplexKey k = simplex_key(tri, 3);
    if (!around.count(k)) absent.push_back(f);
    on_surface.insert(k);
  }
  if (!absent.empty()) {
    if (missing) *missing = absent;
    throw Error(what + ": " + std::to_string(absent.size()) + " surface triangles are not faces of the 4D Delaunay "
                "triangulation's key tetrahedra");
  }
  // Flood fill: hull triangles (one tet) seed their tet; crossing a surface triangle flips the side.
  std::vector<signed char> inside(tets.size(), -1);
  std::vector<int> queue;
  for (const auto& [k, ts] : around)
    if (ts[1] < 0 && inside[ts[0]] < 0) {
      inside[ts[0]] = on_surface.count(k) ? 1 : 0;
      queue.push_back(ts[0]);
    }
  for (size_t q = 0; q < queue.size(); ++q) {
    const int t = queue[q];
    for (const auto& f : kFace) {
      const int tri[3] = {tets[t][f[0]], tets[t][f[1]], tets[t][f[2]]};
      const SimplexKey k = simplex_key(tri, 3);
      const auto& ts = around.at(k);
      const int other = ts[0] == t ? ts[1] : ts[0];
      if (other < 0) continue;
      const signed char side = static_cast<signed char>(inside[t] ^ (on_surface.count(k) ? 1 : 0));
      if (inside[other] < 0) {
        inside[other] = side;
        queue.push_back(other);
      } else if (inside[other] != side) {
        throw Error(what + ": inside and outside of the surface are not separated (is it closed and free of "
                    "self-intersections?)");
      }
    }
  }
  static const int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (int t = 0; t < static_cast<int>(tets.size()); ++t) {
    if (inside[t] != 1) continue;
    ++inside_tets_;
    inside_.insert(simplex_key(tets[t].data(), 4));
    for (const auto& f : kFace) {
      const int tri[3] = {tets[t][f[0]], tets[t][f[1]], tets[t][f[2]]};
      inside_.insert(simplex_key(tri, 3));
    }
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
