#pragma once
// Skinning front door: pick a method, bind once (influences, endpoint weights), skin every pose.
// The GPU pass (render/skin_pass.h) takes the same SkinBinding and the same per-pose inputs, and its
// result must equal skin() within float precision.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/rig/pose.h"
#include "core/rig/rig.h"
#include "core/skin/dqs.h"
#include "core/skin/influences.h"
#include "core/skin/lbs.h"
#include "core/skin/stbs.h"
#include "core/skin/stbs_dqs.h"

namespace dfm {

// STBS: stretchable, twistable bones over LBS; STBS_DQS: over dual quaternions (stbs_dqs.h).
enum class SkinMethod { LBS, DQS, STBS, STBS_DQS };

const char* skin_method_name(SkinMethod m);  // "lbs", "dqs", "stbs", "stbs-dqs"
// STBS over either: the methods that read twist, stretch and endpoint weights.
inline bool is_stbs(SkinMethod m) { return m == SkinMethod::STBS || m == SkinMethod::STBS_DQS; }
// Accepts those names (any case); throws dfm::Error otherwise.
SkinMethod parse_skin_method(const std::string& name);

// Everything about a mesh that does not change with the pose.
struct SkinBinding {
  Eigen::MatrixXd V;          // #V x 3 rest positions
  Eigen::MatrixXd N;          // #V x 3 rest normals, or empty
  Influences influences;      // #V x k
  Eigen::MatrixXd endpoints;  // #V x k bone endpoint weights e (STBS), in influence order
  int num_handles = 0;        // the rig's handles, then the additional ones
  // The last `additional` handles are additional handles (core/rig/additional_handles.h): their
  // columns come last in every row and are skinned linearly whatever the method, the term
  // sum_e w_e (A_e p + t_e) added to the method's position (LBS and STBS also blend A_e into the
  // normal's matrix, as for any handle; the dual-quaternion methods leave the normal theirs).
  int additional = 0;
};

// k <= 0 keeps every weight unchanged (the exact reference); else the k largest, renormalized.
// W: #V x num_handles(rig). Throws dfm::Error on size mismatches.
// additional: #V x a additional weights (additional_handles.h), or empty: handles num_handles(rig) ..
// + a - 1, every column kept as it is (not pruned by k nor renormalized).
// bone_endpoints: STBS endpoint weights from the bind (#V x #bones, core/bind/endpoint_weights.h); empty:
// the projection onto each bone (bone_endpoint_weights).
SkinBinding make_skin_binding(const Eigen::MatrixXd& V, const Eigen::MatrixXd& N, const Eigen::MatrixXd& W,
                              const Rig& rig, int k, const Eigen::MatrixXd& bone_endpoints = {},
                              const Eigen::MatrixXd& additional = {});

struct SkinResult {
  Eigen::MatrixXd V;
  Eigen::MatrixXd N;  // empty when the binding has no normals
};

// stbs: per-handle twist/stretch records (stbs_handles); only STBS reads them, empty = none active;
// the additional handles need none (missing records are inactive).
SkinResult skin(SkinMethod method, const SkinBinding& binding, const Pose& pose,
                const std::vector<StbsHandle>& stbs = {});

// Largest vertex distance between skinning with `reference` (usually all weights) and `truncated`
// (k influences) on this pose: what the k-influence truncation costs.
double truncation_error(SkinMethod method, const SkinBinding& reference, const SkinBinding& truncated,
                        const Pose& pose, const std::vector<StbsHandle>& stbs = {});

// Per-vertex normals of a triangle mesh: area-weighted face normals, normalized.
Eigen::MatrixXd vertex_normals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

}  // namespace dfm
