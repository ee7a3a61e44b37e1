#include "core/bind/monotone_constraints.h"

#include <algorithm>
#include <map>
#include <string>

#include "core/bind/bbw_system.h"
#include "core/bind/cholesky.h"
#include "core/util/error.h"

namespace dfm {

Eigen::MatrixXd monotone_representatives(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXi& b,
                                         const Eigen::MatrixXd& bc) {
  // Edge weights max(cot, 0) + a hundredth of the mean positive weight: positive on every tet edge, so
  // the discrete maximum principle holds and the graph stays connected.
  double sum = 0;
  long count = 0;
  for (int c = 0; c < K.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, c); it; ++it)
      if (it.row() != c && it.value() < 0) sum -= it.value(), ++count;
  const double floor = count ? 0.01 * sum / static_cast<double>(count) : 1.0;
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<size_t>(K.nonZeros()));
  for (int c = 0; c < K.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, c); it; ++it) {
      if (it.row() == c) continue;
      const double w = std::max(-it.value(), 0.0) + floor;
      trip.emplace_back(it.row(), c, -w);
      trip.emplace_back(c, c, w);
    }
  Eigen::SparseMatrix<double> L(K.rows(), K.cols());
  L.setFromTriplets(trip.begin(), trip.end());
  FreeSystem sys = split_free_fixed(std::move(L), b, bc);
  Eigen::MatrixXd U(K.rows(), bc.cols());
  for (int k = 0; k < b.size(); ++k) U.row(b(k)) = bc.row(k);
  if (sys.vertex.size() == 0) return U;
  SpdSolver chol;
  try {
    chol.factorize(sys.Qff);
  } catch (const Error&) {
    throw Error("monotone weights: a part of the volume touches no handle (its representative function is undefined)");
  }
  const Eigen::MatrixXd Uf = chol.solve(-sys.G);
  for (int k = 0; k < sys.vertex.size(); ++k) U.row(sys.vertex(k)) = Uf.row(k);
  return U;
}

MonotoneProblem monotone_problem(const std::vector<std::vector<int>>& neighbours, const Eigen::VectorXd& u,
                                 const Eigen::VectorXi& vertex, const Eigen::VectorXi& b, const Eigen::VectorXd& bc) {
  const int n = static_cast<int>(u.size()), nf = static_cast<int>(vertex.size());
  if (static_cast<int>(neighbours.size()) != n || bc.size() != b.size())
    throw Error("monotone weights: " + std::to_string(neighbours.size()) + " neighbour lists, " +
                std::to_string(n) + " vertices, " + std::to_string(bc.size()) + " values for " +
                std::to_string(b.size()) + " constrained vertices");
  MonotoneProblem p;
  std::map<double, int> value_node;
  auto fixed_node = [&](double v) {
    auto it = value_node.find(v);
    if (it != value_node.end()) return it->second;
    const int id = nf + static_cast<int>(p.fixed_values.size());
    p.fixed_values.push_back(v);
    value_node.emplace(v, id);
    return id;
  };
  std::vector<int> node(n, -1);
  for (int k = 0; k < nf; ++k) node[vertex(k)] = k;
  for (int k = 0; k < b.size(); ++k) node[b(k)] = fixed_node(bc(k));
  const int zero = fixed_node(0.0), one = fixed_node(1.0);
  for (int i = 0; i < n; ++i)
    if (node[i] < 0) throw Error("monotone weights: vertex " + std::to_string(i) + " is neither free nor constrained");
  std::vector<std::pair<int, int>> pairs;  // (upper, lower)
  pairs.reserve(2 * static_cast<size_t>(nf));
  for (int k = 0; k < nf; ++k) {
    const int i = vertex(k);
    int lo = -1, hi = -1;
    for (int j : neighbours[i]) {
      if (lo < 0 || u[j] < u[lo]) lo = j;
      if (hi < 0 || u[j] > u[hi]) hi = j;
    }
    // 5.3.3: the edges to u's smallest and greatest neighbour; without a strict one, the bound instead.
    if (lo >= 0 && u[lo] < u[i]) {
      pairs.emplace_back(k, node[lo]);
    } else {
      pairs.emplace_back(k, zero);
      ++p.free_without_neighbour;
    }
    if (hi >= 0 && u[hi] > u[i]) {
      pairs.emplace_back(node[hi], k);
    } else {
      pairs.emplace_back(one, k);
      ++p.free_without_neighbour;
    }
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  p.constraints.reserve(pairs.size());
  for (const auto& pr : pairs) p.constraints.push_back({pr.first, pr.second});
  return p;
}

}  // namespace dfm
