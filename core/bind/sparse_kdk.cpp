#include "core/bind/sparse_kdk.h"

#include <algorithm>
#include <exception>
#include <thread>
#include <string>
#include <vector>

#include "core/util/error.h"

namespace dfm {

Eigen::SparseMatrix<double> symmetric_kdk(const Eigen::SparseMatrix<double>& K0, const Eigen::VectorXd& d,
                                          int threads) {
  if (K0.rows() != K0.cols()) throw Error("symmetric_kdk: K is not square");
  if (d.size() != K0.rows())
    throw Error("symmetric_kdk: " + std::to_string(d.size()) + " scale values for " + std::to_string(K0.rows()) + " rows");
  Eigen::SparseMatrix<double> K = K0;
  K.makeCompressed();
  const int n = static_cast<int>(K.rows());
  const int* kp = K.outerIndexPtr();
  const int* ki = K.innerIndexPtr();
  const double* kx = K.valuePtr();
  // Columns are independent: with threads > 1, each thread takes a contiguous range of columns with its
  // own accumulator (hand.mesh's assembly runs while the other core has nothing to do yet).
  const int nt = std::max(1, std::min(threads, n / 1024));
  auto ranges = [&](auto&& body) {
    if (nt == 1) return body(0, n);
    std::vector<std::thread> pool;
    std::vector<std::exception_ptr> failed(nt);
    for (int t = 0; t < nt; ++t)
      pool.emplace_back([&, t] {
        try {
          body(static_cast<int>(static_cast<long>(n) * t / nt), static_cast<int>(static_cast<long>(n) * (t + 1) / nt));
        } catch (...) {
          failed[t] = std::current_exception();
        }
      });
    for (auto& th : pool) th.join();
    for (auto& e : failed)
      if (e) std::rethrow_exception(e);
  };
  // Pass 1 counts each column (the 2-ring of its vertex) so the result is written in place: no growth
  // copies, whose page faults cost more than the arithmetic here.
  Eigen::SparseMatrix<double> Q(n, n);
  int* outer = Q.outerIndexPtr();
  outer[0] = 0;
  ranges([&](int begin, int end) {
    std::vector<int> col;
    std::vector<char> seen(n, 0);
    for (int j = begin; j < end; ++j) {
      col.clear();
      for (int p = kp[j]; p < kp[j + 1]; ++p)
        for (int q = kp[ki[p]]; q < kp[ki[p] + 1]; ++q)
          if (!seen[ki[q]]) seen[ki[q]] = 1, col.push_back(ki[q]);
      for (int i : col) seen[i] = 0;
      outer[j + 1] = static_cast<int>(col.size());
    }
  });
  for (int j = 0; j < n; ++j) outer[j + 1] += outer[j];
  Q.resizeNonZeros(outer[n]);
  int* rows = Q.innerIndexPtr();
  double* vals = Q.valuePtr();
  ranges([&](int begin, int end) {
    std::vector<int> col;
    std::vector<double> acc(n, 0.0);
    std::vector<char> seen(n, 0);
    for (int j = begin; j < end; ++j) {
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
  });
  return Q;
}

}  // namespace dfm
