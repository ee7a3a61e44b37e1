#pragma once
// The primal Laplacian boundary condition of Southern 2008, 4.4.1 (Eq. 4.3): at a vertex on the
// manifold's open boundary (an animation manifold's first and last layers), the weights are those that
// make the differential coordinate smallest,
//   min_w | v_i - sum_j w_j v_j |^2   subject to   sum_j w_j = 1,  w_j >= xi,
// so delta_i carries no tangential part (Fig. 4.7: even weights there give a purely tangential delta).
// Q = N^T N has rank <= 4 for a 4D one-ring of more than 4 vertices, so the minimiser is not unique; a
// small proximal term eps |w - w0|^2 toward the start weights w0 (the reciprocal ones) picks the one
// nearest them. Solved by accelerated projected gradient (FISTA) on the shifted simplex; the problem
// is a few dozen variables, so no sparse machinery.
#include <vector>

#include <Eigen/Core>

namespace dfm {

struct PrimalWeightOptions {
  double xi = 1e-3;          // lower bound on each weight (4.4.1's xi; must be < 1 / #neighbours)
  double proximal = 1e-4;    // eps, relative to trace(Q) / #neighbours
  int iterations = 400;
};

// v: the vertex (4), N: its neighbours (k x 4), w0: start weights (k, summing to 1). Returns weights
// that sum to 1 and are >= xi. Throws dfm::Error for k == 0 or xi >= 1 / k.
Eigen::VectorXd primal_boundary_weights(const Eigen::Vector4d& v, const Eigen::MatrixXd& N, const Eigen::VectorXd& w0,
                                        const PrimalWeightOptions& options = {});

// Euclidean projection of y onto { w : sum w = 1, w >= xi }.
Eigen::VectorXd project_shifted_simplex(const Eigen::VectorXd& y, double xi);

}  // namespace dfm
