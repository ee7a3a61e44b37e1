#pragma once
// Inside core/bind only: CHOLMOD views of Eigen matrices, shared by the Cholesky wrapper (cholesky.cpp)
// and the box QP's face solver (qp.cpp).
#include <cholmod.h>

namespace dfm {

inline constexpr const char* kCholeskyNotPositiveDefinite = "sparse Cholesky: matrix is not positive definite";

// A CHOLMOD view (no copy) of a symmetric matrix given by its lower triangle in compressed columns.
inline cholmod_sparse cholmod_lower_view(int n, int* p, int* i, double* x) {
  cholmod_sparse cs{};
  cs.nrow = cs.ncol = static_cast<size_t>(n);
  cs.nzmax = static_cast<size_t>(p[n]);
  cs.p = p;
  cs.i = i;
  cs.x = x;
  cs.stype = -1;  // symmetric, lower triangle used
  cs.itype = CHOLMOD_INT;
  cs.xtype = CHOLMOD_REAL;
  cs.dtype = CHOLMOD_DOUBLE;
  cs.sorted = 1;
  cs.packed = 1;
  return cs;
}

}  // namespace dfm
