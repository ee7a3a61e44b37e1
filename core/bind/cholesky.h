#pragma once
// Sparse Cholesky (CHOLMOD) for the bind's solves: one symbolic analysis, many numeric factorizations
// and right-hand sides, and the AMD ordering shared by every face of a box QP.
#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>

namespace dfm {

// Sparse SPD factorization (CHOLMOD, supernodal when it pays) reused for many right-hand sides.
class SpdSolver {
 public:
  SpdSolver();
  ~SpdSolver();
  SpdSolver(const SpdSolver&) = delete;
  SpdSolver& operator=(const SpdSolver&) = delete;
  // Fill-reducing ordering and symbolic factorization only (permutation() and factor_nonzeros() are
  // then available); a later factorize of a matrix with this pattern reuses it.
  // in_elimination_order: A's own order is already a fill-reducing one (no ordering is computed).
  void analyze(const Eigen::SparseMatrix<double>& A, bool in_elimination_order = false);
  // Throws dfm::Error if A is not numerically positive definite.
  void factorize(const Eigen::SparseMatrix<double>& A);
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;
  long factor_nonzeros() const;
  // The fill-reducing permutation the factorization used (perm[k] = variable eliminated k-th).
  std::vector<int> permutation() const;

 private:
  struct Impl;
  Impl* impl_;
};

// AMD ordering of the symmetric matrix H (perm[k] = the variable eliminated k-th). A face of a box QP is a
// principal submatrix; the ordering restricted to it stays a good one (the filled graph of a subgraph is a
// subgraph of the filled graph), so one ordering serves every face: a few more flops per face than its own
// AMD, but no per-face AMD, which costs more than it saves.
std::vector<int> fill_reducing_ordering(const Eigen::SparseMatrix<double>& H);

}  // namespace dfm
