#pragma once
// Linear blend skinning, the CPU reference in double precision:  p' = sum_j w_j (A_j p + t_j).
// Normals: n' = normalize(cof(sum_j w_j A_j) n), the cofactor matrix being how surface normals
// (cross products of tangents) transform under a linear map.
#include <Eigen/Core>
#include <Eigen/Sparse>

#include "core/rig/pose.h"
#include "core/skin/influences.h"

namespace dfm {

// V: #V x 3 rest positions; N: #V x 3 rest normals or empty (then NU is left empty).
// Throws dfm::Error when sizes disagree or an influence names a handle the pose lacks.
void lbs(const Eigen::MatrixXd& V, const Eigen::MatrixXd& N, const Influences& inf, const Pose& pose,
         Eigen::MatrixXd& U, Eigen::MatrixXd* NU = nullptr);
Eigen::MatrixXd lbs(const Eigen::MatrixXd& V, const Eigen::MatrixXd& W, const Pose& pose);

// libigl's dense formulation, kept as an independent reference and benchmark baseline:
// M = lbs_matrix(V, W) is #V x 4#H with M(i, 4h + c) = W(i,h) * [V(i,:) 1](c), so that
// U = M * pose_matrix(pose), pose_matrix being the 4#H x 3 stack of each [A_h t_h]^T.
Eigen::MatrixXd lbs_matrix(const Eigen::MatrixXd& V, const Eigen::MatrixXd& W);
Eigen::MatrixXd pose_matrix(const Pose& pose);
// The inverse of pose_matrix: one affine per 4-row block.
Pose pose_from_matrix(const Eigen::MatrixXd& T);
// The same M with only the nonzero weights stored (bind weights are sparse), row-major.
Eigen::SparseMatrix<double, Eigen::RowMajor> sparse_lbs_matrix(const Eigen::MatrixXd& V, const Eigen::MatrixXd& W);

// cof(M) n, normalized (zero stays zero).
Eigen::Vector3d transform_normal(const Eigen::Matrix3d& M, const Eigen::Vector3d& n);
// Shared argument checks for every skinning method.
void check_skin_inputs(const Eigen::MatrixXd& V, const Eigen::MatrixXd& N, const Influences& inf, const Pose& pose);

}  // namespace dfm
