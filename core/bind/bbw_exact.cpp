#include "core/bind/bbw_exact.h"

#include "core/util/hash.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_set>
#include <vector>

#include "core/bind/qp.h"
#include "core/util/error.h"

namespace dfm {
namespace {

using Status = Eigen::Matrix<signed char, Eigen::Dynamic, Eigen::Dynamic>;  // -1 at 0, +1 at 1, 0 free

// Minimizer with the active entries at their bounds and each row's free entries summing to 1 - (fixed).
// The pivot of each row (its largest free entry in `xcur`) is eliminated through the sum constraint.
void solve_face(const Eigen::SparseMatrix<double>& H, const Eigen::MatrixXd& G, const Status& st,
                const Eigen::MatrixXd& xcur, Eigen::MatrixXd& out, std::vector<int>& pivot) {
  const int n = static_cast<int>(G.rows()), m = static_cast<int>(G.cols());
  pivot.assign(n, -1);
  Eigen::MatrixXd xa = Eigen::MatrixXd::Zero(n, m);
  Eigen::VectorXd c = Eigen::VectorXd::Zero(n);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i)
      if (st(i, j) > 0) xa(i, j) = 1.0, c(i) += 1.0;
  for (int i = 0; i < n; ++i) {
    double best = -std::numeric_limits<double>::infinity();
    for (int j = 0; j < m; ++j)
      if (st(i, j) == 0 && xcur(i, j) > best) best = xcur(i, j), pivot[i] = j;
    if (pivot[i] < 0) throw Error("exact partition of unity: a row without free entries");
  }
  // Unfixed entries per handle (local numbering), reduced unknowns (non-pivot free entries).
  std::vector<std::vector<int>> rows(m);
  std::vector<int> uoff(m + 1, 0);
  Eigen::MatrixXi uidx = Eigen::MatrixXi::Constant(n, m, -1), yidx = Eigen::MatrixXi::Constant(n, m, -1);
  int ny = 0;
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < n; ++i)
      if (st(i, j) == 0) {
        uidx(i, j) = uoff[j] + static_cast<int>(rows[j].size());
        rows[j].push_back(i);
        if (pivot[i] != j) yidx(i, j) = ny++;
      }
    uoff[j + 1] = uoff[j] + static_cast<int>(rows[j].size());
  }
  const int nu = uoff[m];
  std::vector<Eigen::Triplet<double>> hb, zt;
  Eigen::VectorXd z0 = Eigen::VectorXd::Zero(nu), r(nu);
  const Eigen::MatrixXd R = H * xa + G;
  for (int j = 0; j < m; ++j) {
    const Eigen::VectorXi F = Eigen::Map<Eigen::VectorXi>(rows[j].data(), rows[j].size());
    const Eigen::SparseMatrix<double> Hj = principal_submatrix(H, F);
    for (int k = 0; k < Hj.outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(Hj, k); it; ++it)
        hb.emplace_back(uoff[j] + it.row(), uoff[j] + k, it.value());
    for (int k = 0; k < F.size(); ++k) {
      const int i = F(k), u = uoff[j] + k;
      r(u) = R(i, j);
      if (pivot[i] == j) {
        z0(u) = 1.0 - c(i);
        for (int l = 0; l < m; ++l)
          if (yidx(i, l) >= 0) zt.emplace_back(u, yidx(i, l), -1.0);
      } else {
        zt.emplace_back(u, yidx(i, j), 1.0);
      }
    }
  }
  Eigen::SparseMatrix<double> Hb(nu, nu), Z(nu, ny);
  Hb.setFromTriplets(hb.begin(), hb.end());
  Z.setFromTriplets(zt.begin(), zt.end());
  Eigen::VectorXd xu = z0;
  if (ny > 0) {
    const Eigen::SparseMatrix<double> Hr = Z.transpose() * Hb * Z;
    const Eigen::VectorXd rhs = -(Z.transpose() * (r + Hb * z0));
    SpdSolver chol;
    chol.factorize(Hr);
    xu += Z * chol.solve(rhs);
  }
  out = xa;
  for (int j = 0; j < m; ++j)
    for (size_t k = 0; k < rows[j].size(); ++k) out(rows[j][k], j) = xu(uoff[j] + k);
}

uint64_t hash_status(const Status& st) {
  return fnv1a(kFnv1aBasis, st.data(), sizeof(*st.data()) * static_cast<size_t>(st.size()));
}

// Every row keeps at least one free entry (the sum constraint needs somewhere to live).
void keep_one_free(Status& st, const Eigen::MatrixXd& x) {
  for (int i = 0; i < st.rows(); ++i) {
    bool any = false;
    for (int j = 0; j < st.cols(); ++j) any = any || st(i, j) == 0;
    if (!any) {
      int jm;
      x.row(i).maxCoeff(&jm);
      st(i, jm) = 0;
    }
  }
}

}  // namespace

double exact_pou_kkt_residual(const Eigen::SparseMatrix<double>& H, const Eigen::MatrixXd& G, const Eigen::MatrixXd& X) {
  const Eigen::MatrixXd grad = H * X + G;
  const Eigen::VectorXd hd = H.diagonal();
  double res = 0;
  for (int i = 0; i < X.rows(); ++i) {
    res = std::max(res, std::abs(X.row(i).sum() - 1.0));
    double sum = 0, lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
    int nfree = 0;
    for (int j = 0; j < X.cols(); ++j) {
      const double x = X(i, j);
      res = std::max(res, std::max(-x, x - 1.0));
      if (x > 0 && x < 1) sum += grad(i, j), ++nfree;
      else if (x <= 0) lo = std::max(lo, -grad(i, j));
      else hi = std::min(hi, -grad(i, j));
    }
    double lambda;
    if (nfree) lambda = -sum / nfree;
    else if (std::isinf(lo)) lambda = hi;
    else if (std::isinf(hi)) lambda = lo;
    else lambda = 0.5 * (lo + hi);
    for (int j = 0; j < X.cols(); ++j) {
      const double x = X(i, j), gl = grad(i, j) + lambda;
      const double v = (x > 0 && x < 1) ? std::abs(gl) : (x <= 0 ? std::max(0.0, -gl) : std::max(0.0, gl));
      res = std::max(res, v / hd(i));  // Jacobi-scaled, in weight units (as box_qp_kkt_residual)
    }
  }
  return res;
}

namespace {

// Entries at or beyond a bound start fixed there (-1 at 0, +1 at 1), the rest free; one free per row.
Status status_of(const Eigen::MatrixXd& x) {
  Status st(x.rows(), x.cols());
  for (int k = 0; k < x.size(); ++k) st.data()[k] = x.data()[k] <= 0 ? -1 : (x.data()[k] >= 1 ? 1 : 0);
  keep_one_free(st, x);
  return st;
}

// Multiplier-corrected gradient sign test: releases fixed entries whose multiplier has the wrong sign;
// returns how many.
int release_wrong_signs(const Eigen::SparseMatrix<double>& H, const Eigen::MatrixXd& G, const std::vector<int>& pivot,
                        const Eigen::MatrixXd& xs, double tau, Status& st) {
  const Eigen::MatrixXd grad = H * xs + G;
  const Eigen::VectorXd hd = H.diagonal();
  int released = 0;
  for (int i = 0; i < xs.rows(); ++i) {
    const double lambda = -grad(i, pivot[i]);
    for (int j = 0; j < xs.cols(); ++j) {
      const double gl = grad(i, j) + lambda;
      if ((st(i, j) < 0 && gl < -tau * hd(i)) || (st(i, j) > 0 && gl > tau * hd(i))) st(i, j) = 0, ++released;
    }
  }
  return released;
}

// A feasible point near x: clipped to [0, 1], rows renormalized (an empty row takes X0's positive part).
void clip_and_renormalize(Eigen::MatrixXd& x, const Eigen::MatrixXd& X0) {
  x = x.cwiseMax(0.0).cwiseMin(1.0);
  for (int i = 0; i < x.rows(); ++i) {
    const double s = x.row(i).sum();
    if (s > 1e-12) x.row(i) /= s;
    else x.row(i) = X0.row(i).cwiseMax(0.0) / std::max(X0.row(i).cwiseMax(0.0).sum(), 1e-300);
  }
}

// Moves the free entries of x toward xt as far as the bounds allow; returns the step (1: all the way).
// A blocked step fixes the entries it brought to a bound.
double step_within_bounds(Status& st, Eigen::MatrixXd& x, const Eigen::MatrixXd& xt) {
  double alpha = 1.0;
  for (int k = 0; k < x.size(); ++k) {
    if (st.data()[k] != 0) continue;
    const double xk = x.data()[k], tk = xt.data()[k], d = tk - xk;
    if (tk < 0 && d < 0) alpha = std::min(alpha, -xk / d);
    if (tk > 1 && d > 0) alpha = std::min(alpha, (1 - xk) / d);
  }
  alpha = std::max(alpha, 0.0);
  for (int k = 0; k < x.size(); ++k)
    if (st.data()[k] == 0) x.data()[k] += alpha * (xt.data()[k] - x.data()[k]);
  if (alpha < 1.0) {
    for (int k = 0; k < x.size(); ++k) {
      if (st.data()[k] != 0) continue;
      if (x.data()[k] <= 1e-12) st.data()[k] = -1, x.data()[k] = 0;
      else if (x.data()[k] >= 1 - 1e-12) st.data()[k] = 1, x.data()[k] = 1;
    }
    keep_one_free(st, x);
  }
  return alpha;
}

}  // namespace

ExactPouResult solve_exact_pou(const Eigen::SparseMatrix<double>& H, const Eigen::MatrixXd& G,
                               const Eigen::MatrixXd& X0, double tolerance, const std::atomic<bool>* cancel,
                               int max_iterations) {
  const int n = static_cast<int>(G.rows()), m = static_cast<int>(G.cols());
  if (H.rows() != n || X0.rows() != n || X0.cols() != m) throw Error("exact partition of unity: inconsistent sizes");
  ExactPouResult res;
  auto check_cancel = [&] {
    if (cancel && cancel->load()) throw Cancelled();
  };
  Eigen::MatrixXd x = X0;
  Status st = status_of(x);
  std::vector<int> pivot;
  Eigen::MatrixXd xt;
  const double tau = 0.1 * tolerance;

  // Primal-dual active set steps, until nothing changes or an active set repeats.
  bool done = false;
  std::unordered_set<uint64_t> seen;
  for (int it = 0; it < 60 && !done; ++it) {
    check_cancel();
    solve_face(H, G, st, x, xt, pivot);
    ++res.iterations;
    x = xt;
    int changes = 0;
    for (int k = 0; k < x.size(); ++k) {
      signed char& s = st.data()[k];
      if (s == 0 && x.data()[k] < -1e-13) s = -1, ++changes;
      else if (s == 0 && x.data()[k] > 1 + 1e-13) s = 1, ++changes;
    }
    Status before = st;
    changes += release_wrong_signs(H, G, pivot, x, tau, st);
    keep_one_free(st, x);
    if ((changes == 0 && st == before) || exact_pou_kkt_residual(H, G, x.cwiseMax(0.0).cwiseMin(1.0)) <= tolerance)
      done = true;
    else if (!seen.insert(hash_status(st)).second) break;
  }

  if (!done) {
    // Monotone fallback from a feasible point: feasible descent steps on the faces.
    clip_and_renormalize(x, X0);
    st = status_of(x);
    while (res.iterations < max_iterations) {
      check_cancel();
      solve_face(H, G, st, x, xt, pivot);
      ++res.iterations, ++res.fallback_iterations;
      if (step_within_bounds(st, x, xt) < 1.0) continue;
      if (release_wrong_signs(H, G, pivot, x, tau, st) == 0) {
        done = true;
        break;
      }
    }
  }
  x = x.cwiseMax(0.0).cwiseMin(1.0);
  res.X = x;
  res.kkt_residual = exact_pou_kkt_residual(H, G, x);
  res.converged = done && res.kkt_residual <= tolerance;
  return res;
}

}  // namespace dfm
