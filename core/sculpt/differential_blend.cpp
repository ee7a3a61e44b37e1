#include "core/sculpt/differential_blend.h"

#include <algorithm>
#include <chrono>
#include <deque>
#include <string>

#include "core/bind/surface_laplacian.h"
#include "core/util/error.h"

namespace dfm {
namespace {

using Sparse = Eigen::SparseMatrix<double>;

// Connected parts of the vertex graph of L (an unreferenced vertex is a part of its own).
int connected_parts(const Sparse& L, std::vector<int>& part) {
  const int n = static_cast<int>(L.rows());
  part.assign(n, -1);
  int parts = 0;
  for (int s = 0; s < n; ++s) {
    if (part[s] >= 0) continue;
    std::deque<int> queue{s};
    part[s] = parts;
    while (!queue.empty()) {
      const int i = queue.front();
      queue.pop_front();
      for (Sparse::InnerIterator it(L, i); it; ++it)  // L's pattern is symmetric: column i lists i's neighbours
        if (part[it.row()] < 0) part[it.row()] = parts, queue.push_back(static_cast<int>(it.row()));
    }
    ++parts;
  }
  return parts;
}

}  // namespace

DifferentialBlend::DifferentialBlend(const Eigen::MatrixXd& K0, const Eigen::MatrixXd& K1, const Eigen::MatrixXi& F)
    : K0_(K0), K1_(K1) {
  const auto t0 = std::chrono::steady_clock::now();
  if (K0.rows() != K1.rows() || K0.cols() != 3 || K1.cols() != 3)
    throw Error("differential blend: the keys have different vertex counts (" + std::to_string(K0.rows()) + " and " +
                std::to_string(K1.rows()) + ")");
  const int n = static_cast<int>(K0.rows());
  // L = I - D A (Eq. 4.16-4.17): uniform_stiffness is deg - A, so L = deg^-1 (deg - A).
  const Sparse U = uniform_stiffness(n, F);  // throws for an index out of range
  Eigen::VectorXd inv_deg = U.diagonal();
  for (int i = 0; i < n; ++i) inv_deg(i) = inv_deg(i) > 0 ? 1.0 / inv_deg(i) : 0.0;
  L_ = inv_deg.asDiagonal() * U;
  W0_ = L_ * K0_;
  W1_ = L_ * K1_;
  parts_ = connected_parts(U, part_);
  std::vector<char> anchored(parts_, 0);
  std::vector<int> col(n, -1);
  for (int i = 0; i < n; ++i) {
    if (!anchored[part_[i]]) {
      anchored[part_[i]] = 1;  // the part's first vertex: E = 0 there
      continue;
    }
    col[i] = static_cast<int>(free_.size());
    free_.push_back(i);
  }
  const Sparse N = (L_.transpose() * L_).pruned();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(N.nonZeros());
  for (int k = 0; k < N.outerSize(); ++k)
    for (Sparse::InnerIterator it(N, k); it; ++it)
      if (col[it.row()] >= 0 && col[it.col()] >= 0) t.emplace_back(col[it.row()], col[it.col()], it.value());
  Sparse Nff(static_cast<Eigen::Index>(free_.size()), static_cast<Eigen::Index>(free_.size()));
  Nff.setFromTriplets(t.begin(), t.end());
  if (!free_.empty()) solver_.factorize(Nff);
  factor_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Eigen::MatrixXd DifferentialBlend::at(const Eigen::VectorXd& s) const {
  const Eigen::Index n = K0_.rows();
  if (s.size() != n)
    throw Error("differential blend: " + std::to_string(s.size()) + " transition states for " + std::to_string(n) +
                " vertices");
  const Eigen::ArrayXd a = 1.0 - s.array();
  // P and W~ blend the rows the same way, so at states 0 or 1 r is exactly zero (W0 = L K0 as computed).
  const Eigen::MatrixXd P = (K0_.array().colwise() * a + K1_.array().colwise() * s.array()).matrix();
  const Eigen::MatrixXd Wt = (W0_.array().colwise() * a + W1_.array().colwise() * s.array()).matrix();
  Eigen::MatrixXd LP = L_ * P;  // evaluated as W0_ and W1_ were (a fused "Wt - L P" sums in another order)
  const Eigen::MatrixXd r = Wt - LP;
  if (free_.empty() || r.isZero(0.0)) return P;
  const Eigen::MatrixXd g = L_.transpose() * r;
  Eigen::MatrixXd gf(free_.size(), 3);
  for (size_t k = 0; k < free_.size(); ++k) gf.row(static_cast<Eigen::Index>(k)) = g.row(free_[k]);
  const Eigen::MatrixXd ef = solver_.solve(gf);
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(n, 3);
  for (size_t k = 0; k < free_.size(); ++k) E.row(free_[k]) = ef.row(static_cast<Eigen::Index>(k));
  // Any per-part constant leaves |L E - r| unchanged; zero mean per part keeps P's centroids.
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(parts_, 3);
  Eigen::VectorXd count = Eigen::VectorXd::Zero(parts_);
  for (Eigen::Index i = 0; i < n; ++i) sum.row(part_[i]) += E.row(i), count(part_[i]) += 1;
  for (Eigen::Index i = 0; i < n; ++i) E.row(i) -= sum.row(part_[i]) / count(part_[i]);
  return P + E;
}

Eigen::VectorXd transition_states(const Eigen::VectorXd& offsets, double t) {
  Eigen::VectorXd s(offsets.size());
  for (Eigen::Index i = 0; i < offsets.size(); ++i) {
    const double o = offsets(i);
    if (!(o > -1 && o < 1))
      throw Error("transition state offset " + std::to_string(o) + " at vertex " + std::to_string(i) +
                  " is outside (-1, 1)");
    if (t <= 0 || t >= 1) s(i) = t;
    else if (o >= 0) s(i) = std::min(1.0, t / (1 - o));
    else s(i) = std::max(0.0, (t + o) / (1 + o));
  }
  return s;
}

}  // namespace dfm
