#include "core/bind/bbw_system.h"

#include <exception>
#include <thread>
#include <vector>

#include "core/bind/cholesky.h"
#include "core/bind/cholmod_memory.h"
#include "core/bind/qp.h"

namespace dfm {

FreeSystem split_free_fixed(Eigen::SparseMatrix<double> Q, const Eigen::VectorXi& b, const Eigen::MatrixXd& bc) {
  const int n = static_cast<int>(Q.rows()), m = static_cast<int>(bc.cols());
  std::vector<int> fmap(n, 0);
  for (int k = 0; k < b.size(); ++k) fmap[b(k)] = -1;
  std::vector<int> free_list;
  for (int i = 0; i < n; ++i)
    if (fmap[i] == 0) fmap[i] = static_cast<int>(free_list.size()), free_list.push_back(i);
  FreeSystem sys;
  sys.vertex = Eigen::Map<Eigen::VectorXi>(free_list.data(), free_list.size());
  sys.Qff = principal_submatrix(Q, sys.vertex);
  sys.G = Eigen::MatrixXd::Zero(sys.vertex.size(), m);
  for (int k = 0; k < b.size(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(Q, b(k)); it; ++it)
      if (fmap[it.row()] >= 0) sys.G.row(fmap[it.row()]) += it.value() * bc.row(k);
  return sys;  // Q is freed here: only Q_ff from now on, less at the bind's peak
}

namespace {

Eigen::MatrixXd rows_permuted(const Eigen::MatrixXd& A, const std::vector<int>& perm) {
  Eigen::MatrixXd out(A.rows(), A.cols());
  for (int k = 0; k < A.rows(); ++k) out.row(k) = A.row(perm[k]);
  return out;
}

}  // namespace

Eigen::MatrixXd order_free_system(FreeSystem& sys, bool bound_free_start, int threads,
                                  const std::function<void()>& ordered) {
  const int nf = static_cast<int>(sys.Qff.rows());
  Eigen::MatrixXd X0;
  std::vector<int> perm;
  Eigen::SparseMatrix<double> Q_renumbered;
  {
    SpdSolver chol;
    chol.analyze(sys.Qff);
    sys.factor_nonzeros = chol.factor_nonzeros();
    perm = chol.permutation();
    if (ordered) ordered();
    const Eigen::VectorXi p = Eigen::Map<const Eigen::VectorXi>(perm.data(), nf);
    if (bound_free_start && threads > 1) {
      // The renumbered copy is made on the idle core while this one factorizes.
      std::exception_ptr failed;
      std::thread renumber([&] {
        try {
          Q_renumbered = principal_submatrix(sys.Qff, p);
        } catch (...) {
          failed = std::current_exception();
        }
      });
      try {
        chol.factorize(sys.Qff);
        X0 = chol.solve(-sys.G);
      } catch (...) {
        renumber.join();
        throw;
      }
      renumber.join();
      if (failed) std::rethrow_exception(failed);
    } else {
      if (bound_free_start) {
        chol.factorize(sys.Qff);
        X0 = chol.solve(-sys.G);
      }
      Q_renumbered = principal_submatrix(sys.Qff, p);
    }
  }
  release_cholmod_block_cache();  // the whole-matrix factor's blocks: faces are smaller
  sys.Qff = std::move(Q_renumbered);
  sys.G = rows_permuted(sys.G, perm);
  if (X0.size()) X0 = rows_permuted(X0, perm);
  Eigen::VectorXi vertex(nf);
  for (int k = 0; k < nf; ++k) vertex(k) = sys.vertex(perm[k]);
  sys.vertex.swap(vertex);
  return X0;
}

}  // namespace dfm
