#include "core/bind/qp.h"

#include <cholmod.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_set>
#include <vector>

#include "core/util/error.h"

namespace dfm {

// ---------------------------------------------------------------------------------------------- SpdSolver

struct SpdSolver::Impl {
  mutable cholmod_common c;
  cholmod_factor* L = nullptr;
  Impl() {
    cholmod_start(&c);
    c.print = 0;
    c.error_handler = nullptr;
  }
  ~Impl() {
    if (L) cholmod_free_factor(&L, &c);
    cholmod_finish(&c);
  }
};

SpdSolver::SpdSolver() : impl_(new Impl) {}
SpdSolver::~SpdSolver() { delete impl_; }

void SpdSolver::factorize(const Eigen::SparseMatrix<double>& A0) {
  Eigen::SparseMatrix<double> A = A0;  // compressed copy CHOLMOD can view
  A.makeCompressed();
  cholmod_sparse cs{};
  cs.nrow = cs.ncol = static_cast<size_t>(A.rows());
  cs.nzmax = static_cast<size_t>(A.nonZeros());
  cs.p = A.outerIndexPtr();
  cs.i = A.innerIndexPtr();
  cs.x = A.valuePtr();
  cs.stype = -1;  // symmetric, lower triangle used
  cs.itype = CHOLMOD_INT;
  cs.xtype = CHOLMOD_REAL;
  cs.dtype = CHOLMOD_DOUBLE;
  cs.sorted = 1;
  cs.packed = 1;
  cholmod_common& c = impl_->c;
  if (impl_->L) cholmod_free_factor(&impl_->L, &c);
  // Small systems: AMD alone (METIS costs more than it saves). Large: let CHOLMOD pick AMD or METIS.
  if (A.rows() < 20000) {
    c.nmethods = 1;
    c.method[0].ordering = CHOLMOD_AMD;
  } else {
    c.nmethods = 0;
  }
  c.supernodal = CHOLMOD_AUTO;
  impl_->L = cholmod_analyze(&cs, &c);
  if (!impl_->L) throw Error("sparse Cholesky: analysis failed (out of memory?)");
  cholmod_factorize(&cs, impl_->L, &c);
  if (c.status == CHOLMOD_NOT_POSDEF || impl_->L->minor < impl_->L->n)
    throw Error("sparse Cholesky: matrix is not positive definite (is every connected part of the volume "
                "constrained by a handle?)");
  if (c.status < 0) throw Error("sparse Cholesky: factorization failed (out of memory?)");
}

Eigen::MatrixXd SpdSolver::solve(const Eigen::MatrixXd& B0) const {
  if (!impl_->L) throw Error("SpdSolver::solve before factorize");
  Eigen::MatrixXd B = B0;
  cholmod_dense bd{};
  bd.nrow = static_cast<size_t>(B.rows());
  bd.ncol = static_cast<size_t>(B.cols());
  bd.nzmax = bd.nrow * bd.ncol;
  bd.d = bd.nrow;
  bd.x = B.data();
  bd.xtype = CHOLMOD_REAL;
  bd.dtype = CHOLMOD_DOUBLE;
  cholmod_dense* X = cholmod_solve(CHOLMOD_A, impl_->L, &bd, &impl_->c);
  if (!X) throw Error("sparse Cholesky: solve failed (out of memory?)");
  Eigen::MatrixXd out = Eigen::Map<Eigen::MatrixXd>(static_cast<double*>(X->x), B.rows(), B.cols());
  cholmod_free_dense(&X, &impl_->c);
  return out;
}

long SpdSolver::factor_nonzeros() const {
  if (!impl_->L) return 0;
  return static_cast<long>(impl_->c.lnz);
}

// ---------------------------------------------------------------------------------------------- helpers

Eigen::SparseMatrix<double> principal_submatrix(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXi& idx) {
  std::vector<int> map(A.rows(), -1);
  for (int k = 0; k < idx.size(); ++k) map[idx(k)] = k;
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<size_t>(idx.size()) * 64);
  for (int k = 0; k < idx.size(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, idx(k)); it; ++it)
      if (map[it.row()] >= 0) trip.emplace_back(map[it.row()], k, it.value());
  Eigen::SparseMatrix<double> S(idx.size(), idx.size());
  S.setFromTriplets(trip.begin(), trip.end());
  return S;
}

namespace {

uint64_t hash_status(const std::vector<signed char>& st) {
  uint64_t h = 1469598103934665603ull;
  for (signed char s : st) h = (h ^ static_cast<uint64_t>(s + 1)) * 1099511628211ull;
  return h;
}

}  // namespace

double box_qp_kkt_residual(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& g, const Eigen::VectorXd& lo,
                           const Eigen::VectorXd& hi, const Eigen::VectorXd& x) {
  const Eigen::VectorXd grad = H * x + g;
  const Eigen::VectorXd d = H.diagonal();
  double r = 0;
  for (int i = 0; i < x.size(); ++i) {
    if (!(d(i) > 0)) throw Error("box QP: the matrix has a non-positive diagonal entry");
    // Natural residual in the Jacobi metric: how far one diagonal Newton step, projected on the box,
    // would move x_i. Zero iff stationary (free), or the gradient points out of the box (at a bound).
    const double step = std::min(std::max(x(i) - grad(i) / d(i), lo(i)), hi(i));
    double v = std::abs(step - x(i));
    if (x(i) < lo(i)) v = std::max(v, lo(i) - x(i));
    if (x(i) > hi(i)) v = std::max(v, x(i) - hi(i));
    r = std::max(r, v);
  }
  return r;
}

BoxQPResult solve_box_qp(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& g, const Eigen::VectorXd& lo,
                         const Eigen::VectorXd& hi, const Eigen::VectorXd& x0, const BoxQPOptions& opts) {
  const int n = static_cast<int>(g.size());
  if (H.rows() != n || H.cols() != n || lo.size() != n || hi.size() != n || (x0.size() != 0 && x0.size() != n))
    throw Error("box QP: inconsistent sizes");
  if ((lo.array() > hi.array()).any()) throw Error("box QP: a lower bound exceeds its upper bound");
  BoxQPResult res;
  // status: -1 at lower bound, +1 at upper bound, 0 free.
  std::vector<signed char> st(n, 0);
  Eigen::VectorXd x = x0.size() ? x0 : lo;
  for (int i = 0; i < n; ++i) st[i] = x(i) <= lo(i) ? -1 : (x(i) >= hi(i) ? 1 : 0);

  auto check_cancel = [&] {
    if (opts.cancel && opts.cancel->load()) throw Error("cancelled");
  };
  // Minimizer over the free variables with the others at their bounds.
  SpdSolver chol;
  auto solve_face = [&](Eigen::VectorXd& out) {
    std::vector<int> free_idx;
    Eigen::VectorXd xa = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i) {
      if (st[i] == 0)
        free_idx.push_back(i);
      else
        xa(i) = st[i] < 0 ? lo(i) : hi(i);
    }
    out = xa;
    ++res.iterations;
    if (free_idx.empty()) return;
    const Eigen::VectorXi F = Eigen::Map<Eigen::VectorXi>(free_idx.data(), free_idx.size());
    const Eigen::VectorXd r = H * xa + g;
    Eigen::VectorXd rhs(F.size());
    for (int k = 0; k < F.size(); ++k) rhs(k) = -r(F(k));
    chol.factorize(principal_submatrix(H, F));
    const Eigen::VectorXd xf = chol.solve(rhs);
    for (int k = 0; k < F.size(); ++k) out(F(k)) = xf(k);
  };

  const Eigen::VectorXd hd = H.diagonal();
  // ---- primal-dual active set
  std::unordered_set<uint64_t> seen;
  bool done = false;
  for (int it = 0; it < opts.max_pdas_iterations && !done; ++it) {
    check_cancel();
    solve_face(x);
    const Eigen::VectorXd grad = H * x + g;
    const double tau = 0.1 * opts.tolerance;  // in the Jacobi-scaled units of the KKT residual
    int changes = 0;
    for (int i = 0; i < n; ++i) {
      signed char s = st[i];
      const double eps = 1e-13 * (hi(i) - lo(i));
      if (s == 0) {
        if (x(i) < lo(i) - eps) s = -1;
        else if (x(i) > hi(i) + eps) s = 1;
      } else if (s < 0 && grad(i) < -tau * hd(i)) {
        s = 0;
      } else if (s > 0 && grad(i) > tau * hd(i)) {
        s = 0;
      }
      if (s != st[i]) ++changes, st[i] = s;
    }
    // The tail of PDAS moves a few variables with tiny multipliers: stop as soon as the clipped iterate
    // is a KKT point to the tolerance (checked exactly, not estimated).
    if (changes == 0 || box_qp_kkt_residual(H, g, lo, hi, x.cwiseMax(lo).cwiseMin(hi)) <= opts.tolerance) done = true;
    else if (!seen.insert(hash_status(st)).second) break;  // cycling: go monotone
  }

  // ---- monotone fallback: primal active set with a ratio test (objective strictly decreases).
  if (!done) {
    x = x.cwiseMax(lo).cwiseMin(hi);
    for (int i = 0; i < n; ++i) st[i] = x(i) <= lo(i) ? -1 : (x(i) >= hi(i) ? 1 : 0);
    Eigen::VectorXd xt;
    while (res.iterations < opts.max_iterations) {
      check_cancel();
      ++res.fallback_iterations;
      solve_face(xt);
      double alpha = 1.0;
      for (int i = 0; i < n; ++i) {
        if (st[i] != 0) continue;
        const double d = xt(i) - x(i);
        if (xt(i) < lo(i) && d < 0) alpha = std::min(alpha, (lo(i) - x(i)) / d);
        if (xt(i) > hi(i) && d > 0) alpha = std::min(alpha, (hi(i) - x(i)) / d);
      }
      alpha = std::max(alpha, 0.0);
      for (int i = 0; i < n; ++i)
        if (st[i] == 0) x(i) += alpha * (xt(i) - x(i));
      if (alpha < 1.0) {
        for (int i = 0; i < n; ++i) {
          if (st[i] != 0) continue;
          const double eps = 1e-12 * (hi(i) - lo(i));
          if (x(i) <= lo(i) + eps) st[i] = -1, x(i) = lo(i);
          else if (x(i) >= hi(i) - eps) st[i] = 1, x(i) = hi(i);
        }
        continue;
      }
      const Eigen::VectorXd grad = H * x + g;
      const double tau = 0.1 * opts.tolerance;  // in the Jacobi-scaled units of the KKT residual
      int released = 0;
      for (int i = 0; i < n; ++i)
        if ((st[i] < 0 && grad(i) < -tau * hd(i)) || (st[i] > 0 && grad(i) > tau * hd(i))) st[i] = 0, ++released;
      if (released == 0) {
        done = true;
        break;
      }
    }
  }

  x = x.cwiseMax(lo).cwiseMin(hi);
  res.x = x;
  res.kkt_residual = box_qp_kkt_residual(H, g, lo, hi, x);
  res.converged = done && res.kkt_residual <= opts.tolerance;
  res.num_free = 0;
  for (int i = 0; i < n; ++i) res.num_free += (x(i) > lo(i) && x(i) < hi(i));
  return res;
}

}  // namespace dfm
