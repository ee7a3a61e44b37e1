#include "core/export/prune.h"

#include <cmath>
#include <string>

#include <vector>

#include <Eigen/Dense>

#include "core/util/error.h"

namespace dfm {

Influences prune_for_export(const Eigen::MatrixXd& W, int k) {
  if (k < 1) throw Error("influence pruning: k must be at least 1, got " + std::to_string(k));
  if (W.cols() < 1) throw Error("influence pruning: weight matrix has no columns");
  if (!W.allFinite()) throw Error("influence pruning: weights contain a non-finite value");
  Influences inf = top_influences(W.cwiseMax(0.0), k, true);
  for (int v = 0; v < inf.num_vertices(); ++v) {
    if (inf.weight.row(v).sum() <= 0) {
      int best = 0;
      for (int h = 1; h < W.cols(); ++h)
        if (std::abs(W(v, h)) > std::abs(W(v, best))) best = h;
      inf.weight.row(v).setZero();
      inf.index.row(v).setZero();
      inf.weight(v, 0) = 1.0;
      inf.index(v, 0) = best;
    }
    for (int j = 0; j < inf.k(); ++j)
      if (inf.weight(v, j) <= 0) inf.weight(v, j) = 0, inf.index(v, j) = 0;
  }
  return inf;
}

int refit_influences(Influences& inf, const Eigen::MatrixXd& V, const Eigen::MatrixXd& W,
                     const std::vector<Pose>& poses) {
  if (V.rows() != inf.num_vertices() || W.rows() != V.rows()) throw Error("refit_influences: sizes differ");
  const int np = static_cast<int>(poses.size());
  for (const auto& p : poses)
    if (p.size() != W.cols()) throw Error("refit_influences: a pose does not match the weight columns");
  if (np == 0) return 0;
  int refit = 0;
  for (int v = 0; v < inf.num_vertices(); ++v) {
    std::vector<int> kept;
    double kept_mass = 0;
    for (int j = 0; j < inf.k(); ++j)
      if (inf.weight(v, j) > 0) kept.push_back(j);
    for (int j : kept) kept_mass += std::max(0.0, W(v, inf.index(v, j)));
    const double total = W.row(v).cwiseMax(0.0).sum();
    if (kept.size() < 2 || total - kept_mass <= 1e-15 * total) continue;  // nothing dropped, or nothing to solve
    const int m = static_cast<int>(kept.size());
    const Eigen::Vector3d p = V.row(v).transpose();
    Eigen::MatrixXd A(3 * np, m);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(3 * np);
    for (int q = 0; q < np; ++q) {
      for (int j = 0; j < m; ++j) A.block(3 * q, j, 3, 1) = poses[q].transforms[inf.index(v, kept[j])] * p;
      for (int h = 0; h < W.cols(); ++h)
        if (W(v, h) != 0) b.segment<3>(3 * q) += W(v, h) * (poses[q].transforms[h] * p);
    }
    Eigen::VectorXd w0(m);
    for (int j = 0; j < m; ++j) w0[j] = inf.weight(v, kept[j]);
    const double lambda = 1e-10 * std::max(A.squaredNorm() / m, 1e-300);
    // Active set on w >= 0 with sum(w) = 1: solve the equality-constrained problem on the free set,
    // fix the most negative weight at 0, repeat.
    std::vector<bool> free(m, true);
    Eigen::VectorXd w = w0;
    for (int it = 0; it < m; ++it) {
      std::vector<int> F;
      for (int j = 0; j < m; ++j)
        if (free[j]) F.push_back(j);
      const int f = static_cast<int>(F.size());
      Eigen::MatrixXd K = Eigen::MatrixXd::Zero(f + 1, f + 1);
      Eigen::VectorXd r(f + 1);
      for (int a = 0; a < f; ++a) {
        for (int c = 0; c < f; ++c) K(a, c) = A.col(F[a]).dot(A.col(F[c]));
        K(a, a) += lambda;
        K(a, f) = K(f, a) = 1.0;
        r[a] = A.col(F[a]).dot(b) + lambda * w0[F[a]];
      }
      r[f] = 1.0;
      const Eigen::VectorXd x = K.fullPivLu().solve(r);
      w.setZero();
      int worst = -1;
      for (int a = 0; a < f; ++a) {
        w[F[a]] = x[a];
        if (x[a] < 0 && (worst < 0 || x[a] < w[worst])) worst = F[a];
      }
      if (worst < 0 || f == 1) break;
      free[worst] = false;
    }
    w = w.cwiseMax(0.0);
    if (!w.allFinite() || w.sum() <= 0) continue;  // keep the renormalized weights
    w /= w.sum();
    for (int j = 0; j < m; ++j) inf.weight(v, kept[j]) = w[j];
    for (int j = 0; j < inf.k(); ++j)
      if (inf.weight(v, j) <= 0) inf.weight(v, j) = 0, inf.index(v, j) = 0;
    ++refit;
  }
  return refit;
}

}  // namespace dfm
