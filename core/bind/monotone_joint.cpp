#include "core/bind/monotone_joint.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <string>

#include "core/bind/cholesky.h"
#include "core/bind/monotone_groups.h"
#include "core/util/error.h"
#include "core/util/hash.h"

namespace dfm {
namespace {

struct JointSolve {
  Eigen::MatrixXd X;   // #free x #handles
  Eigen::VectorXd mu;  // per free vertex: the multiplier of its row sum (0 where every entry is fixed)
  double sum_residual = 0;
};

// min sum_j 1/2 x_j^T H x_j + g_j^T x_j over x_j = P_j z_j (+ fixed values) with sum_j x_ij = 1: the method of
// multipliers, (A + rho C^T C) z = b - C^T (mu - rho d), mu += rho (C z - d), on one factorization.
JointSolve solve_joint_reduced(const Eigen::SparseMatrix<double>& H, const Eigen::MatrixXd& G,
                               const std::vector<MonotoneGroups>& gr, double scale) {
  const int nf = static_cast<int>(H.rows()), m = static_cast<int>(G.cols());
  std::vector<int> offset(m + 1, 0);
  for (int j = 0; j < m; ++j) offset[j + 1] = offset[j] + gr[j].count;
  const int nz = offset[m];
  Eigen::VectorXd b = Eigen::VectorXd::Zero(nz), d = Eigen::VectorXd::Ones(nf);
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<size_t>(H.nonZeros()) * m);
  for (int j = 0; j < m; ++j) {
    const MonotoneGroups& g = gr[j];
    for (int c = 0; c < nf; ++c) {
      const int gc = g.unknown[c];
      if (gc < 0) {
        d[c] -= g.value[c];
        continue;
      }
      b[offset[j] + gc] -= G(c, j);
      for (Eigen::SparseMatrix<double>::InnerIterator it(H, c); it; ++it) {
        const int r = static_cast<int>(it.row()), gg = g.unknown[r];
        if (gg >= 0)
          trip.emplace_back(offset[j] + gg, offset[j] + gc, it.value());
        else
          b[offset[j] + gc] -= it.value() * g.value[r];
      }
    }
  }
  const double rho = 1e3 * scale;  // large enough that a few steps reach round-off
  std::vector<int> cols;
  std::vector<char> has_row(nf, 0);
  for (int k = 0; k < nf; ++k) {
    cols.clear();
    for (int j = 0; j < m; ++j)
      if (gr[j].unknown[k] >= 0) cols.push_back(offset[j] + gr[j].unknown[k]);
    has_row[k] = !cols.empty();
    for (int a : cols)
      for (int c : cols) trip.emplace_back(a, c, rho);
  }
  JointSolve out;
  out.mu = Eigen::VectorXd::Zero(nf);
  auto fill_x = [&](const Eigen::VectorXd& z) {
    out.X.resize(nf, m);
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < nf; ++k)
        out.X(k, j) = gr[j].unknown[k] >= 0 ? z[offset[j] + gr[j].unknown[k]] : gr[j].value[k];
  };
  if (nz == 0) {
    fill_x(Eigen::VectorXd());
  } else {
    Eigen::SparseMatrix<double> R(nz, nz);
    R.setFromTriplets(trip.begin(), trip.end());
    SpdSolver chol;
    chol.factorize(R);
    for (int step = 0; step < 100; ++step) {
      Eigen::VectorXd rhs = b;
      for (int j = 0; j < m; ++j)
        for (int k = 0; k < nf; ++k)
          if (gr[j].unknown[k] >= 0) rhs[offset[j] + gr[j].unknown[k]] -= out.mu[k] - rho * d[k];
      fill_x(chol.solve(rhs));
      double worst = 0;
      for (int k = 0; k < nf; ++k) {
        if (!has_row[k]) continue;
        const double res = out.X.row(k).sum() - 1.0;
        out.mu[k] += rho * res;
        worst = std::max(worst, std::abs(res));
      }
      if (worst <= 1e-14) break;
    }
  }
  for (int k = 0; k < nf; ++k) out.sum_residual = std::max(out.sum_residual, std::abs(out.X.row(k).sum() - 1.0));
  return out;
}

// The active sets' bytes, concatenated (fixed sizes, so positions are unambiguous): a repeat detector.
std::uint64_t hash_of(const std::vector<std::vector<char>>& active) {
  std::uint64_t h = kFnv1aBasis;
  for (const auto& a : active) h = fnv1a(h, a.data(), a.size());
  return h;
}

}  // namespace

MonotoneJointResult solve_monotone_joint(const Eigen::SparseMatrix<double>& H, const Eigen::MatrixXd& G,
                                         const std::vector<MonotoneProblem>& problems, const Eigen::MatrixXd& X0,
                                         double tolerance, const std::atomic<bool>* cancel, int max_iterations) {
  const int nf = static_cast<int>(H.rows()), m = static_cast<int>(G.cols());
  if (G.rows() != nf || static_cast<int>(problems.size()) != m || X0.rows() != nf || X0.cols() != m)
    throw Error("monotone joint QP: " + std::to_string(G.rows()) + "x" + std::to_string(m) + " linear terms, " +
                std::to_string(problems.size()) + " problems and a " + std::to_string(X0.rows()) + "x" +
                std::to_string(X0.cols()) + " start for " + std::to_string(nf) + " variables");
  const double scale = nf ? H.diagonal().mean() : 1.0;
  auto node_value = [&](const Eigen::MatrixXd& X, int j, int v) {
    return v < nf ? X(v, j) : problems[j].fixed_values[v - nf];
  };
  std::vector<std::vector<char>> active(m);
  for (int j = 0; j < m; ++j) {
    const auto& cs = problems[j].constraints;
    active[j].assign(cs.size(), 0);
    for (size_t c = 0; c < cs.size(); ++c)
      active[j][c] = node_value(X0, j, cs[c].upper) <= node_value(X0, j, cs[c].lower);
  }
  MonotoneJointResult res;
  std::set<std::uint64_t> seen;
  bool add_only = false;
  std::vector<MonotoneGroups> gr(m);
  for (;;) {
    if (cancel && cancel->load()) throw Cancelled();
    int conflicts = 0;
    for (int j = 0; j < m; ++j) {
      gr[j] = make_monotone_groups(nf, problems[j], active[j]);
      conflicts += gr[j].conflicts;
    }
    JointSolve js = solve_joint_reduced(H, G, gr, scale);
    res.X = std::move(js.X);
    res.sum_residual = js.sum_residual;
    ++res.iterations;
    if (add_only) ++res.add_only_iterations;
    bool changed = false;
    double worst = 0;
    int violated = 0;
    std::vector<std::vector<char>> next = active;
    for (int j = 0; j < m; ++j) {
      const MonotoneProblem& p = problems[j];
      const Eigen::VectorXd r = H * res.X.col(j) + G.col(j) + js.mu;
      const std::vector<double> lambda = monotone_multipliers(p, gr[j], r);
      for (size_t c = 0; c < p.constraints.size(); ++c) {
        const MonotoneConstraint& e = p.constraints[c];
        if (active[j][c]) {
          const double l = lambda[c] / scale;
          worst = std::max(worst, -l);
          if (!add_only && gr[j].tree[c] && l < -tolerance) next[j][c] = 0, changed = true;
        } else if (node_value(res.X, j, e.upper) < node_value(res.X, j, e.lower)) {
          next[j][c] = 1, changed = true, ++violated;
        }
      }
    }
    res.dual_residual = worst;
    if (!changed) {
      res.feasible = conflicts == 0 && res.sum_residual <= 1e-12;
      res.optimal = res.feasible && worst <= tolerance;
      break;
    }
    if (!add_only && (!seen.insert(hash_of(active)).second || res.iterations >= max_iterations)) {
      add_only = true;
      for (int j = 0; j < m; ++j)
        for (size_t c = 0; c < active[j].size(); ++c)
          if (active[j][c]) next[j][c] = 1;
    }
    if (res.iterations >= 4 * max_iterations + 50) break;  // not feasible: the caller falls back
    active.swap(next);
  }
  return res;
}

}  // namespace dfm
