#include "core/pose/fast_dynamics.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "core/skin/lbs.h"
#include "core/util/error.h"

namespace dfm {
namespace {

double dynamic_coefficient(const FastDynamicsOptions& o) {
  if (!(o.dt > 0)) throw Error("dynamics: the time step must be > 0, got " + std::to_string(o.dt));
  if (!(o.damping >= 0)) throw Error("dynamics: the damping must be >= 0, got " + std::to_string(o.damping));
  if (o.iterations < 1) throw Error("dynamics: at least one iteration per step");
  return (1 + o.damping * o.dt) / (o.dt * o.dt);
}

Eigen::VectorXd lumped_vertex_mass(const Eigen::MatrixXd& V, const Eigen::MatrixXi& E) {
  Eigen::VectorXd m = Eigen::VectorXd::Zero(V.rows());
  for (int e = 0; e < E.rows(); ++e) {
    double measure;
    if (E.cols() == 3) {
      const Eigen::Vector3d a = V.row(E(e, 0)), b = V.row(E(e, 1)), c = V.row(E(e, 2));
      measure = 0.5 * (b - a).cross(c - a).norm();
    } else if (E.cols() == 4) {
      const Eigen::Vector3d a = V.row(E(e, 0)), b = V.row(E(e, 1)), c = V.row(E(e, 2)), d = V.row(E(e, 3));
      measure = std::abs((b - a).dot((c - a).cross(d - a))) / 6;
    } else {
      throw Error("dynamics: elements must be triangles or tets, got " + std::to_string(E.cols()) + " columns");
    }
    for (int k = 0; k < E.cols(); ++k) m(E(e, k)) += measure / E.cols();
  }
  return m;
}

}  // namespace

FastMass fast_mass(const Eigen::MatrixXd& V, const Eigen::MatrixXi& elements, const Eigen::MatrixXd& W, double density,
                   const Eigen::VectorXd& mask) {
  if (W.rows() != V.rows())
    throw Error("dynamics: " + std::to_string(W.rows()) + " weight rows for " + std::to_string(V.rows()) + " vertices");
  if (!(density >= 0)) throw Error("dynamics: the density must be >= 0, got " + std::to_string(density));
  if (mask.size() && mask.size() != V.rows())
    throw Error("dynamics: a mass mask of " + std::to_string(mask.size()) + " values for " + std::to_string(V.rows()) +
                " vertices");
  if (mask.size() && !(mask.minCoeff() >= 0)) throw Error("dynamics: the mass mask has a negative or NaN value");
  // Per unit of the diagonal squared: the ARAP stiffness and the mass both scale as the measure, so
  // this keeps the frequencies (about 1 / (diagonal sqrt(density))) free of the model's units.
  const double diag = V.rows() ? (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm() : 1.0;
  Eigen::VectorXd m = (density / std::max(diag * diag, 1e-300)) * lumped_vertex_mass(V, elements);
  if (mask.size()) m = m.cwiseProduct(mask);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> L = sparse_lbs_matrix(V, W);
  FastMass out;
  const Eigen::SparseMatrix<double> MW = m.asDiagonal() * L;
  out.Mt = Eigen::MatrixXd(L.transpose() * MW);
  out.Mt = 0.5 * (out.Mt + out.Mt.transpose()).eval();
  out.moments = L.transpose() * m;
  out.total = m.sum();
  return out;
}

FastDynamics::FastDynamics(const FastModel& model, const FastMass& mass, std::vector<FastConstraint> constraints,
                           std::vector<FastJoint> joints, const FastDynamicsOptions& opts, const Pose& start)
    : mass_(&mass),
      opts_(opts),
      a_(dynamic_coefficient(opts)),
      solver_(model, std::move(constraints), std::move(joints), a_ * mass.Mt) {
  if (start.size() != model.handles) throw Error("dynamics: the start pose has the wrong number of handles");
  T0_ = pose_matrix(start);
  S0_ = Eigen::MatrixXd::Zero(T0_.rows(), 3);
}

void FastDynamics::step(Pose& pose, const std::vector<Eigen::Vector3d>& targets) {
  const double h = opts_.dt;
  // The inertial guess Y (damped velocity) is the warm start and, through a Mt Y, the right-hand side.
  Y_ = T0_ + (h / (1 + opts_.damping * h)) * S0_;
  B_.noalias() = a_ * (mass_->Mt * Y_);
  B_.noalias() += mass_->moments * opts_.gravity.transpose();
  solver_.set_targets(pose, targets, B_);
  const std::vector<FastConstraint>& cons = solver_.constraints();
  for (size_t q = 0; q < cons.size(); ++q)
    if (cons[q].state != HandleConstraint::Fixed) pose.transforms[q].matrix().topRows<3>() = Y_.block<4, 3>(4 * q, 0).transpose();
  solver_.iterate(pose, opts_.iterations);
  // S0 = (T - T0) / h and T0 = T, block by block (no temporaries).
  for (size_t q = 0; q < cons.size(); ++q) {
    const Eigen::Matrix<double, 4, 3> T = pose.transforms[q].matrix().topRows<3>().transpose();
    S0_.block<4, 3>(4 * q, 0) = (T - T0_.block<4, 3>(4 * q, 0)) / h;
    T0_.block<4, 3>(4 * q, 0) = T;
  }
}

double FastDynamics::kinetic_energy() const { return 0.5 * (S0_.transpose() * mass_->Mt * S0_).trace(); }

}  // namespace dfm
