#pragma once
// K diag(d) K for a symmetric sparse K: the bilaplacian K M^-1 K of the weight energy. Gustavson's
// column-by-column product with a dense accumulator, written for this one shape: Eigen's general
// product makes a row-major temporary, 64-bit indices and a transposed copy (see bench_bind's assembly).
#include <Eigen/Core>
#include <Eigen/Sparse>

namespace dfm {

// K: square, symmetric (both triangles stored), compressed. d: one value per row. Returns K diag(d) K,
// compressed with sorted row indices. threads: columns are split over that many threads (same result).
Eigen::SparseMatrix<double> symmetric_kdk(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& d,
                                          int threads = 1);

}  // namespace dfm
