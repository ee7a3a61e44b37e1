#pragma once
// The whole bind: volume (TetGen or the given tets) -> FEM -> BBW -> weights on the user's vertices,
// with per-stage timings, progress and cancellation for the editor's worker thread.
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/bind/bbw.h"
#include "core/bind/bind_volume.h"
#include "core/mesh/mesh.h"
#include "core/rig/rig.h"

namespace dfm {

struct BindOptions {
  VolumeOptions volume;
  // The weight solve. bbw.shape_mask: per-tet rho of the bind volume (only with a tet-mesh input), or
  // empty. bbw.progress and bbw.qp.cancel are the bind's own (set from progress and cancel below).
  BbwOptions bbw;
  // Per user-vertex rho (e.g. the editor's painted mask, scaled), or empty; used when bbw.shape_mask is
  // empty: mapped onto the volume once it is built (tet_mask_from_user_vertices).
  Eigen::VectorXd vertex_mask;
  // (stage, fraction of the whole bind in [0, 1]); stages: "meshing", "assembly", "factorization",
  // "solve", "monotone" (BbwOptions::monotone), "mapping", "endpoints", "additional"
  // (additional_weights), "done". May be empty.
  std::function<void(const std::string& stage, double fraction)> progress;
  const std::atomic<bool>* cancel = nullptr;  // throws dfm::Cancelled soon after it is set
  // With bones: also the STBS endpoint weights (endpoint_weights.h), a second solve over the joints.
  bool endpoint_weights = true;
  // Additional weight functions (additional_weights.h, Jacobson 2013 7.3.3): bind_surface and
  // bind_tet_mesh then solve the weights a second time with this many more handles (0: none).
  int additional_weights = 0;
};

struct BindReport {
  double meshing_seconds = 0, assembly_seconds = 0, factorization_seconds = 0, solve_seconds = 0, total_seconds = 0;
  double endpoint_seconds = 0;  // the joint weights' solve (in total_seconds)
  double additional_seconds = 0;  // the additional weights' solve (in total_seconds)
  int tet_vertices = 0, tets = 0, handles = 0;
  BbwStats bbw;  // iterations, KKT residual, factor size
  // On the user's vertices:
  double min_weight = 0, max_weight = 0, max_row_sum_error = 0, zero_fraction = 0;
  std::vector<std::string> notes;
};

struct BindResult {
  Eigen::MatrixXd weights;  // #user vertices x #handles (rig.h order), rows sum to 1
  BindVolume volume;        // the tets the weights were solved on, with the constraints
  Eigen::MatrixXd tet_weights;  // #tet vertices x #handles
  // STBS endpoint weights on the user's vertices (#user vertices x #bones); empty without bones or
  // with BindOptions::endpoint_weights off (bind_on_volume: no rig, none).
  Eigen::MatrixXd endpoint_weights;
  // #user vertices x BindOptions::additional_weights (additional_weights.h), or empty.
  Eigen::MatrixXd additional_weights;
  BindReport report;
};

// Surface input: tetrahedralized conforming to the handles (build_bind_volume).
BindResult bind_surface(const TriMesh& surface, const Rig& rig, const BindOptions& opts = {});
// Tet-mesh input, used as it is (bind_volume_from_tets).
BindResult bind_tet_mesh(const TetMesh& tets, const Rig& rig, const BindOptions& opts = {});
// The weights stage alone, on a volume already built.
BindResult bind_on_volume(BindVolume volume, const BindOptions& opts = {});

// Per-vertex values on the user's vertices -> per-tet rho on `volume`: a tet vertex takes the largest
// value of the user vertices mapped onto it (to_user), a tet the mean of its four vertices.
Eigen::VectorXd tet_mask_from_user_vertices(const BindVolume& volume, const Eigen::VectorXd& vertex_values);

// Weight statistics used in the report (min, max, max |row sum - 1|, fraction of exact zeros).
void weight_statistics(const Eigen::MatrixXd& W, BindReport& report);

}  // namespace dfm
