#include "core/mesh/red_green_refine.h"

#include <algorithm>
#include <map>
#include <string>
#include <utility>

#include "core/util/error.h"

namespace dfm {

namespace {

using Edge = std::pair<int, int>;

Edge edge_key(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

// The split edges: those of red triangles, after closing red over triangles with two split edges.
std::map<Edge, int> split_edges(const Eigen::MatrixXi& F, std::vector<char>& red) {
  for (;;) {
    std::map<Edge, int> cut;
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      if (red[static_cast<size_t>(f)])
        for (int j = 0; j < 3; ++j) cut.emplace(edge_key(F(f, j), F(f, (j + 1) % 3)), -1);
    bool grew = false;
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      if (red[static_cast<size_t>(f)]) continue;
      int c = 0;
      for (int j = 0; j < 3; ++j) c += static_cast<int>(cut.count(edge_key(F(f, j), F(f, (j + 1) % 3))));
      if (c >= 2) red[static_cast<size_t>(f)] = 1, grew = true;
    }
    if (!grew) return cut;
  }
}

}  // namespace

RedGreenRefinement red_green_refine(const Eigen::MatrixXi& F, int num_vertices, std::vector<char> red) {
  if (red.size() != static_cast<size_t>(F.rows()) || F.cols() != 3)
    throw Error("red-green refinement: " + std::to_string(red.size()) + " flags for " + std::to_string(F.rows()) +
                " triangles");
  if (F.size() > 0 && (F.minCoeff() < 0 || F.maxCoeff() >= num_vertices))
    throw Error("red-green refinement: a triangle index is outside the " + std::to_string(num_vertices) + " vertices");
  std::map<Edge, int> mid = split_edges(F, red);
  RedGreenRefinement out;
  for (auto& [e, id] : mid) {
    id = num_vertices + static_cast<int>(out.middles.size());
    out.middles.push_back({e.first, e.second});
  }
  std::vector<Eigen::RowVector3i> T;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const int a = F(f, 0), b = F(f, 1), c = F(f, 2);
    if (red[static_cast<size_t>(f)]) {
      const int ab = mid.at(edge_key(a, b)), bc = mid.at(edge_key(b, c)), ca = mid.at(edge_key(c, a));
      T.insert(T.end(), {{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}});
      continue;
    }
    int j = 0;
    while (j < 3 && !mid.count(edge_key(F(f, j), F(f, (j + 1) % 3)))) ++j;
    if (j == 3) {
      T.push_back({a, b, c});
      continue;
    }
    const int p = F(f, j), q = F(f, (j + 1) % 3), r = F(f, (j + 2) % 3), m = mid.at(edge_key(p, q));
    T.insert(T.end(), {{p, m, r}, {m, q, r}});
  }
  out.F.resize(static_cast<Eigen::Index>(T.size()), 3);
  for (size_t i = 0; i < T.size(); ++i) out.F.row(static_cast<Eigen::Index>(i)) = T[i];
  return out;
}

Eigen::MatrixXd append_middles(const Eigen::MatrixXd& V, const std::vector<std::array<int, 2>>& middles) {
  Eigen::MatrixXd out(V.rows() + static_cast<Eigen::Index>(middles.size()), V.cols());
  out.topRows(V.rows()) = V;
  for (size_t i = 0; i < middles.size(); ++i)
    out.row(V.rows() + static_cast<Eigen::Index>(i)) = 0.5 * (V.row(middles[i][0]) + V.row(middles[i][1]));
  return out;
}

}  // namespace dfm
