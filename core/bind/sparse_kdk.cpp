#include "core/bind/sparse_kdk.h"

#include <algorithm>
#include <string>
#include <vector>

#include "core/util/error.h"

namespace dfm {

Eigen::SparseMatrix<double> symmetric_kdk(const Eigen::SparseMatrix<double>& K0, const Eigen::VectorXd& d) {
  if (K0.rows() != K0.cols()) throw Error("symmetric_kdk: K is not square");
  if (d.size() != K0.rows())
    throw Error("symmetric_kdk: " + std::to_string(d.size()) + " scale values for " + std::to_string(K0.rows()) + " rows");
  Eigen::SparseMatrix<double> K = K0;
  K.makeCompressed();
  const int n = static_cast<int>(K.rows());
  const int* kp = K.outerIndexPtr();
  const int* ki = K.innerIndexPtr();
  const double* kx = K.valuePtr();
  std::vector<int> col;
  std::vector<double> acc(n, 0.0);
  std::vector<char> seen(n, 0);
  // Pass 1 counts each column (the 2-ring of its vertex) so the result is written in place: no growth
  // copies, whose page faults cost more than the arithmetic here.
  Eigen::SparseMatrix<double> Q(n, n);
  int* outer = Q.outerIndexPtr();
  outer[0] = 0;
  for (int j = 0; j < n; ++j) {
    col.clear();
    for (int p = kp[j]; p < kp[j + 1]; ++p)
      for (int q = kp[ki[p]]; q < kp[ki[p] + 1]; ++q)
        if (!seen[ki[q]]) seen[ki[q]] = 1, col.push_back(ki[q]);
    for (int i : col) seen[i] = 0;
    outer[j + 1] = outer[j] + static_cast<int>(col.size());
  }
  Q.resizeNonZeros(outer[n]);
  int* rows = Q.innerIndexPtr();
  double* vals = Q.valuePtr();
  for (int j = 0; j < n; ++j) {
    col.clear();
    // Column j of K D K = sum over k of K(:, k) d_k K(k, j); K(k, j) = K(j, k) walks column j.
    for (int p = kp[j]; p < kp[j + 1]; ++p) {
      const int k = ki[p];
      const double s = d(k) * kx[p];
      for (int q = kp[k]; q < kp[k + 1]; ++q) {
        const int i = ki[q];
        if (!seen[i]) seen[i] = 1, col.push_back(i);
        acc[i] += kx[q] * s;
      }
    }
    std::sort(col.begin(), col.end());
    int pos = outer[j];
    for (int i : col) rows[pos] = i, vals[pos] = acc[i], ++pos, acc[i] = 0.0, seen[i] = 0;
  }
  return Q;
}

}  // namespace dfm
