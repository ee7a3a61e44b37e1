#include "core/bind/monotone_qp.h"

#include <algorithm>
#include <cstdint>
#include <set>
#include <string>

#include "core/bind/cholesky.h"
#include "core/util/error.h"

namespace dfm {
namespace {

int find_root(std::vector<int>& parent, int v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

// The groups an active set makes: free variables joined by active constraints share one unknown, or
// the fixed value their group reaches. tree[c]: c joined two groups (a spanning forest of the active set).
struct Groups {
  std::vector<int> root;     // per node (free and fixed): its group's union-find root
  std::vector<int> unknown;  // per free variable: reduced index, or -1 when fixed
  std::vector<double> value; // per free variable with unknown -1: its fixed value
  std::vector<char> tree;
  int count = 0;
  int conflicts = 0;  // active constraints that would join two different fixed values (left out)
};

Groups make_groups(int nf, const MonotoneProblem& p, const std::vector<char>& active) {
  const int nodes = nf + static_cast<int>(p.fixed_values.size());
  std::vector<int> parent(nodes), fixed(nodes, -1);
  for (int v = 0; v < nodes; ++v) parent[v] = v;
  for (int v = nf; v < nodes; ++v) fixed[v] = v - nf;
  Groups g;
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

// min over x = P z (+ fixed values) of 1/2 x^T H x + g^T x: the reduced system P^T H P z = rhs.
Eigen::VectorXd solve_reduced(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& g, const Groups& gr) {
  const int nf = static_cast<int>(H.rows());
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(gr.count);
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<size_t>(H.nonZeros()));
  for (int c = 0; c < nf; ++c) {
    const int gc = gr.unknown[c];
    if (gc < 0) continue;
    rhs[gc] -= g[c];
    for (Eigen::SparseMatrix<double>::InnerIterator it(H, c); it; ++it) {
      const int r = static_cast<int>(it.row()), gg = gr.unknown[r];
      if (gg >= 0)
        trip.emplace_back(gg, gc, it.value());
      else
        rhs[gc] -= it.value() * gr.value[r];
    }
  }
  Eigen::VectorXd x(nf);
  if (gr.count) {
    Eigen::SparseMatrix<double> R(gr.count, gr.count);
    R.setFromTriplets(trip.begin(), trip.end());
    SpdSolver chol;
    chol.factorize(R);
    const Eigen::VectorXd z = chol.solve(rhs);
    for (int v = 0; v < nf; ++v) x[v] = gr.unknown[v] >= 0 ? z[gr.unknown[v]] : gr.value[v];
  } else {
    for (int v = 0; v < nf; ++v) x[v] = gr.value[v];
  }
  return x;
}

// Multipliers of the spanning-forest constraints from the gradient r = H x + g (stationarity
// r_i = sum_{c: upper = i} lambda_c - sum_{c: lower = i} lambda_c), leaves first; a fixed node, where no
// stationarity holds, is its group's root. Other constraints get 0.
std::vector<double> multipliers(const MonotoneProblem& p, const Groups& gr, const Eigen::VectorXd& r) {
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

std::uint64_t hash_of(const std::vector<char>& active) {
  std::uint64_t h = 1469598103934665603ull;
  for (size_t c = 0; c < active.size(); ++c)
    if (active[c]) h = (h ^ (c + 0x9e3779b97f4a7c15ull)) * 1099511628211ull;
  return h;
}

}  // namespace

MonotoneQPResult solve_monotone_qp(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& g,
                                   const MonotoneProblem& p, const Eigen::VectorXd& x0, double tolerance,
                                   const std::atomic<bool>* cancel, int max_iterations) {
  const int nf = static_cast<int>(H.rows());
  if (g.size() != nf || (x0.size() && x0.size() != nf))
    throw Error("monotone QP: " + std::to_string(g.size()) + " linear terms and a start of " +
                std::to_string(x0.size()) + " for " + std::to_string(nf) + " variables");
  const int nodes = nf + static_cast<int>(p.fixed_values.size());
  for (const MonotoneConstraint& c : p.constraints)
    if (c.upper < 0 || c.upper >= nodes || c.lower < 0 || c.lower >= nodes)
      throw Error("monotone QP: a constraint names node " + std::to_string(std::max(c.upper, c.lower)) +
                  " of " + std::to_string(nodes));
  const double scale = nf ? H.diagonal().mean() : 1.0;
  auto node_value = [&](const Eigen::VectorXd& x, int v) { return v < nf ? x[v] : p.fixed_values[v - nf]; };
  const size_t nc = p.constraints.size();
  std::vector<char> active(nc, 0);
  if (x0.size())
    for (size_t c = 0; c < nc; ++c)
      active[c] = node_value(x0, p.constraints[c].upper) <= node_value(x0, p.constraints[c].lower);
  MonotoneQPResult res;
  std::set<std::uint64_t> seen;
  bool add_only = false;
  for (;;) {
    if (cancel && cancel->load()) throw Error("cancelled");
    const Groups gr = make_groups(nf, p, active);
    res.x = solve_reduced(H, g, gr);
    ++res.iterations;
    if (add_only) ++res.add_only_iterations;
    const Eigen::VectorXd r = H * res.x + g;
    const std::vector<double> lambda = multipliers(p, gr, r);
    std::vector<char> next = active;
    bool changed = false;
    double worst = 0;
    for (size_t c = 0; c < nc; ++c) {
      const MonotoneConstraint& e = p.constraints[c];
      if (active[c]) {
        const double l = lambda[c] / scale;
        worst = std::max(worst, -l);
        if (!add_only && gr.tree[c] && l < -tolerance) next[c] = 0, changed = true;
      } else if (node_value(res.x, e.upper) < node_value(res.x, e.lower)) {
        next[c] = 1, changed = true;
      }
    }
    res.dual_residual = worst;
    res.groups = gr.count;
    if (!changed) {
      res.optimal = worst <= tolerance && gr.conflicts == 0;
      break;
    }
    if (!add_only && (!seen.insert(hash_of(active)).second || res.iterations >= max_iterations)) {
      // A repeated active set (or the cap): from here on only add violated constraints.
      add_only = true;
      for (size_t c = 0; c < nc; ++c)
        if (active[c]) next[c] = 1;
    }
    active.swap(next);
  }
  res.active = static_cast<int>(std::count(active.begin(), active.end(), 1));
  return res;
}

}  // namespace dfm
