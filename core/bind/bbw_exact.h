#pragma once
// Exact partition of unity: all handles' weights solved jointly,
//   min sum_j 1/2 x_j^T H x_j + g_j^T x_j   s.t.  sum_j x_ij = 1 for every row i,  0 <= x <= 1.
// Primal-dual active set on the entries (i, j); each iteration eliminates one free entry per row (its
// "pivot") through the row's sum constraint and solves the reduced SPD system exactly (CHOLMOD). Falls
// back to a monotone primal active-set method on cycling, like solve_box_qp.
#include <atomic>

#include <Eigen/Core>
#include <Eigen/Sparse>

namespace dfm {

struct ExactPouResult {
  Eigen::MatrixXd X;  // #rows x #handles
  int iterations = 0;
  int fallback_iterations = 0;
  double kkt_residual = 0;  // weight units: Jacobi-scaled stationarity with the rows' multipliers, signs, row sums
  bool converged = false;
};

// H: #rows x #rows SPD (shared by all handles), G: #rows x #handles linear terms, X0: starting guess.
ExactPouResult solve_exact_pou(const Eigen::SparseMatrix<double>& H, const Eigen::MatrixXd& G,
                               const Eigen::MatrixXd& X0, double tolerance,
                               const std::atomic<bool>* cancel = nullptr, int max_iterations = 500);

// The KKT residual used above, for any X (row multipliers estimated from the free entries).
double exact_pou_kkt_residual(const Eigen::SparseMatrix<double>& H, const Eigen::MatrixXd& G, const Eigen::MatrixXd& X);

}  // namespace dfm
