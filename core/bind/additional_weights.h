#pragma once
// Additional weight functions (Jacobson 2013, 7.3.3): abstract handles whose transformations FAST
// solves and nobody sets, enriching the skinning subspace where fully constrained handles leave no
// freedom (a cigar bent by its ends pinches, Fig. 7.7d-e). The original weights keep the partition of
// unity; the additional ones need not (the energies are translation invariant, 7.3.3).
//
// Here: k farthest-point samples among the bind volume's vertices, starting from the vertices the
// rig's handles constrain, each a new point handle; bounded biharmonic weights (ch. 4) on the same
// volume for the old and new handles together, of which the new handles' columns are returned.
#include <vector>

#include <Eigen/Core>

#include "core/bind/bind.h"

namespace dfm {

// Indices of k vertices of V, each the farthest (Euclidean) from `seeds` and the samples before it.
// Throws dfm::Error when V has fewer than k vertices outside the seeds, or no seeds are given.
std::vector<int> farthest_point_samples(const Eigen::MatrixXd& V, const std::vector<int>& seeds, int k);

struct AdditionalWeights {
  Eigen::MatrixXd weights;               // #user vertices x k (bind.weights' rows), in [0, 1]
  std::vector<Eigen::Vector3d> points;   // the samples, rest positions
  BindReport report;                     // of the solve with the extra handles
};

// From a finished bind (its volume and constraints). Throws dfm::Error for k < 1.
AdditionalWeights additional_weights(const BindResult& bind, int k, const BindOptions& opts = {});

}  // namespace dfm
