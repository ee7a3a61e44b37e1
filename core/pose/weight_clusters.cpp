#include "core/pose/weight_clusters.h"

#include <algorithm>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/util/error.h"

namespace dfm {
namespace {

// k-means++: each next centre drawn with probability proportional to the squared distance to the
// nearest centre so far; stops early when every row coincides with a centre.
Eigen::MatrixXd seed_centres(const Eigen::MatrixXd& W, int k, std::mt19937& rng) {
  const int n = static_cast<int>(W.rows());
  std::vector<Eigen::VectorXd> centres{W.row(std::uniform_int_distribution<int>(0, n - 1)(rng)).transpose()};
  Eigen::VectorXd d2 = (W.rowwise() - centres[0].transpose()).rowwise().squaredNorm();
  while (static_cast<int>(centres.size()) < k) {
    const double total = d2.sum();
    if (!(total > 0)) break;
    double pick = std::uniform_real_distribution<double>(0.0, total)(rng);
    int i = 0;
    for (; i < n - 1 && pick >= d2(i); ++i) pick -= d2(i);
    centres.push_back(W.row(i).transpose());
    d2 = d2.cwiseMin((W.rowwise() - centres.back().transpose()).rowwise().squaredNorm());
  }
  Eigen::MatrixXd C(centres.size(), W.cols());
  for (size_t c = 0; c < centres.size(); ++c) C.row(c) = centres[c].transpose();
  return C;
}

int nearest(const Eigen::MatrixXd& C, const Eigen::VectorXd& p) {
  int best = 0;
  double bd = std::numeric_limits<double>::infinity();
  for (int c = 0; c < C.rows(); ++c) {
    const double d = (C.row(c).transpose() - p).squaredNorm();
    if (d < bd) bd = d, best = c;
  }
  return best;
}

}  // namespace

WeightClusters weight_clusters(const Eigen::MatrixXd& W, int clusters, int max_iterations, unsigned seed) {
  if (W.rows() == 0) throw Error("rotation clusters: no vertices");
  if (clusters < 1) throw Error("rotation clusters: need at least one cluster, got " + std::to_string(clusters));
  std::mt19937 rng(seed);
  Eigen::MatrixXd C = seed_centres(W, std::min<int>(clusters, static_cast<int>(W.rows())), rng);
  const int n = static_cast<int>(W.rows()), k = static_cast<int>(C.rows());
  Eigen::VectorXi label = Eigen::VectorXi::Constant(n, -1);
  for (int it = 0; it < max_iterations; ++it) {
    bool changed = false;
    for (int i = 0; i < n; ++i) {
      const int c = nearest(C, W.row(i).transpose());
      if (c != label(i)) label(i) = c, changed = true;
    }
    if (!changed) break;
    Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(k, W.cols());
    Eigen::VectorXi count = Eigen::VectorXi::Zero(k);
    for (int i = 0; i < n; ++i) sum.row(label(i)) += W.row(i), ++count(label(i));
    for (int c = 0; c < k; ++c)
      if (count(c)) C.row(c) = sum.row(c) / count(c);
  }
  WeightClusters out;
  std::vector<int> renumber(k, -1);
  out.cluster.resize(n);
  for (int i = 0; i < n; ++i) {
    int& r = renumber[label(i)];
    if (r < 0) r = out.count++;
    out.cluster(i) = r;
  }
  return out;
}

}  // namespace dfm
