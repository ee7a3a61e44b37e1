#pragma once
// FAST precomputation that does not depend on which handles are constrained (Jacobson 2013, 7.3.1):
// the reduced ARAP energy of Eq. 7.15 in the transform unknowns T (4m x 3, core/skin/lbs.h's pose_matrix:
// handle j's rows 4j..4j+3 are [A_j t_j]^T, so V' = M T is the LBS of Eq. 7.2):
//   E(T, R) = 1/2 tr(T^T Lt T) - tr(R Kt T) + const,   Lt = M^T L M,  Kt = K M,
// with M the LBS matrix of the energy mesh (M(i, 4j + c) = w_ij [v_i; 1]_c), L and K from the
// element edge sets of arap_elements.h grouped into rotation clusters (weight_clusters.h).
#include <Eigen/Core>

namespace dfm {

enum class FastEnergy { SpokesAndRims, Tetrahedra };

struct FastModelOptions {
  int clusters = 0;  // rotation clusters r; 0: twice the number of handles (7.3.2)
  int kmeans_iterations = 50;
  unsigned seed = 1;
};

struct FastModel {
  int handles = 0;
  int clusters = 0;
  Eigen::MatrixXd Lt;  // 4m x 4m, symmetric positive semi-definite
  Eigen::MatrixXd Kt;  // 3r x 4m; rows 3k..3k+2 are cluster k's
  double rest_term = 0;  // 1/2 tr(V^T L V): the energy's constant, so E >= 0 for c_ij >= 0
  double cluster_seconds = 0, assembly_seconds = 0;
};

// V (#V x 3) and W (#V x m, rows sum to 1) on the energy mesh; elements #E x 3 (surface: spokes and
// rims) or #E x 4 (the bind's tets). Throws dfm::Error on mismatched sizes or a degenerate element.
FastModel fast_model(const Eigen::MatrixXd& V, const Eigen::MatrixXi& elements, const Eigen::MatrixXd& W,
                     const FastModelOptions& opts = {});

}  // namespace dfm
