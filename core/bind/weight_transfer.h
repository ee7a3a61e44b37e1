#pragma once
// Skin weights carried from a bound surface onto another (clothing, a remeshed or subdivided
// character), after Abdrashitov et al. 2023, "Robust Skin Weights Transfer via Weight Inpainting":
// 1. each target vertex is matched to its closest point on the source (barycentric in the closest
//    triangle) when that point is within max_distance and the normals there differ by at most
//    max_angle_degrees; a matched vertex takes the source's weights there, blended barycentrically;
// 2. the others are inpainted: per handle, the Dirichlet energy w^T K w on the target (cotangent
//    stiffness, clamped: surface_laplacian.h, so the maximum principle holds) is minimized with the
//    matched vertices fixed; a piece of the target with no matched vertex takes its closest source
//    points' weights whatever their distance;
// 3. inpainted rows are clamped to [0, 1] and divided by their sums (matched rows are blends of rows
//    summing to 1 and are kept as they are: a vertex on the source reads its weights exactly).
#include <Eigen/Core>

namespace dfm {

struct WeightTransferOptions {
  double max_distance = -1;        // < 0: 5% of the source's bounding-box diagonal
  double max_angle_degrees = 30;  // between the target's vertex normal and the source's face normal
};

struct WeightTransferReport {
  int matched = 0, inpainted = 0;
  int nearest = 0;  // vertices of pieces with no match, given their closest source point's weights
  double max_distance = 0;  // the distance used
};

// Source (V, F) with weights W (#V x #handles); target (TV, TF), open, non-manifold or in pieces.
// Returns #TV x #handles. Throws dfm::Error on sizes, indices or an empty source.
Eigen::MatrixXd transfer_weights(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& W,
                                 const Eigen::MatrixXd& TV, const Eigen::MatrixXi& TF,
                                 const WeightTransferOptions& options = {}, WeightTransferReport* report = nullptr);

}  // namespace dfm
