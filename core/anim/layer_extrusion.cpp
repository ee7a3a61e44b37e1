#include "core/anim/layer_extrusion.h"

#include <algorithm>
#include <array>

namespace dfm {

MatrixX4iRow hull_facets_in(const Delaunay4& D, int first, int last) {
  std::vector<std::array<int, 4>> tets;
  for (Eigen::Index s = 0; s < D.simplices.rows(); ++s)
    for (int j = 0; j < 5; ++j) {
      if (D.neighbors(s, j) >= 0) continue;
      std::array<int, 4> t;
      bool inside = true;
      for (int i = 0, n = 0; i < 5; ++i) {
        if (i == j) continue;
        const int p = D.simplices(s, i);
        inside = inside && p >= first && p < last;
        t[n++] = p - first;
      }
      if (!inside) continue;
      std::sort(t.begin(), t.end());
      tets.push_back(t);
    }
  std::sort(tets.begin(), tets.end());
  tets.erase(std::unique(tets.begin(), tets.end()), tets.end());
  MatrixX4iRow K(static_cast<Eigen::Index>(tets.size()), 4);
  for (size_t i = 0; i < tets.size(); ++i)
    for (int c = 0; c < 4; ++c) K(static_cast<Eigen::Index>(i), c) = tets[i][c];
  return K;
}

}  // namespace dfm
