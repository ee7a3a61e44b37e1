#pragma once
// FAST posing for the editor and the script (one code path): turns a pose's parameters into solved
// transforms for every handle that is not fixed, caching the precomputation (rebuilt when the weights
// or the energy mesh change) and the constraint switch (rebuilt when the states change), and warm
// starting from the transforms solved last time (Jacobson 2013, 7.3: local-global from the last frame).
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "core/pose/fast_model.h"
#include "core/pose/fast_solver.h"
#include "core/rig/pose_params.h"
#include "core/rig/rig.h"

namespace dfm {

// Per handle (rig.h order): points and cage vertices position-constrained, bones and regions fixed.
std::vector<HandleConstraint> default_constraint_states(const Rig& rig);

struct FastSolveReport {
  bool precomputed = false, switched = false;  // whether this call rebuilt them
  double precompute_seconds = 0, switch_seconds = 0, iterate_seconds = 0;
  int iterations = 0, clusters = 0;
  double energy = 0;  // after the last iteration
};

class FastPosing {
 public:
  // V, elements, W: the energy mesh (the surface with its triangles, or the bind's tets) and its weights;
  // columns past the rig's handles are additional handles (additional_handles.h), always free, solved
  // into params.solved[num_handles(rig) + e].
  // Fixed transforms come from evaluate_pose(params) without solved entries, position targets from
  // evaluate_handle_parameters; the skeleton's joints are constraints (fast_joints), so solved bones
  // stay connected. params.solved is rewritten to hold exactly the non-fixed handles' solved transforms.
  // Throws dfm::Error when sizes disagree with the rig.
  FastSolveReport solve(const Rig& rig, const Eigen::MatrixXd& V, const Eigen::MatrixXi& elements,
                        const Eigen::MatrixXd& W, const std::vector<HandleConstraint>& states, int iterations,
                        PoseParams& params);
  void invalidate();

 private:
  struct Signature {
    const void* data[3] = {nullptr, nullptr, nullptr};
    Eigen::Index size[3] = {0, 0, 0};
    double fingerprint[3] = {0, 0, 0};
    bool operator==(const Signature& o) const;
  };
  Signature model_signature_;
  std::unique_ptr<FastModel> model_;
  std::vector<FastConstraint> constraints_;
  std::vector<FastJoint> joints_;  // the skeleton's (fast_joints): every solve keeps bones connected
  std::unique_ptr<FastSolver> solver_;
};

}  // namespace dfm
