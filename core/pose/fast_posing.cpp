#include "core/pose/fast_posing.h"

#include <chrono>
#include <string>

#include "core/pose/fast_rig.h"
#include "core/rig/additional_handles.h"
#include "core/util/error.h"

namespace dfm {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

bool same_constraints(const std::vector<FastConstraint>& a, const std::vector<FastConstraint>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].state != b[i].state || a[i].anchor != b[i].anchor) return false;
  return true;
}

// r^T X c with uneven r, c: differs for new contents at a reused address (a rebind), where a plain
// sum would not (weights always sum to #V).
double fingerprint(const Eigen::MatrixXd& X) {
  Eigen::VectorXd r(X.rows()), c(X.cols());
  for (Eigen::Index i = 0; i < X.rows(); ++i) r(i) = 1.0 + static_cast<double>(i % 97) / 97.0;
  for (Eigen::Index j = 0; j < X.cols(); ++j) c(j) = 1.0 + 0.37 * static_cast<double>(j);
  return r.dot(X * c);
}

}  // namespace

std::vector<HandleConstraint> default_constraint_states(const Rig& rig) {
  std::vector<HandleConstraint> s;
  for (const FastConstraint& c : default_fast_constraints(rig, {})) s.push_back(c.state);
  return s;
}

bool FastPosing::Signature::operator==(const Signature& o) const {
  for (int i = 0; i < 3; ++i)
    if (data[i] != o.data[i] || size[i] != o.size[i] || fingerprint[i] != o.fingerprint[i]) return false;
  return true;
}

void FastPosing::invalidate() {
  model_.reset();
  solver_.reset();
  constraints_.clear();
  joints_.clear();
}

FastSolveReport FastPosing::solve(const Rig& rig, const Eigen::MatrixXd& V, const Eigen::MatrixXi& elements,
                                  const Eigen::MatrixXd& W, const std::vector<HandleConstraint>& states,
                                  int iterations, PoseParams& params) {
  const int nh = num_handles(rig);
  if (static_cast<int>(states.size()) != nh || W.cols() < nh)
    throw Error("FAST posing: " + std::to_string(states.size()) + " handle states and " + std::to_string(W.cols()) +
                " weight columns for a rig of " + std::to_string(nh) + " handles");
  const int na = static_cast<int>(W.cols()) - nh;  // additional handles (additional_handles.h): free
  FastSolveReport report;
  Signature sig;
  sig.data[0] = V.data(), sig.data[1] = elements.data(), sig.data[2] = W.data();
  sig.size[0] = V.size(), sig.size[1] = elements.size(), sig.size[2] = W.size();
  sig.fingerprint[0] = fingerprint(V), sig.fingerprint[1] = fingerprint(elements.cast<double>()), sig.fingerprint[2] = fingerprint(W);
  if (!model_ || !(sig == model_signature_)) {
    const auto t0 = std::chrono::steady_clock::now();
    model_ = std::make_unique<FastModel>(fast_model(V, elements, W));
    model_signature_ = sig;
    solver_.reset();
    report.precomputed = true;
    report.precompute_seconds = seconds_since(t0);
  }
  std::vector<FastConstraint> constraints(nh + na);
  for (int h = 0; h < nh; ++h) constraints[h] = {states[h], handle_anchor(rig, h)};
  for (int h = nh; h < nh + na; ++h) constraints[h] = {HandleConstraint::Free, Eigen::Vector3d::Zero()};
  std::vector<FastJoint> joints = fast_joints(rig);
  if (!solver_ || !same_constraints(constraints, constraints_) || joints != joints_) {
    solver_ = std::make_unique<FastSolver>(*model_, constraints, joints);
    constraints_ = constraints;
    joints_ = std::move(joints);
    report.switched = true;
    report.switch_seconds = solver_->switch_seconds();
  }
  PoseParams base = params;
  base.solved.clear();
  Pose given = evaluate_pose(rig, base);
  given.transforms.resize(nh + na, zero_transform());  // set_targets reads one per handle
  Pose pose = skin_pose(rig, params, na);  // the warm start: last solved transforms where present
  for (int h = 0; h < nh; ++h)
    if (states[h] == HandleConstraint::Fixed) pose.transforms[h] = given.transforms[h];
  // Targets where the parameters put each anchor: a bone dragged as IK keeps its target in its
  // translation, which the connected pose projects out.
  Pose anchors = evaluate_handle_parameters(rig, base);
  anchors.transforms.resize(nh + na, zero_transform());
  solver_->set_targets(given, fast_targets(constraints, anchors));
  const auto t0 = std::chrono::steady_clock::now();
  solver_->iterate(pose, iterations);
  report.iterate_seconds = seconds_since(t0);
  report.iterations = iterations;
  report.clusters = model_->clusters;
  report.energy = fast_energy(*model_, pose);
  params.solved.clear();
  for (int h = 0; h < nh + na; ++h)
    if (h >= nh || states[h] != HandleConstraint::Fixed) params.solved[h] = pose.transforms[h];
  return report;
}

}  // namespace dfm
