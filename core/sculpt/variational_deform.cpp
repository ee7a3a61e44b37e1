#include "core/sculpt/variational_deform.h"

#include <algorithm>
#include <chrono>
#include <deque>
#include <string>

#include "core/bind/surface_laplacian.h"
#include "core/util/error.h"

namespace dfm {
namespace {

using Sparse = Eigen::SparseMatrix<double>;

std::vector<int> sorted_unique(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

void check_range(const std::vector<int>& idx, int nv, const char* what) {
  for (int i : idx)
    if (i < 0 || i >= nv)
      throw Error(std::string("variational deform: ") + what + " vertex " + std::to_string(i) + " out of range (" +
                  std::to_string(nv) + " vertices)");
}

// Rows `rows` of the identity (#rows x n): S * A picks A's rows, A * S^T its columns.
Sparse selector(const std::vector<int>& rows, int n) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(rows.size());
  for (size_t k = 0; k < rows.size(); ++k) t.emplace_back(static_cast<int>(k), rows[k], 1.0);
  Sparse S(static_cast<Eigen::Index>(rows.size()), n);
  S.setFromTriplets(t.begin(), t.end());
  return S;
}

// Free vertices with no mesh path to a known one: Q is singular there (nothing sets their displacement).
int count_unreachable(int nv, const Eigen::MatrixXi& F, const std::vector<char>& known) {
  std::vector<std::vector<int>> adj(nv);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      adj[a].push_back(b), adj[b].push_back(a);
    }
  std::vector<char> seen(known);
  std::deque<int> queue;
  for (int i = 0; i < nv; ++i)
    if (known[i]) queue.push_back(i);
  while (!queue.empty()) {
    const int i = queue.front();
    queue.pop_front();
    for (int j : adj[i])
      if (!seen[j]) seen[j] = 1, queue.push_back(j);
  }
  return static_cast<int>(std::count(seen.begin(), seen.end(), 0));
}

}  // namespace

HandleTransform handle_translation(const Eigen::RowVector3d& d) {
  HandleTransform T;
  T.topRows(3).setIdentity();
  T.row(3) = d;
  return T;
}

VariationalDeform::VariationalDeform(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                     const std::vector<int>& fixed_in, const std::vector<int>& handle_in,
                                     const VariationalDeformOptions& opts)
    : V_(V) {
  const auto t0 = std::chrono::steady_clock::now();
  const int nv = static_cast<int>(V.rows());
  if (opts.order != 2 && opts.order != 3)
    throw Error("variational deform: order must be 2 (biharmonic) or 3 (triharmonic), not " + std::to_string(opts.order));
  if (V.cols() != 3) throw Error("variational deform: vertices must have 3 coordinates");
  if (F.size() && (F.cols() != 3 || F.minCoeff() < 0 || F.maxCoeff() >= nv))
    throw Error("variational deform: a triangle's index is out of range (" + std::to_string(nv) + " vertices)");
  const std::vector<int> fixed = sorted_unique(fixed_in);
  handle_ = sorted_unique(handle_in);
  check_range(fixed, nv, "fixed");
  check_range(handle_, nv, "handle");
  if (handle_.empty()) throw Error("variational deform: the handle region is empty");
  std::vector<char> known(nv, 0);
  for (int i : fixed) known[i] = 1;
  for (int i : handle_) {
    if (known[i]) throw Error("variational deform: vertex " + std::to_string(i) + " is both fixed and in the handle");
    known[i] = 1;
  }
  for (int i = 0; i < nv; ++i)
    if (!known[i]) free_.push_back(i);
  if (free_.empty()) throw Error("variational deform: the free region is empty (every vertex is fixed or in the handle)");
  if (const int lost = count_unreachable(nv, F, known))
    throw Error("variational deform: " + std::to_string(lost) +
                " free vertices have no path through the mesh to a fixed or handle vertex (the free region is "
                "unreachable; hold that part of the surface)");

  const Sparse K = surface_cotangent_stiffness(V, F, /*clamp_negative=*/false);
  const Eigen::VectorXd m = surface_lumped_mass(V, F);
  // A vertex without area has no equation (its row of K is empty too); 0 keeps it out of the products.
  const Eigen::VectorXd minv = m.unaryExpr([](double x) { return x > 0 ? 1.0 / x : 0.0; });
  const Sparse S = selector(free_, nv);
  // The free rows of Q only: K_{Omega,:} M^-1 K (M^-1 K), 3.12 with v (and w) eliminated.
  Sparse R = S * K;
  for (int p = 1; p < opts.order; ++p) R = (R * minv.asDiagonal() * K).pruned();
  const Sparse Qff = R * S.transpose();
  Q_free_handle_ = R * selector(handle_, nv).transpose();
  solver_.factorize(Qff);
  factor_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Eigen::MatrixXd VariationalDeform::solve(const HandleTransform& T) const {
  const Eigen::Index nh = static_cast<Eigen::Index>(handle_.size());
  Eigen::MatrixXd Ph(nh, 3), Dh(nh, 3);
  for (Eigen::Index k = 0; k < nh; ++k) {
    const Eigen::RowVector3d p = V_.row(handle_[k]);
    Ph.row(k) = p * T.topRows(3) + T.row(3);
    Dh.row(k) = Ph.row(k) - p;
  }
  const Eigen::MatrixXd rhs = -(Q_free_handle_ * Dh);
  const Eigen::MatrixXd d = solver_.solve(rhs);
  Eigen::MatrixXd out = V_;  // the fixed rows are copied, never computed
  for (size_t k = 0; k < free_.size(); ++k) out.row(free_[k]) += d.row(static_cast<Eigen::Index>(k));
  for (Eigen::Index k = 0; k < nh; ++k) out.row(handle_[k]) = Ph.row(k);
  return out;
}

}  // namespace dfm
