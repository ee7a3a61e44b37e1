#pragma once
// Additional handles (Jacobson 2013, 7.3.3): abstract handles past the rig's, one per additional weight
// column (core/bind/additional_weights.h), whose transforms only FAST sets. They live in
// PoseParams::solved under the indices num_handles(rig) + e, so keys, scenes and interpolation carry
// them like any solved transform.
//
// Unsolved (FAST off, a fresh pose) an additional handle's transform is ZERO, not the identity: the
// additional weights do not partition unity, so identity would add w(v) v to each vertex and swell
// the mesh, while zero leaves exactly the original bind's skin. At rest FAST finds zero too (the
// original weights alone reproduce the rest shape, and the energy is 0 there).
#include <Eigen/Core>

#include "core/rig/pose.h"
#include "core/rig/pose_params.h"
#include "core/rig/rig.h"

namespace dfm {

// The transform of a handle nobody has solved: the zero 3 x 4 matrix.
Eigen::Affine3d zero_transform();

// evaluate_pose(rig, params) followed by `additional` transforms: params.solved[num_handles(rig) + e],
// or zero_transform(). The pose skinning with [W | additional weights] takes.
Pose skin_pose(const Rig& rig, const PoseParams& params, int additional);

// Erases params.solved's entries from num_rig_handles on (the additional handles'): before a rig edit
// gives those indices to new handles.
void drop_additional_transforms(PoseParams& params, int num_rig_handles);

// [W | A] (A empty or with W's rows): the weights skinning and FAST use. Throws dfm::Error on a row mismatch.
Eigen::MatrixXd with_additional_weights(const Eigen::MatrixXd& W, const Eigen::MatrixXd& A);

}  // namespace dfm
