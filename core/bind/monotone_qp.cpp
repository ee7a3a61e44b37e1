#include "core/bind/monotone_qp.h"

#include <algorithm>
#include <cstdint>
#include <set>
#include <string>

#include "core/bind/cholesky.h"
#include "core/bind/monotone_groups.h"
#include "core/util/error.h"
#include "core/util/hash.h"

namespace dfm {
namespace {

// min over x = P z (+ fixed values) of 1/2 x^T H x + g^T x: the reduced system P^T H P z = rhs.
Eigen::VectorXd solve_reduced(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& g, const MonotoneGroups& gr) {
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

std::uint64_t hash_of(const std::vector<char>& active) { return fnv1a(kFnv1aBasis, active.data(), active.size()); }

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
    if (cancel && cancel->load()) throw Cancelled();
    const MonotoneGroups gr = make_monotone_groups(nf, p, active);
    res.x = solve_reduced(H, g, gr);
    ++res.iterations;
    if (add_only) ++res.add_only_iterations;
    const Eigen::VectorXd r = H * res.x + g;
    const std::vector<double> lambda = monotone_multipliers(p, gr, r);
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
