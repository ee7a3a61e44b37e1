#include "core/pose/fast_solver.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <string>

#include <Eigen/Dense>

#include "core/pose/best_rotation.h"
#include "core/skin/lbs.h"
#include "core/util/error.h"

namespace dfm {
namespace {

// Rows (or columns) of the 4-row blocks of the given handles.
std::vector<int> block_indices(const std::vector<int>& handles) {
  std::vector<int> idx;
  for (int h : handles)
    for (int c = 0; c < 4; ++c) idx.push_back(4 * h + c);
  return idx;
}

// The best rotations for S (3r x 3), stacked transposed (3r x 3) as R^T of Eq. 7.19.
Eigen::MatrixXd best_rotations_transposed(const Eigen::MatrixXd& S) {
  Eigen::MatrixXd Rt(S.rows(), 3);
  for (int k = 0; 3 * k < S.rows(); ++k)
    Rt.block<3, 3>(3 * k, 0) = best_rotation(S.block<3, 3>(3 * k, 0)).transpose();
  return Rt;
}

double energy_of(const FastModel& model, const Eigen::MatrixXd& T, const Eigen::MatrixXd& Rt) {
  const Eigen::MatrixXd S = model.Kt * T;
  return 0.5 * (T.transpose() * model.Lt * T).trace() - Rt.cwiseProduct(S).sum() + model.rest_term;
}

}  // namespace

double fast_energy(const FastModel& model, const Pose& pose) {
  const Eigen::MatrixXd T = pose_matrix(pose);
  return energy_of(model, T, best_rotations_transposed(model.Kt * T));
}

FastSolver::FastSolver(const FastModel& model, std::vector<FastConstraint> constraints, std::vector<FastJoint> joints,
                       Eigen::MatrixXd inertia)
    : model_(&model), constraints_(std::move(constraints)), inertia_(std::move(inertia)) {
  const auto t0 = std::chrono::steady_clock::now();
  if (static_cast<int>(constraints_.size()) != model.handles)
    throw Error("FAST: " + std::to_string(constraints_.size()) + " constraint states for " +
                std::to_string(model.handles) + " handles");
  for (int j = 0; j < model.handles; ++j) {
    if (constraints_[j].state == HandleConstraint::Fixed) fixed_.push_back(j);
    else unknown_.push_back(j);
    if (constraints_[j].state == HandleConstraint::Position) position_.push_back(j);
  }
  if (inertia_.size() && (inertia_.rows() != 4 * model.handles || inertia_.cols() != 4 * model.handles))
    throw Error("FAST: the inertia term is " + std::to_string(inertia_.rows()) + " x " + std::to_string(inertia_.cols()) +
                " for " + std::to_string(model.handles) + " handles");
  for (const FastJoint& jt : joints)
    if (jt.child < 0 || jt.child >= model.handles || jt.parent < 0 || jt.parent >= model.handles || jt.child == jt.parent)
      throw Error("FAST: a joint between handles " + std::to_string(jt.child) + " and " + std::to_string(jt.parent) +
                  " of " + std::to_string(model.handles));
  joints.erase(std::remove_if(joints.begin(), joints.end(),
                              [&](const FastJoint& jt) { return constraints_[jt.child].state == HandleConstraint::Fixed; }),
               joints.end());
  unknown_rows_ = block_indices(unknown_);
  const std::vector<int>& u = unknown_rows_;
  const std::vector<int> f = block_indices(fixed_);
  const int nu = static_cast<int>(u.size()), c = static_cast<int>(position_.size());
  const int k = c + static_cast<int>(joints.size());  // constraint rows: positions, then joints
  Kt_u_ = model.Kt(Eigen::all, u);
  Kt_f_ = model.Kt(Eigen::all, f);
  T_fixed_ = Eigen::MatrixXd::Zero(f.size(), 3);
  s_fixed_ = Eigen::MatrixXd::Zero(model.Kt.rows(), 3);
  phi_ = Eigen::MatrixXd::Zero(nu, 3);
  P_ = Eigen::MatrixXd::Zero(c, 3);
  if (inertia_.size()) B_ = Eigen::MatrixXd::Zero(4 * model.handles, 3);
  X_.resize(nu, 3);
  S_.resize(model.Kt.rows(), 3);
  Rt_.resize(model.Kt.rows(), 3);
  if (nu == 0) return;
  // M_eq over every handle's block (Eq. 7.15): [anchor^T 1] per position constraint, then per joint
  // [point^T 1] on the child's block and its negative on the parent's.
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(k, 4 * model.handles);
  auto put = [&](int row, int handle, const Eigen::Vector3d& x, double sign) {
    C.block<1, 3>(row, 4 * handle) += sign * x.transpose();
    C(row, 4 * handle + 3) += sign;
  };
  for (int p = 0; p < c; ++p) put(p, position_[p], constraints_[position_[p]].anchor, 1.0);
  for (size_t j = 0; j < joints.size(); ++j) {
    put(c + static_cast<int>(j), joints[j].child, joints[j].point, 1.0);
    put(c + static_cast<int>(j), joints[j].parent, joints[j].point, -1.0);
  }
  const Eigen::MatrixXd C_u = C(Eigen::all, u), C_f = C(Eigen::all, f);
  // Eq. 7.19 on the unknown blocks: [Lt_uu C_u^T; C_u 0]; fixed blocks move to the right-hand side.
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(nu + k, nu + k);
  // Lt plus the momentum term (7.7.2): the only place dynamics touches the switch.
  const Eigen::MatrixXd Q = inertia_.size() ? Eigen::MatrixXd(model.Lt + inertia_) : model.Lt;
  A.topLeftCorner(nu, nu) = Q(u, u);
  A.topRightCorner(nu, k) = C_u.transpose();
  A.bottomLeftCorner(k, nu) = C_u;
  // A pseudo-inverse: free handles may leave directions the energy does not see (a global
  // translation with no position constraint); those get the least-norm solution.
  const Eigen::MatrixXd Pi = Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(A).pseudoInverse();
  gamma_ = Pi.topLeftCorner(nu, nu) * Kt_u_.transpose();
  pi_fixed_ = -Pi.topLeftCorner(nu, nu) * Q(u, f) - Pi.topRightCorner(nu, k) * C_f;
  if (inertia_.size()) pi_linear_ = Pi.topLeftCorner(nu, nu);
  pi_targets_ = Pi.topRightCorner(nu, k).leftCols(c);
  // An iteration in rotation space costs (3r)^2 against 2 (3r)(4u) multiply-adds per column.
  rotation_space_ = model.Kt.rows() < 2 * nu;
  if (rotation_space_) kt_gamma_ = Kt_u_ * gamma_;
  switch_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void FastSolver::set_targets(const Pose& pose, const std::vector<Eigen::Vector3d>& targets) {
  read_targets(pose, targets);
  update_phi();
}

void FastSolver::set_targets(const Pose& pose, const std::vector<Eigen::Vector3d>& targets, const Eigen::MatrixXd& B) {
  check_linear_term(B);
  read_targets(pose, targets);
  B_ = B;
  update_phi();
}

void FastSolver::read_targets(const Pose& pose, const std::vector<Eigen::Vector3d>& targets) {
  if (pose.size() != model_->handles) throw Error("FAST: the pose has the wrong number of handles");
  for (size_t q = 0; q < fixed_.size(); ++q) {
    T_fixed_.block<3, 3>(4 * q, 0) = pose.transforms[fixed_[q]].linear().transpose();
    T_fixed_.row(4 * q + 3) = pose.transforms[fixed_[q]].translation().transpose();
  }
  for (size_t p = 0; p < position_.size(); ++p) {
    if (position_[p] >= static_cast<int>(targets.size()))
      throw Error("FAST: no target for position-constrained handle " + std::to_string(position_[p]));
    P_.row(p) = targets[position_[p]].transpose();
  }
  s_fixed_.noalias() = Kt_f_ * T_fixed_;
}

void FastSolver::check_linear_term(const Eigen::MatrixXd& B) const {
  if (!inertia_.size()) throw Error("FAST: a linear term needs a solver built with an inertia term");
  if (B.rows() != 4 * model_->handles || B.cols() != 3)
    throw Error("FAST: the linear term is " + std::to_string(B.rows()) + " x " + std::to_string(B.cols()) + " for " +
                std::to_string(model_->handles) + " handles");
}

void FastSolver::set_linear_term(const Eigen::MatrixXd& B) {
  check_linear_term(B);
  B_ = B;
  update_phi();
}

void FastSolver::update_phi() {
  if (!unknown_.empty()) {
    phi_ = pi_fixed_ * T_fixed_ + pi_targets_ * P_;
    if (inertia_.size()) phi_.noalias() += pi_linear_ * B_(unknown_rows_, Eigen::all);
  }
  if (rotation_space_) s_const_ = Kt_u_ * phi_ + s_fixed_;
}

double FastSolver::dynamic_terms(const Eigen::MatrixXd& T) const {
  if (!inertia_.size()) return 0;
  return 0.5 * (T.transpose() * inertia_ * T).trace() - B_.cwiseProduct(T).sum();
}

void FastSolver::read_unknown_blocks(const Pose& pose) const {
  for (size_t q = 0; q < unknown_.size(); ++q)
    X_.block<4, 3>(4 * q, 0) = pose.transforms[unknown_[q]].matrix().topRows<3>().transpose();
}

void FastSolver::write_unknown_blocks(Pose& pose) const {
  for (size_t q = 0; q < unknown_.size(); ++q)
    pose.transforms[unknown_[q]].matrix().topRows<3>() = X_.block<4, 3>(4 * q, 0).transpose();
}

double FastSolver::iterate(Pose& pose, bool with_energy) const {
  if (pose.size() != model_->handles) throw Error("FAST: the pose has the wrong number of handles");
  if (unknown_.empty()) return with_energy ? fast_energy(*model_, pose) + dynamic_terms(pose_matrix(pose)) : 0.0;
  read_unknown_blocks(pose);
  S_.noalias() = Kt_u_ * X_;
  S_ += s_fixed_;
  local_step();
  global_step(pose);
  if (!with_energy) return std::numeric_limits<double>::quiet_NaN();
  const Eigen::MatrixXd T = pose_matrix(pose);
  return energy_of(*model_, T, Rt_) + dynamic_terms(T);
}

void FastSolver::iterate(Pose& pose, int count) const {
  if (!rotation_space_ || count < 2) {
    for (int i = 0; i < count; ++i) iterate(pose, false);
    return;
  }
  if (pose.size() != model_->handles) throw Error("FAST: the pose has the wrong number of handles");
  read_unknown_blocks(pose);
  S_.noalias() = Kt_u_ * X_;
  S_ += s_fixed_;
  for (int i = 0; i + 1 < count; ++i) {
    local_step();
    S_.noalias() = kt_gamma_ * Rt_;
    S_ += s_const_;
  }
  local_step();
  global_step(pose);
}

void FastSolver::global_step(Pose& pose) const {
  X_.noalias() = gamma_ * Rt_;
  X_ += phi_;
  write_unknown_blocks(pose);
}

void FastSolver::local_step() const {
  for (int k = 0; 3 * k < S_.rows(); ++k) Rt_.block<3, 3>(3 * k, 0) = best_rotation(S_.block<3, 3>(3 * k, 0)).transpose();
}

}  // namespace dfm
