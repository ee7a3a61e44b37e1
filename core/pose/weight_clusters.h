#pragma once
// Rotation clusters (Jacobson 2013, 7.3.2): vertices grouped by k-means on their rows of the weight
// matrix, so vertices that skinning moves alike share one best-fit rotation. Rigid parts (identical
// rows) collapse to one point of weight space and land in one cluster.
#include <Eigen/Core>

namespace dfm {

struct WeightClusters {
  Eigen::VectorXi cluster;  // #V, in [0, count)
  int count = 0;            // clusters actually used (never more than the distinct rows)
};

// k-means++ seeding (deterministic for a given seed), then Lloyd iterations until no vertex changes
// cluster or `max_iterations` pass; empty clusters are dropped and the rest renumbered.
WeightClusters weight_clusters(const Eigen::MatrixXd& W, int clusters, int max_iterations = 50, unsigned seed = 1);

}  // namespace dfm
