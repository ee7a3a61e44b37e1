#include "core/bind/monotone_groups.h"

#include <algorithm>

namespace dfm {
namespace {

int find_root(std::vector<int>& parent, int v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

}  // namespace

MonotoneGroups make_monotone_groups(int nf, const MonotoneProblem& p, const std::vector<char>& active) {
  const int nodes = nf + static_cast<int>(p.fixed_values.size());
  std::vector<int> parent(nodes), fixed(nodes, -1);
  for (int v = 0; v < nodes; ++v) parent[v] = v;
  for (int v = nf; v < nodes; ++v) fixed[v] = v - nf;
  MonotoneGroups g;
  g.tree.assign(p.constraints.size(), 0);
  for (size_t c = 0; c < p.constraints.size(); ++c) {
    if (!active[c]) continue;
    const int ra = find_root(parent, p.constraints[c].upper), rb = find_root(parent, p.constraints[c].lower);
    if (ra == rb) continue;
    if (fixed[ra] >= 0 && fixed[rb] >= 0) {
      ++g.conflicts;
      continue;
    }
    parent[rb] = ra;
    fixed[ra] = std::max(fixed[ra], fixed[rb]);
    g.tree[c] = 1;
  }
  g.root.resize(nodes);
  for (int v = 0; v < nodes; ++v) g.root[v] = find_root(parent, v);
  std::vector<int> id(nodes, -1);
  g.unknown.assign(nf, -1);
  g.value.assign(nf, 0.0);
  for (int v = 0; v < nf; ++v) {
    const int r = g.root[v];
    if (fixed[r] >= 0) {
      g.value[v] = p.fixed_values[fixed[r]];
    } else {
      if (id[r] < 0) id[r] = g.count++;
      g.unknown[v] = id[r];
    }
  }
  return g;
}

// Multipliers of the spanning-forest constraints from the gradient r = H x + g (stationarity
// r_i = sum_{c: upper = i} lambda_c - sum_{c: lower = i} lambda_c), leaves first; a fixed node, where no
// stationarity holds, is its group's root. Other constraints get 0.
std::vector<double> monotone_multipliers(const MonotoneProblem& p, const MonotoneGroups& gr, const Eigen::VectorXd& r) {
  const int nf = static_cast<int>(r.size()), nodes = static_cast<int>(gr.root.size());
  std::vector<std::vector<int>> edges(nodes);
  for (size_t c = 0; c < p.constraints.size(); ++c)
    if (gr.tree[c]) {
      edges[p.constraints[c].upper].push_back(static_cast<int>(c));
      edges[p.constraints[c].lower].push_back(static_cast<int>(c));
    }
  std::vector<int> order, parent_edge(nodes, -1);
  std::vector<char> seen(nodes, 0);
  order.reserve(nodes);
  auto visit_from = [&](int s) {  // breadth first over the forest
    seen[s] = 1;
    size_t q = order.size();
    order.push_back(s);
    for (; q < order.size(); ++q) {
      const int v = order[q];
      for (int c : edges[v]) {
        const int w = p.constraints[c].upper == v ? p.constraints[c].lower : p.constraints[c].upper;
        if (seen[w]) continue;
        seen[w] = 1, parent_edge[w] = c, order.push_back(w);
      }
    }
  };
  for (int v = nf; v < nodes; ++v) visit_from(v);  // fixed roots first
  for (int v = 0; v < nf; ++v)
    if (!seen[v]) visit_from(v);
  std::vector<double> S(nodes, 0.0), lambda(p.constraints.size(), 0.0);
  for (int v = 0; v < nf; ++v) S[v] = r[v];
  for (size_t q = order.size(); q-- > 0;) {
    const int v = order[q], c = parent_edge[v];
    if (c < 0) continue;
    const MonotoneConstraint& e = p.constraints[c];
    const int parent = e.upper == v ? e.lower : e.upper;
    lambda[c] = e.upper == v ? S[v] : -S[v];
    S[parent] -= e.upper == parent ? lambda[c] : -lambda[c];
  }
  return lambda;
}

}  // namespace dfm
