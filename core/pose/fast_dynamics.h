#pragma once
// Physically based dynamics in the FAST subspace (Jacobson 2013, 7.7): each time step minimizes
//   1/2 tr(T^T (Lt + a Mt) T) - tr((R Kt + a Y^T Mt + F^T) T)   subject to the handles' constraints
// (Eq. 7.36), Mt = W^T M W with M the lumped mass, by the same local-global iterations as the static
// solve; only the switch (Lt + a Mt) and the right-hand side (a Mt Y + F) change, the local step does
// not (7.7.1). With mass-proportional damping c (an implicit force -c M v, added to Eq. 7.28)
//   a = (1 + c h) / h^2,   Y = T0 + h S0 / (1 + c h),
// which for c = 0 is Eq. 7.36's 1/h^2 and T0 + h S0 (S0: the transforms' velocity). F = W^T M 1 g^T is
// gravity. Fixed and position-constrained handles are the boundary conditions; free ones follow.
#include <vector>

#include <Eigen/Core>

#include "core/pose/fast_model.h"
#include "core/pose/fast_solver.h"
#include "core/rig/pose.h"

namespace dfm {

// What the lumped mass becomes in the subspace (7.7.2), independent of h: build it once per bind.
struct FastMass {
  Eigen::MatrixXd Mt;       // 4m x 4m: W^T M W (LBS matrix W of core/skin/lbs.h)
  Eigen::VectorXd moments;  // 4m: W^T M 1, gravity's reduced force per unit of g
  double total = 0;         // sum of the vertex masses
};

// Lumped mass on the energy mesh (Jacobson 2013, 2.1.3): a third of each triangle's area, or a quarter
// of each tet's volume, per vertex, times `density` / diagonal^2 (the bounding box's: the same
// motion whatever the model's units) and, when given, a per-vertex mask (#V, >= 0; painted: where the
// flesh is heavy). Throws dfm::Error on mismatched sizes or a negative mask or density.
FastMass fast_mass(const Eigen::MatrixXd& V, const Eigen::MatrixXi& elements, const Eigen::MatrixXd& W,
                   double density = 1.0, const Eigen::VectorXd& mask = {});

struct FastDynamicsOptions {
  double dt = 1.0 / 60;   // h, seconds
  double damping = 4.0;   // c, 1/s: mass-proportional; the arm's step settles within 2% in 1.6 s
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  // model units / s^2; off by default
  int iterations = 4;     // local-global iterations per step, warm-started at the inertial guess Y
};

// The state a simulation carries from step to step (T0, S0) and the solver built for it.
class FastDynamics {
 public:
  // `model` and `mass` must outlive it. `start`: the transforms at rest at t = 0 (velocity zero).
  // Throws dfm::Error for h <= 0, c < 0, fewer than one iteration or mismatched sizes.
  FastDynamics(const FastModel& model, const FastMass& mass, std::vector<FastConstraint> constraints,
               std::vector<FastJoint> joints, const FastDynamicsOptions& opts, const Pose& start);

  // One time step: `pose` supplies the Fixed handles' transforms and receives every handle's
  // transforms at the new time; targets as FastSolver::set_targets. solver().iterate(pose) gives
  // Eq. 7.36's objective for the step just taken, if wanted (it costs as much as an iteration).
  void step(Pose& pose, const std::vector<Eigen::Vector3d>& targets);

  const Eigen::MatrixXd& transforms() const { return T0_; }  // 4m x 3, pose_matrix layout
  const Eigen::MatrixXd& velocity() const { return S0_; }    // 4m x 3, dT/dt
  // 1/2 v^T M v of the vertices x = W T (exact in the subspace: 1/2 tr(S0^T Mt S0)).
  double kinetic_energy() const;
  const FastSolver& solver() const { return solver_; }

 private:
  const FastMass* mass_;
  FastDynamicsOptions opts_;
  double a_ = 0;  // (1 + c h) / h^2
  FastSolver solver_;
  Eigen::MatrixXd T0_, S0_, Y_, B_;
};

}  // namespace dfm
