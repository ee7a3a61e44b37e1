#include "core/bind/bind.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/bind/additional_weights.h"
#include "core/bind/endpoint_weights.h"
#include "core/bind/rigid_pieces.h"
#include "core/util/error.h"

namespace dfm {
namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

void check_cancel(const BindOptions& opts) {
  if (opts.cancel && opts.cancel->load()) throw Cancelled();
}

// Meshing takes the first 30% of the progress bar when it runs, the weights the rest.
constexpr double kMeshingShare = 0.3;

// With bones, the weights' solve reports up to here and the joints' solve from here to 0.97 (they take
// about as long).
constexpr double kEndpointsStart = 0.6;

// The endpoint weights on the user's vertices (bind_endpoint_weights mapped by to_user), timed.
Eigen::MatrixXd user_endpoint_weights(const BindVolume& volume, const Rig& rig, const BindOptions& opts,
                                      const Eigen::VectorXd& shape_mask, BindReport& r) {
  const auto t0 = Clock::now();
  if (opts.progress) opts.progress("endpoints", kEndpointsStart);
  BbwOptions bo;
  bo.qp.cancel = opts.cancel;
  if (opts.progress)
    bo.progress = [&](const std::string&, double f) {
      opts.progress("endpoints", kEndpointsStart + (0.97 - kEndpointsStart) * f);
    };
  bo.shape_mask = shape_mask;
  const Eigen::MatrixXd E = (volume.to_user * bind_endpoint_weights(volume, rig, bo)).cwiseMax(0.0).cwiseMin(1.0);
  r.endpoint_seconds = since(t0);
  return E;
}

BindResult solve_weights(BindVolume volume, const BindOptions& opts, double progress_start, Clock::time_point t_all,
                         const Rig* rig = nullptr) {
  check_cancel(opts);
  BindResult res;
  BbwOptions bo = opts.bbw;
  if (bo.shape_mask.size() == 0 && opts.vertex_mask.size() && opts.vertex_mask.maxCoeff() > 0)
    bo.shape_mask = tet_mask_from_user_vertices(volume, opts.vertex_mask);
  bo.qp.cancel = opts.cancel;
  bo.progress = nullptr;
  const bool endpoints = rig && opts.endpoint_weights && rig->skeleton.num_bones() > 0;
  const double solved_at = endpoints ? kEndpointsStart : 0.97;
  if (opts.progress)
    bo.progress = [&](const std::string& stage, double f) {
      opts.progress(stage, progress_start + (solved_at - progress_start) * f);
    };
  if (opts.bbw.shape_mask.size() && opts.bbw.shape_mask.size() != volume.tets.num_tets())
    throw Error("shape mask has " + std::to_string(opts.bbw.shape_mask.size()) + " values for " +
                std::to_string(volume.tets.num_tets()) + " tets of the bind volume");
  res.tet_weights = bbw_weights(volume.tets.V, volume.tets.T, volume.b, volume.bc, bo, &res.report.bbw);
  apply_rigid_pieces(volume, res.tet_weights);
  if (opts.progress) opts.progress("mapping", solved_at);
  if (volume.to_user.cols() != res.tet_weights.rows())
    throw Error("bind volume: the map to the user's vertices has " + std::to_string(volume.to_user.cols()) +
                " columns for " + std::to_string(res.tet_weights.rows()) + " tet vertices");
  res.weights = volume.to_user * res.tet_weights;
  // The map interpolates (rows sum to 1); renormalize away its rounding.
  for (int i = 0; i < res.weights.rows(); ++i) {
    const double s = res.weights.row(i).sum();
    if (s > 0) res.weights.row(i) /= s;
  }
  BindReport& r = res.report;
  r.meshing_seconds = volume.meshing_seconds;
  r.assembly_seconds = r.bbw.assembly_seconds;
  r.factorization_seconds = r.bbw.factorization_seconds;
  r.solve_seconds = r.bbw.solve_seconds;
  r.tet_vertices = volume.tets.num_vertices();
  r.tets = volume.tets.num_tets();
  r.handles = static_cast<int>(volume.bc.cols());
  r.notes = volume.notes;
  if (r.bbw.rows_renormalized_from_zero)
    r.notes.push_back(std::to_string(r.bbw.rows_renormalized_from_zero) +
                      " tet vertices had every weight at 0; they took the bound-free solution");
  weight_statistics(res.weights, r);
  if (endpoints)
    res.endpoint_weights = user_endpoint_weights(volume, *rig, opts, bo.shape_mask, r);
  res.volume = std::move(volume);
  r.total_seconds = since(t_all);
  if (opts.progress) opts.progress("done", 1.0);
  return res;
}

// The additional weights (BindOptions::additional_weights) on the finished bind's volume.
BindResult with_additional(BindResult res, const BindOptions& opts, Clock::time_point t_all) {
  if (opts.additional_weights <= 0) return res;
  const auto t0 = Clock::now();
  if (opts.progress) opts.progress("additional", 0.99);
  BindOptions o = opts;
  o.progress = nullptr;  // a second solve: its own fractions would run the bar backwards
  o.additional_weights = 0;
  res.additional_weights = additional_weights(res, opts.additional_weights, o).weights;
  res.report.additional_seconds = since(t0);
  res.report.total_seconds = since(t_all);
  if (opts.progress) opts.progress("done", 1.0);
  return res;
}

}  // namespace

Eigen::VectorXd tet_mask_from_user_vertices(const BindVolume& vol, const Eigen::VectorXd& m) {
  const Eigen::SparseMatrix<double>& A = vol.to_user;  // #user x #tet vertices
  if (m.size() != A.rows())
    throw Error("shape mask has " + std::to_string(m.size()) + " values for " + std::to_string(A.rows()) +
                " mesh vertices");
  if (A.cols() != vol.tets.num_vertices())
    throw Error("bind volume: the map to the user's vertices has " + std::to_string(A.cols()) + " columns for " +
                std::to_string(vol.tets.num_vertices()) + " tet vertices");
  Eigen::VectorXd per_vertex = Eigen::VectorXd::Zero(A.cols());
  for (int k = 0; k < A.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it)
      if (it.value() > 0) per_vertex[it.col()] = std::max(per_vertex[it.col()], m[it.row()]);
  const Eigen::MatrixXi& T = vol.tets.T;
  Eigen::VectorXd rho(T.rows());
  for (int t = 0; t < T.rows(); ++t)
    rho[t] = 0.25 * (per_vertex[T(t, 0)] + per_vertex[T(t, 1)] + per_vertex[T(t, 2)] + per_vertex[T(t, 3)]);
  return rho;
}

void weight_statistics(const Eigen::MatrixXd& W, BindReport& r) {
  if (W.size() == 0) return;
  r.min_weight = W.minCoeff();
  r.max_weight = W.maxCoeff();
  r.max_row_sum_error = (W.rowwise().sum().array() - 1.0).abs().maxCoeff();
  r.zero_fraction = static_cast<double>((W.array() == 0.0).count()) / static_cast<double>(W.size());
}

BindResult bind_surface(const TriMesh& surface, const Rig& rig, const BindOptions& opts) {
  const auto t0 = Clock::now();
  if (opts.progress) opts.progress("meshing", 0.0);
  check_cancel(opts);
  BindVolume vol = build_bind_volume(surface, rig, opts.volume);
  if (vol.meshing_seconds == 0) vol.meshing_seconds = since(t0);
  return with_additional(solve_weights(std::move(vol), opts, kMeshingShare, t0, &rig), opts, t0);
}

BindResult bind_tet_mesh(const TetMesh& tets, const Rig& rig, const BindOptions& opts) {
  const auto t0 = Clock::now();
  if (opts.progress) opts.progress("meshing", 0.0);
  check_cancel(opts);
  BindVolume vol = bind_volume_from_tets(tets, rig);
  if (vol.meshing_seconds == 0) vol.meshing_seconds = since(t0);
  return with_additional(solve_weights(std::move(vol), opts, 0.05, t0, &rig), opts, t0);
}

BindResult bind_on_volume(BindVolume volume, const BindOptions& opts) {
  return solve_weights(std::move(volume), opts, 0.0, Clock::now());
}

}  // namespace dfm
