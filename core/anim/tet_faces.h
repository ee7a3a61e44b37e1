#pragma once
// Oriented faces of tetrahedra, as chains: the boundary of [v0 v1 v2 v3] is
// [v1 v2 v3] - [v0 v2 v3] + [v0 v1 v3] - [v0 v1 v2], and a triangle is stored sorted with the sign of
// the sort, so that two tetrahedra on either side of a consistently oriented face give it opposite signs.
// And the one edit the key-time steps make to a manifold's tetrahedra.
#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include "core/anim/manifold.h"

namespace dfm {

using Face = std::array<int, 3>;

struct FaceHash {
  size_t operator()(const Face& f) const {
    return (static_cast<size_t>(f[0]) * 0x9E3779B97F4A7C15ull) ^ (static_cast<size_t>(f[1]) * 0xC2B2AE3D27D4EB4Full) ^
           static_cast<size_t>(f[2]);
  }
};

// The face of tet opposite corner i, with the orientation the tet's boundary gives it.
inline Face oriented_face(const std::array<int, 4>& tet, int i) {
  Face f;
  int k = 0;
  for (int c = 0; c < 4; ++c)
    if (c != i) f[k++] = tet[c];
  if (i % 2 == 1) std::swap(f[1], f[2]);
  return f;
}

// Sorted vertices and the parity of the sort (+1 even).
inline std::pair<Face, int> canonical(Face f) {
  int sign = 1;
  if (f[0] > f[1]) std::swap(f[0], f[1]), sign = -sign;
  if (f[1] > f[2]) std::swap(f[1], f[2]), sign = -sign;
  if (f[0] > f[1]) std::swap(f[0], f[1]), sign = -sign;
  return {f, sign};
}

// Whether b is an even permutation of a (the same four corners): the same orientation.
inline bool same_orientation(const std::array<int, 4>& a, const std::array<int, 4>& b) {
  int pos[4] = {0, 0, 0, 0};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (b[j] == a[i]) pos[i] = j;
  int inversions = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) inversions += pos[i] > pos[j];
  return inversions % 2 == 0;
}

// Drops the rows of T marked in drop, then appends the vertices extra_v and the tetrahedra extra_t
// (which may use them).
// In place: the manifolds are large, and a copy of T costs more than the edit.
inline void edit_tets(MatrixX4dRow& V, MatrixX4iRow& T, const std::vector<char>& drop,
                      const std::vector<Eigen::RowVector4d>& extra_v, const std::vector<std::array<int, 4>>& extra_t) {
  Eigen::Index r = 0;
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    if (!drop[static_cast<size_t>(t)]) {
      if (r != t) T.row(r) = T.row(t);
      ++r;
    }
  T.conservativeResize(r + static_cast<Eigen::Index>(extra_t.size()), 4);
  for (const auto& t : extra_t) T.row(r++) << t[0], t[1], t[2], t[3];
  const Eigen::Index nv = V.rows();
  V.conservativeResize(nv + static_cast<Eigen::Index>(extra_v.size()), 4);
  for (size_t k = 0; k < extra_v.size(); ++k) V.row(nv + static_cast<Eigen::Index>(k)) = extra_v[k];
}

}  // namespace dfm
