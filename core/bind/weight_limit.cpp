#include "core/bind/weight_limit.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "core/bind/handle_geometry.h"
#include "core/bind/surface_laplacian.h"
#include "core/util/error.h"

namespace dfm {
namespace {

using Keep = Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic>;

void check_sizes(const Eigen::MatrixXd& W, const Eigen::MatrixXd& V, const std::vector<bool>& fixed) {
  if (W.rows() != V.rows())
    throw Error("weights have " + std::to_string(W.rows()) + " rows for " + std::to_string(V.rows()) + " vertices");
  if (!fixed.empty() && fixed.size() != static_cast<size_t>(W.rows()))
    throw Error("fixed-row flags: " + std::to_string(fixed.size()) + " for " + std::to_string(W.rows()) + " rows");
}

int nonzeros(const Eigen::MatrixXd& W, int i) { return static_cast<int>((W.row(i).array() != 0).count()); }

// The vertices within `rings` edges of a seed (breadth first over K's pattern), seeds included.
std::vector<bool> near(const Eigen::SparseMatrix<double>& K, const std::vector<int>& seeds, int rings) {
  std::vector<bool> in(K.rows(), false);
  std::vector<int> front = seeds, next;
  for (int s : seeds) in[s] = true;
  for (int r = 0; r < rings && !front.empty(); ++r, front.swap(next)) {
    next.clear();
    for (int i : front)
      for (Eigen::SparseMatrix<double>::InnerIterator it(K, i); it; ++it)
        if (!in[it.row()]) in[it.row()] = true, next.push_back(static_cast<int>(it.row()));
  }
  return in;
}

// Minimizes t w^T K w + (w - w0)^T M (w - w0) over w on `free`, w = known elsewhere:
// (t K_FF + M_FF) w_F = M_FF w0_F - t K_FC w_C. Returns w_F in the order of `free`.
Eigen::VectorXd screened_solve(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& mass, double t,
                               const std::vector<int>& free, const Eigen::VectorXd& known, const Eigen::VectorXd& w0) {
  const int n = static_cast<int>(free.size());
  std::vector<int> local(K.rows(), -1);
  for (int a = 0; a < n; ++a) local[free[a]] = a;
  std::vector<Eigen::Triplet<double>> trip;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  for (int a = 0; a < n; ++a) {
    const int i = free[a];
    trip.emplace_back(a, a, mass(i));
    rhs(a) = mass(i) * w0(i);
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, i); it; ++it) {  // K symmetric: column i = row i
      const int b = local[it.row()];
      if (b >= 0) trip.emplace_back(a, b, t * it.value());
      else rhs(a) -= t * it.value() * known(it.row());
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(trip.begin(), trip.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
  if (solver.info() != Eigen::Success) throw Error("limit influences: the re-solve's matrix is not positive definite");
  return solver.solve(rhs);
}

}  // namespace

Keep kept_influences(const Eigen::MatrixXd& W, int k, const std::vector<bool>& fixed) {
  if (k < 1) throw Error("influences per vertex must be >= 1 (got " + std::to_string(k) + ")");
  Keep keep = W.array() != 0;
  std::vector<int> order(W.cols());
  for (int i = 0; i < W.rows(); ++i) {
    if ((!fixed.empty() && fixed[i]) || nonzeros(W, i) <= k) continue;
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return W(i, a) > W(i, b); });
    for (size_t r = k; r < order.size(); ++r) keep(i, order[r]) = false;
  }
  return keep;
}

Eigen::MatrixXd limit_influences(const Eigen::MatrixXd& W, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                 const std::vector<bool>& fixed, const LimitOptions& opts, LimitReport* report) {
  check_sizes(W, V, fixed);
  if (!(opts.radius >= 0) || !std::isfinite(opts.radius)) throw Error("limit influences: radius must be >= 0");
  const Keep keep = kept_influences(W, opts.k, fixed);
  const int nv = static_cast<int>(W.rows()), nh = static_cast<int>(W.cols());
  auto is_fixed = [&](int i) { return !fixed.empty() && fixed[i]; };
  LimitReport rep;
  for (int i = 0; i < nv; ++i)
    if (nonzeros(W, i) > opts.k) ++(is_fixed(i) ? rep.fixed_rows_over_k : rep.rows_limited);
  if (report) *report = rep;
  Eigen::MatrixXd out = W;
  std::vector<bool> changed(nv, false);
  for (int i = 0; i < nv; ++i)
    for (int j = 0; j < nh; ++j)
      if (!keep(i, j)) out(i, j) = 0, changed[i] = changed[i] || W(i, j) != 0;
  const Eigen::MatrixXd cut = out;
  if (rep.rows_limited > 0 && opts.radius > 0) {
    const Eigen::SparseMatrix<double> K = surface_cotangent_stiffness(V, F);
    const Eigen::VectorXd mass = surface_lumped_mass(V, F);
    const double h = mean_edge_length(V, F), t = (opts.radius * h) * (opts.radius * h);
    const int rings = static_cast<int>(std::ceil(3 * opts.radius));  // diffusion reaches ~exp(-3) that far
    for (int j = 0; j < nh; ++j) {
      std::vector<int> seeds;  // where w_j was cut
      for (int i = 0; i < nv; ++i)
        if (!keep(i, j) && W(i, j) != 0) seeds.push_back(i);
      if (seeds.empty()) continue;
      const std::vector<bool> reach = near(K, seeds, rings);
      std::vector<int> free;
      for (int i = 0; i < nv; ++i)
        if (reach[i] && keep(i, j) && W(i, j) != 0 && !is_fixed(i) && mass(i) > 0) free.push_back(i);
      if (free.empty()) continue;
      const Eigen::VectorXd w = screened_solve(K, mass, t, free, cut.col(j), W.col(j));
      for (size_t a = 0; a < free.size(); ++a) {
        const int i = free[a];
        out(i, j) = std::max(0.0, w(a));
        changed[i] = changed[i] || out(i, j) != W(i, j);
      }
    }
  }
  for (int i = 0; i < nv; ++i) {
    if (!changed[i]) continue;
    double s = out.row(i).sum();
    if (!(s > 1e-300)) out.row(i) = cut.row(i), s = cut.row(i).sum();  // nothing survived the re-solve
    if (s > 0) out.row(i) /= s;
  }
  return out;
}

}  // namespace dfm
