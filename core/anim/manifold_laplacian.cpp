#include "core/anim/manifold_laplacian.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/util/error.h"

namespace dfm {

std::vector<LaplacianRow> manifold_laplacian_rows(const AnimationManifold& m, const std::vector<int>& rows) {
  std::unordered_map<int, int> slot;
  slot.reserve(rows.size() * 2);
  for (size_t r = 0; r < rows.size(); ++r) slot.emplace(rows[r], static_cast<int>(r));
  std::vector<LaplacianRow> L(rows.size());
  for (int k = 0; k < m.num_tets(); ++k)
    for (int a = 0; a < 4; ++a) {
      const auto it = slot.find(m.T(k, a));
      if (it == slot.end()) continue;
      for (int b = 0; b < 4; ++b)
        if (b != a) L[it->second].neighbours.push_back(m.T(k, b));
    }
  for (size_t r = 0; r < rows.size(); ++r) {
    std::vector<int>& nb = L[r].neighbours;
    std::sort(nb.begin(), nb.end());
    nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
    if (nb.empty()) throw Error("manifold Laplacian: vertex " + std::to_string(rows[r]) + " is in no tetrahedron");
    double sum = 0;
    for (int j : nb) {
      const double len = (m.V.row(rows[r]) - m.V.row(j)).norm();
      if (!(len > 0)) throw Error("manifold Laplacian: vertices " + std::to_string(rows[r]) + " and " + std::to_string(j) +
                                  " coincide (a zero-length edge)");
      L[r].weights.push_back(1 / len);
      sum += 1 / len;
    }
    for (double& w : L[r].weights) w /= sum;
  }
  return L;
}

Eigen::MatrixXd differential_coordinates(const AnimationManifold& m, const std::vector<int>& rows,
                                         const std::vector<LaplacianRow>& L) {
  Eigen::MatrixXd D(rows.size(), 4);
  for (size_t r = 0; r < rows.size(); ++r) {
    Eigen::RowVector4d d = m.V.row(rows[r]);
    for (size_t k = 0; k < L[r].neighbours.size(); ++k) d -= L[r].weights[k] * m.V.row(L[r].neighbours[k]);
    D.row(r) = d;
  }
  return D;
}

}  // namespace dfm
