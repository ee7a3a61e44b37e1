#pragma once
// FAST local-global iterations (Jacobson 2013, 7.3.1) for one set of constraint states. Handles are
// fixed (transform given), position-constrained (the image of an anchor point given, the rest of the
// transform solved) or free (solved entirely: shape-aware IK). The constructor is Table 7.1's "switch"
// precomputation: the KKT system of Eq. 7.19 restricted to the unknown blocks, inverted once, giving
//   T_unknown = Gamma R^T + Phi(targets)
// so an iteration is S = Kt T, r SVDs, one small product: independent of the mesh size.
#include <vector>

#include <Eigen/Core>

#include "core/pose/fast_model.h"
#include "core/rig/handle_constraint.h"
#include "core/rig/pose.h"

namespace dfm {

struct FastConstraint {
  HandleConstraint state = HandleConstraint::Fixed;
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();  // rest point a Position constraint moves
};

// Two handles that must map `point` to the same place: a bone's first joint and the bone it hangs
// from (core/rig/forward_kinematics.h, bone_attachments). More rows of Eq. 7.15's M_eq T = P_eq, with
// P_eq = 0: [point; 1]^T (T_child - T_parent) = 0. A joint whose child is fixed adds nothing (the
// child follows its parent afterwards, connect_bones).
struct FastJoint {
  int child = -1, parent = -1;  // handle indices
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  bool operator==(const FastJoint& o) const { return child == o.child && parent == o.parent && point == o.point; }
};

class FastSolver {
 public:
  // One constraint per handle of the model; joints as above. `inertia` (4m x 4m, symmetric positive
  // semi-definite, or empty) is added to Lt: the momentum term (1/h^2) W^T M W of Eq. 7.36
  // (fast_dynamics.h); it changes only this precomputation. Throws dfm::Error on a size mismatch.
  FastSolver(const FastModel& model, std::vector<FastConstraint> constraints, std::vector<FastJoint> joints = {},
             Eigen::MatrixXd inertia = {});

  // Per-frame inputs: `pose` supplies the transforms of the Fixed handles; targets[j] is where the
  // anchor of Position handle j must go (entries for other handles are ignored).
  void set_targets(const Pose& pose, const std::vector<Eigen::Vector3d>& targets);
  // A linear term -tr(B^T T) of the energy (B: 4m x 3), kept until set again: Eq. 7.36's
  // (T0 + h S0)^T Mt, plus external forces. Only a solver built with `inertia` takes one (else
  // dfm::Error); it moves Phi, never the local step (7.7.1).
  void set_linear_term(const Eigen::MatrixXd& B);
  // Both at once (Phi formed once): what a dynamics step sets.
  void set_targets(const Pose& pose, const std::vector<Eigen::Vector3d>& targets, const Eigen::MatrixXd& B);

  // One iteration: local step from the current transforms of `pose` (warm start), global step written
  // back into its non-fixed handles. Returns E(T, R) after the global step (Eq. 7.15 plus the rest
  // term; with inertia, Eq. 7.36's terms too), which never increases from one iteration to the next
  // for fixed targets; NaN when with_energy is false (the energy costs as much as the iteration).
  double iterate(Pose& pose, bool with_energy = true) const;
  // `count` iterations as one call, for the same result as `count` calls of iterate (to rounding):
  // where it is cheaper, the iterations in between stay in rotation space,
  //   S = (Kt_u Gamma) R^T + (Kt_u Phi + Kt_f T_f),
  // one 3r x 3r product instead of two 3r x 4u ones, and T is formed once at the end.
  void iterate(Pose& pose, int count) const;

  const std::vector<FastConstraint>& constraints() const { return constraints_; }
  double switch_seconds() const { return switch_seconds_; }

 private:
  void read_unknown_blocks(const Pose& pose) const;
  void local_step() const;                // Rt_ from S_
  void global_step(Pose& pose) const;     // T_u = Gamma R^T + Phi into pose
  void write_unknown_blocks(Pose& pose) const;
  void update_phi();  // Phi and s_const from T_fixed_, P_ and B_
  void read_targets(const Pose& pose, const std::vector<Eigen::Vector3d>& targets);  // T_fixed_, P_, s_fixed_
  void check_linear_term(const Eigen::MatrixXd& B) const;
  double dynamic_terms(const Eigen::MatrixXd& T) const;  // 1/2 tr(T^T inertia T) - tr(B^T T)

  const FastModel* model_;
  std::vector<FastConstraint> constraints_;
  std::vector<int> unknown_, fixed_, position_;  // handle indices by state
  std::vector<int> unknown_rows_;                 // rows of T in the unknown blocks
  Eigen::MatrixXd Kt_u_, Kt_f_;     // Kt's columns of unknown / fixed blocks
  Eigen::MatrixXd gamma_;           // 4u x 3r
  Eigen::MatrixXd pi_fixed_;        // 4u x 4f: -Pi11 Lt_uf - Pi12 C_f (joint rows on fixed blocks)
  Eigen::MatrixXd pi_targets_;      // 4u x c:   Pi12
  Eigen::MatrixXd phi_;             // 4u x 3 for the current targets
  Eigen::MatrixXd s_fixed_;         // 3r x 3: Kt_f T_f for the current fixed transforms
  Eigen::MatrixXd T_fixed_;         // 4f x 3
  Eigen::MatrixXd P_;               // c x 3: the position targets
  Eigen::MatrixXd inertia_;         // 4m x 4m or empty
  Eigen::MatrixXd B_;               // 4m x 3 linear term (with inertia_)
  Eigen::MatrixXd pi_linear_;       // 4u x 4u: Pi11, maps B's unknown rows into Phi (with inertia_)
  bool rotation_space_ = false;     // whether iterate(pose, count) stays in rotation space
  Eigen::MatrixXd kt_gamma_;        // 3r x 3r: Kt_u Gamma (when rotation_space_)
  Eigen::MatrixXd s_const_;         // 3r x 3: Kt_u Phi + s_fixed for the current targets
  double switch_seconds_ = 0;
  // Per-iteration scratch, sized once: an iteration allocates nothing.
  mutable Eigen::MatrixXd X_, S_, Rt_;
};

// E(T, R) for given transforms with the best rotations for them (the energy a local step reaches).
double fast_energy(const FastModel& model, const Pose& pose);

}  // namespace dfm
