#pragma once
// glTF 2.0 export of a bound, posed and keyed surface (.glb, or .gltf + .bin beside it).
//
// Layout of the written file:
//   scene 0: node "<name>" (mesh + skin, at the scene root as glTF asks of skinned meshes) and node
//            "rig" (identity), whose children are one joint node per handle in rig.h order:
//            bones nested as the skeleton (a bone's node sits at its first joint, under its parent
//            bone's node), point handles, cage vertices and regions directly under "rig".
//   skin 0:  joints = those nodes in handle order, so JOINTS_n values are weight-column indices;
//            inverse bind matrices = inverse of each joint node's rest (bind) global transform.
//   nodes' TRS = the current pose; animation 0 = one T/R/S channel per joint (LINEAR) over the keys.
//   residual morph targets (optional, GltfExportOptions::residual_morph_tolerance): when pruning to k
//            influences cannot reproduce LBS with all weights, mesh 0 gets one POSITION morph target
//            per key (plus one for the current pose unless it equals a key): the rest-space offset that
//            makes the pruned skin hit the full-weight LBS result (or GltfExportInput::exact, the
//            surface the document shows with its own method, twist and stretch) at that pose. glTF applies
//            targets before skinning; a "weights" channel on node 0 shows target i at key i (LINEAR in
//            between) and mesh.weights shows the current pose's target when no animation plays.
//   scene 1 (only with morph frames): node "<name>-baked", an unskinned mesh whose morph targets are
//            the baked frames, with a "weights" channel in animation 0 that shows frame i at its time.
// A handle transform T_h (pose.h, world space) becomes the joint's global transform T_h * G_h with
// G_h its rest global, so glTF's jointMatrix = global * inverseBind reproduces T_h exactly, up to
// float rounding and to the shear a TRS cannot hold (reported).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/mesh/mesh.h"
#include "core/rig/pose.h"
#include "core/rig/rig.h"

namespace dfm {

struct GltfKey {
  double time = 0.0;  // seconds, strictly increasing across keys
  Pose pose;          // one affine per handle
};

struct GltfExportInput {
  std::string name = "mesh";
  TriMesh surface;          // rest pose; normals computed when N is empty
  Eigen::MatrixXd weights;  // #surface.V x num_handles(rig)
  Rig rig;
  Pose current;                  // the nodes' default transforms; empty = rest
  std::vector<GltfKey> keys;     // empty = no skeletal animation
  std::vector<Eigen::MatrixXd> morph_frames;  // optional baked positions, each #V x 3
  std::vector<double> morph_times;            // one per frame (strictly increasing)
  // Optional: what the file should show at each key and then at the current pose (keys.size() + 1
  // matrices, #V x 3) when that is not LBS with all weights (a DQS or STBS document, twisted or
  // stretched bones); the pruning error and the residual morph targets are measured against it.
  std::vector<Eigen::MatrixXd> exact;
};

struct GltfExportOptions {
  int influences = 4;  // 4 (JOINTS_0/WEIGHTS_0) or 8 (adds JOINTS_1/WEIGHTS_1)
  // Refit the kept weights to the current pose and keys (prune.h refit_influences) instead of only
  // renormalizing them; lowers the pruning error at the keys.
  bool refit = true;
  // 0 = never. > 0: when the pruned skin misses LBS with all weights by more than this fraction of the
  // bbox diagonal at the current pose or a key, store the misses as residual morph targets of the skinned
  // mesh (see the layout above), so the file reproduces those poses up to float rounding. 1e-4 is what
  // the editor's File > Export and `deform export --residual-morphs` use.
  double residual_morph_tolerance = 0.0;
};

struct GltfExportReport {
  int vertices = 0, triangles = 0, joints = 0, influences = 0, keys = 0, morph_targets = 0;
  int refit_vertices = 0;  // vertices whose kept weights were refit
  int residual_targets = 0;  // residual morph targets written (0: the skin alone was within tolerance)
  double bbox_diagonal = 0.0;
  // Largest vertex distance between the pruned LBS skin and what the file should show (LBS with all
  // weights, or `exact`), over the current pose and every key; max_prune_error_key is the key (-1: the
  // current pose).
  double max_prune_error = 0.0;
  // This is the skin's own error: residual morph targets (if written) correct it at these poses.
  int max_prune_error_key = -1;
  // Largest relative TRS residual over every exported node transform (see trs.h); transforms
  // above 1e-6 are counted in sheared_transforms and their node names listed (first few) in notes.
  double max_shear = 0.0;
  int sheared_transforms = 0;
  std::vector<std::string> notes;
};

// Writes `path` (.glb, or .gltf with <stem>.bin beside it) atomically. Throws dfm::Error naming the
// problem for inconsistent input (weight rows/columns, pose sizes, key times) or an unwritable path.
GltfExportReport export_gltf(const std::string& path, const GltfExportInput& in,
                             const GltfExportOptions& options = {});

}  // namespace dfm
