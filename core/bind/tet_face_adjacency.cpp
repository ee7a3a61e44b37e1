#include "core/bind/tet_face_adjacency.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>

namespace dfm {
namespace {

using Key = std::array<int, 3>;

Key sorted_key(int a, int b, int c) {
  Key k{a, b, c};
  std::sort(k.begin(), k.end());
  return k;
}

}  // namespace

TetFaceAdjacency tet_face_adjacency(const TetMesh& m) {
  // Sort all 4 #T faces by their vertex triple; equal neighbours are shared faces.
  struct Entry {
    Key key;
    int tet;
  };
  std::vector<Entry> all;
  all.reserve(static_cast<size_t>(m.T.rows()) * 4);
  for (int t = 0; t < m.T.rows(); ++t)
    for (int k = 0; k < 4; ++k)
      all.push_back({sorted_key(m.T(t, (k + 1) % 4), m.T(t, (k + 2) % 4), m.T(t, (k + 3) % 4)), t});
  std::sort(all.begin(), all.end(), [](const Entry& x, const Entry& y) {
    return x.key != y.key ? x.key < y.key : x.tet < y.tet;
  });
  std::vector<size_t> shared;  // index of the first entry of each face on exactly two tets
  for (size_t i = 0; i < all.size();) {
    size_t j = i + 1;
    while (j < all.size() && all[j].key == all[i].key) ++j;
    if (j - i == 2) shared.push_back(i);
    i = j;
  }
  TetFaceAdjacency adj;
  const int n = static_cast<int>(shared.size());
  adj.tets.resize(n, 2);
  adj.faces.resize(n, 3);
  adj.area.resize(n);
  for (int s = 0; s < n; ++s) {
    const Entry& e = all[shared[s]];
    adj.tets.row(s) << e.tet, all[shared[s] + 1].tet;
    adj.faces.row(s) << e.key[0], e.key[1], e.key[2];
    const Eigen::Vector3d a = m.V.row(e.key[0]), b = m.V.row(e.key[1]), c = m.V.row(e.key[2]);
    adj.area(s) = 0.5 * (b - a).cross(c - a).norm();
  }
  return adj;
}

std::vector<char> shared_faces_on_surface(const TetFaceAdjacency& adj, const Eigen::MatrixXi& F) {
  std::vector<Key> surface;
  surface.reserve(F.rows());
  for (int f = 0; f < F.rows(); ++f)
    if (F.row(f).minCoeff() >= 0) surface.push_back(sorted_key(F(f, 0), F(f, 1), F(f, 2)));
  std::sort(surface.begin(), surface.end());
  std::vector<char> on(adj.faces.rows(), 0);
  for (int s = 0; s < adj.faces.rows(); ++s)
    on[s] = std::binary_search(surface.begin(), surface.end(), Key{adj.faces(s, 0), adj.faces(s, 1), adj.faces(s, 2)});
  return on;
}

}  // namespace dfm
