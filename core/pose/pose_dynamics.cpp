#include "core/pose/pose_dynamics.h"

#include <cmath>
#include <string>

#include "core/pose/fast_rig.h"
#include "core/rig/additional_handles.h"
#include "core/util/error.h"

namespace dfm {

PoseDynamics::PoseDynamics(const Rig& rig, const Eigen::MatrixXd& V, const Eigen::MatrixXi& elements,
                           const Eigen::MatrixXd& W, const std::vector<HandleConstraint>& states,
                           const FastDynamicsOptions& opts, double density, const PoseParams& start)
    : states_(states), opts_(opts) {
  const int nh = num_handles(rig);
  if (static_cast<int>(states.size()) != nh || W.cols() < nh)
    throw Error("dynamics: " + std::to_string(states.size()) + " handle states and " + std::to_string(W.cols()) +
                " weight columns for a rig of " + std::to_string(nh) + " handles");
  // Columns past the rig's: additional handles (additional_handles.h), free like any unset handle.
  states_.resize(W.cols(), HandleConstraint::Free);
  nh_ = nh;
  model_ = std::make_unique<FastModel>(fast_model(V, elements, W));
  mass_ = std::make_unique<FastMass>(fast_mass(V, elements, W, density));
  diagonal_ = std::max(1e-12, (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm());
  restart(rig, start);
}

std::vector<FastConstraint> PoseDynamics::constraints(const Rig& rig) const {
  std::vector<FastConstraint> c(states_.size());
  for (size_t h = 0; h < states_.size(); ++h)
    c[h] = {states_[h], static_cast<int>(h) < nh_ ? handle_anchor(rig, static_cast<int>(h)) : Eigen::Vector3d::Zero()};
  return c;
}

void PoseDynamics::restart(const Rig& rig, const PoseParams& start) {
  const int n = static_cast<int>(states_.size());
  dyn_.reset();
  dyn_ = std::make_unique<FastDynamics>(*model_, *mass_, constraints(rig), fast_joints(rig), opts_,
                                        skin_pose(rig, start, n - nh_));
  steps_ = 0;
}

void PoseDynamics::step(const Rig& rig, PoseParams& params) {
  const int n = static_cast<int>(states_.size());
  PoseParams base = params;
  base.solved.clear();
  Pose pose = skin_pose(rig, base, n - nh_);  // Fixed handles' transforms: the boundary condition
  dyn_->step(pose, fast_targets(constraints(rig), evaluate_handle_parameters(rig, base)));
  ++steps_;
  params.solved.clear();
  for (int h = 0; h < n; ++h)
    if (states_[h] != HandleConstraint::Fixed) params.solved[h] = pose.transforms[h];
}

double PoseDynamics::relative_speed() const {
  return std::sqrt(2 * dyn_->kinetic_energy() / std::max(1e-300, mass_->total)) / diagonal_;
}

}  // namespace dfm
