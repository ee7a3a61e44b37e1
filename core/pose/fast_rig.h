#pragma once
// FAST constraints from a rig (Jacobson 2013, 7.3.1): what each handle kind pins by default, and the
// targets a pose gives the position-constrained handles.
//   point handles, cage vertices: position-constrained at their rest point (rotation solved);
//   bones, regions: fixed (their transform as posed);
//   handles listed as free: solved entirely.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/pose/fast_solver.h"
#include "core/rig/pose.h"
#include "core/rig/rig.h"

namespace dfm {

// The rest point a handle's position constraint moves: a point's position, a cage vertex, a bone's
// second joint (its tip, what IK drags), a region's centroid on `surface` (#V x 3; may be empty).
Eigen::Vector3d handle_anchor(const Rig& rig, int handle, const Eigen::MatrixXd& surface = {});

std::vector<FastConstraint> default_fast_constraints(const Rig& rig, const std::vector<int>& free_handles);

// targets[h] = pose(h) * anchor(h), for every handle (FastSolver reads the position-constrained ones).
std::vector<Eigen::Vector3d> fast_targets(const std::vector<FastConstraint>& constraints, const Pose& pose);

// IK on a bone chain (what "IK chain" in the Posing panel and the script's `ik-chain` do): `bone_handle`
// becomes position-constrained at its tip, the bones above it free up to the chain's root, which is
// pinned; every other state is kept. Throws dfm::Error when the handle is not a bone.
std::vector<HandleConstraint> ik_chain_states(const Rig& rig, std::vector<HandleConstraint> states, int bone_handle);

// The skeleton's joints (bone_attachments) as FAST joint rows: a solve keeps every bone starting
// where its parent ends.
std::vector<FastJoint> fast_joints(const Rig& rig);

// "2,point 3,bone 1": handle indices or names (find_handle) (rig.h order), in any mix. Throws dfm::Error naming an
// unknown entry.
std::vector<int> parse_handle_list(const Rig& rig, const std::string& list);

}  // namespace dfm
