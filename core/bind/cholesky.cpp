#include "core/bind/cholesky.h"

#include <cholmod.h>

#include <string>
#include <vector>

#include "core/bind/cholmod_view.h"
#include "core/util/error.h"

namespace dfm {

// ---------------------------------------------------------------------------------------------- SpdSolver

struct SpdSolver::Impl {
  mutable cholmod_common c;
  cholmod_factor* L = nullptr;
  bool numeric = false;  // L holds a numeric factorization (not only the symbolic analysis)
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

void SpdSolver::analyze(const Eigen::SparseMatrix<double>& A0, bool in_elimination_order) {
  Eigen::SparseMatrix<double> A = A0;  // compressed copy CHOLMOD can view
  A.makeCompressed();
  cholmod_sparse cs =
      cholmod_lower_view(static_cast<int>(A.rows()), A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr());
  cholmod_common& c = impl_->c;
  if (impl_->L) cholmod_free_factor(&impl_->L, &c);
  impl_->numeric = false;
  if (in_elimination_order) {
    c.nmethods = 1;
    c.method[0].ordering = CHOLMOD_NATURAL;
  } else if (A.rows() < 20000) {  // small systems: AMD alone (METIS costs more than it saves)
    c.nmethods = 1;
    c.method[0].ordering = CHOLMOD_AMD;
  } else {
    // Large volume meshes: nested dissection (METIS) alone. CHOLMOD's default also runs AMD first and
    // keeps the better, which costs both orderings to pick METIS on these meshes anyway.
    c.nmethods = 1;
    c.method[0].ordering = CHOLMOD_METIS;
  }
  c.supernodal = CHOLMOD_AUTO;
  impl_->L = cholmod_analyze(&cs, &c);
  if (!impl_->L) throw Error("sparse Cholesky: analysis failed (out of memory?)");
}

void SpdSolver::factorize(const Eigen::SparseMatrix<double>& A0) {
  // Reuses a symbolic analysis of a matrix of the same size and pattern (analyze), else makes one.
  if (!impl_->L || impl_->numeric || static_cast<long>(impl_->L->n) != A0.rows()) analyze(A0);
  Eigen::SparseMatrix<double> A = A0;
  A.makeCompressed();
  cholmod_sparse cs =
      cholmod_lower_view(static_cast<int>(A.rows()), A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr());
  cholmod_common& c = impl_->c;
  cholmod_factorize(&cs, impl_->L, &c);
  impl_->numeric = true;
  if (c.status == CHOLMOD_NOT_POSDEF || impl_->L->minor < impl_->L->n)
    throw Error(kCholeskyNotPositiveDefinite);
  if (c.status < 0) throw Error("sparse Cholesky: factorization failed (out of memory?)");
}

Eigen::MatrixXd SpdSolver::solve(const Eigen::MatrixXd& B0) const {
  if (!impl_->L || !impl_->numeric) throw Error("SpdSolver::solve before factorize");
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

std::vector<int> SpdSolver::permutation() const {
  if (!impl_->L) throw Error("SpdSolver::permutation before analyze or factorize");
  const int* p = static_cast<const int*>(impl_->L->Perm);
  return std::vector<int>(p, p + impl_->L->n);
}

long SpdSolver::factor_nonzeros() const {
  if (!impl_->L) return 0;
  return static_cast<long>(impl_->c.lnz);
}

std::vector<int> fill_reducing_ordering(const Eigen::SparseMatrix<double>& H0) {
  Eigen::SparseMatrix<double> H = H0;
  H.makeCompressed();
  cholmod_common c;
  cholmod_start(&c);
  c.print = 0;
  c.error_handler = nullptr;
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_AMD;
  cholmod_sparse cs =
      cholmod_lower_view(static_cast<int>(H.rows()), H.outerIndexPtr(), H.innerIndexPtr(), H.valuePtr());
  cholmod_factor* L = cholmod_analyze(&cs, &c);
  if (!L) {
    cholmod_finish(&c);
    throw Error("sparse Cholesky: ordering failed (out of memory?)");
  }
  const int* p = static_cast<const int*>(L->Perm);
  std::vector<int> perm(p, p + L->n);
  cholmod_free_factor(&L, &c);
  cholmod_finish(&c);
  return perm;
}

}  // namespace dfm
