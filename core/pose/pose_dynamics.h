#pragma once
// Dynamics for the editor and the script (what FastPosing is to the static solve): turns pose
// parameters into the handles' transforms one time step at a time (FastDynamics, Jacobson 2013 7.7).
// The parameters give the boundary conditions (Fixed handles' transforms, position targets); free
// handles follow by momentum. Built per drag or per simulation: its state is the motion since then.
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "core/pose/fast_dynamics.h"
#include "core/pose/fast_model.h"
#include "core/rig/pose_params.h"
#include "core/rig/rig.h"

namespace dfm {

class PoseDynamics {
 public:
  // V, elements, W: the energy mesh and its weights (as FastPosing::solve; columns past the rig's are
  // additional handles, additional_handles.h). `start`: the pose at rest
  // at t = 0 (its solved transforms where present). Throws dfm::Error on mismatched sizes or bad options.
  PoseDynamics(const Rig& rig, const Eigen::MatrixXd& V, const Eigen::MatrixXi& elements, const Eigen::MatrixXd& W,
               const std::vector<HandleConstraint>& states, const FastDynamicsOptions& opts, double density,
               const PoseParams& start);
  // A new simulation at rest in `start` on the same mesh, weights, states and options: keeps the
  // model and the mass (the precompute), rebuilds only the momentum solve (a small switch).
  void restart(const Rig& rig, const PoseParams& start);
  // One time step toward `params`' constraints; params.solved receives the non-fixed handles' transforms.
  void step(const Rig& rig, PoseParams& params);
  // Root-mean-square vertex speed sqrt(2 KE / mass) over the bounding box's diagonal (1/s): below
  // ~1e-3 the motion has settled.
  double relative_speed() const;
  int steps() const { return steps_; }

 private:
  std::vector<FastConstraint> constraints(const Rig& rig) const;

  std::vector<HandleConstraint> states_;  // the rig's, then Free for each additional handle
  int nh_ = 0;                            // the rig's handles
  FastDynamicsOptions opts_;
  std::unique_ptr<FastModel> model_;
  std::unique_ptr<FastMass> mass_;
  std::unique_ptr<FastDynamics> dyn_;
  double diagonal_ = 1;
  int steps_ = 0;
};

}  // namespace dfm
