#include "core/anim/manifold_laplacian.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include "core/anim/primal_boundary_weights.h"
#include "core/util/error.h"

namespace dfm {

std::vector<char> manifold_boundary_rows(const AnimationManifold& m, const std::vector<int>& rows) {
  std::unordered_map<int, int> slot;
  for (size_t r = 0; r < rows.size(); ++r) slot.emplace(rows[r], static_cast<int>(r));
  // Every triangle with a row vertex, once per tetrahedron holding it: all those tetrahedra hold the
  // vertex, so the count is complete.
  std::vector<std::array<int, 3>> faces;
  for (int k = 0; k < m.num_tets(); ++k) {
    bool touches = false;
    for (int j = 0; j < 4; ++j) touches = touches || slot.count(m.T(k, j));
    if (!touches) continue;
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> f;
      for (int j = 0, c = 0; j < 4; ++j)
        if (j != skip) f[c++] = m.T(k, j);
      if (!slot.count(f[0]) && !slot.count(f[1]) && !slot.count(f[2])) continue;
      std::sort(f.begin(), f.end());
      faces.push_back(f);
    }
  }
  std::sort(faces.begin(), faces.end());
  std::vector<char> boundary(rows.size(), 0);
  for (size_t i = 0; i < faces.size();) {
    size_t j = i;
    while (j < faces.size() && faces[j] == faces[i]) ++j;
    if (j - i == 1)
      for (int v : faces[i]) {
        const auto it = slot.find(v);
        if (it != slot.end()) boundary[it->second] = 1;
      }
    i = j;
  }
  return boundary;
}

std::vector<LaplacianRow> manifold_laplacian_rows(const AnimationManifold& m, const std::vector<int>& rows,
                                                  LaplacianWeights scheme, double time_scale) {
  if (!(time_scale > 0) || !std::isfinite(time_scale))
    throw Error("manifold Laplacian: the time scale must be positive and finite");
  if (scheme == LaplacianWeights::Dual)
    throw Error("manifold Laplacian: the dual Laplacian has rows per tetrahedron (dual_laplacian_rows), not per vertex");
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
      Eigen::RowVector4d e = m.V.row(rows[r]) - m.V.row(j);
      e[3] *= time_scale;
      const double len = e.norm();
      if (!(len > 0)) throw Error("manifold Laplacian: vertices " + std::to_string(rows[r]) + " and " + std::to_string(j) +
                                  " coincide (a zero-length edge)");
      L[r].weights.push_back(1 / len);
      sum += 1 / len;
    }
    for (double& w : L[r].weights) w = scheme == LaplacianWeights::Equal ? 1.0 / nb.size() : w / sum;
  }
  if (scheme == LaplacianWeights::PrimalBoundary) {
    const std::vector<char> boundary = manifold_boundary_rows(m, rows);
    for (size_t r = 0; r < rows.size(); ++r) {
      if (!boundary[r]) continue;
      const std::vector<int>& nb = L[r].neighbours;
      Eigen::MatrixXd N(nb.size(), 4);
      for (size_t k = 0; k < nb.size(); ++k) N.row(k) = m.V.row(nb[k]);
      const Eigen::VectorXd w0 = Eigen::Map<const Eigen::VectorXd>(L[r].weights.data(), nb.size());
      PrimalWeightOptions o;
      o.xi = std::min(o.xi, 0.1 / nb.size());
      const Eigen::VectorXd w = primal_boundary_weights(m.V.row(rows[r]).transpose(), N, w0, o);
      L[r].weights.assign(w.data(), w.data() + w.size());
    }
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
