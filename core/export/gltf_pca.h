#pragma once
// A compressed animation (core/anim/pca_animation.h) as glTF 2.0 morph targets, the way Alexa 2003,
// 7.3 proposes for graphics standards: the base shapes are the morph targets (a CoordinateMorpher),
// the coefficients the animated morph weights (a VectorInterpolator), the rigid motion a node transform.
//
// Layout: scene 0 holds one node "<name>" with mesh 0 and no skin.
//   mesh 0:   POSITION = the base b = mean + sum_j lo_j B_j, NORMAL = b's unit normals; target j
//             (j < k) = s_j B_j with s_j = hi_j - lo_j, lo_j / hi_j the smallest / largest coefficient
//             of base j over the frames. Weights w_ij = (c_ij - lo_j) / s_j then lie in [0, 1], so
//             b + sum_j w_ij target_j = mean + sum_j c_ij B_j, and viewers that clamp shape-key
//             sliders to [0, 1] (Blender's importer widens them from the first key only) play it.
//             Each target also has NORMAL deltas D_j: the least-squares fit over the frames of
//             N0 + sum_j w_ij D_j to the unit normals of the reconstructed frames (viewers renormalize),
//             7.3.3's "interpolate linearly and normalize". mesh.weights = frame 0's weights.
//   animation 0: at time t_i (LINEAR): "weights" = w_i, "rotation" = R_i, "translation" = t_i, so
//             glTF's T * R * (b + sum w target) is pca_frame(i). Node TRS default = frame 0's.
//   mesh.extras.targetNames = "base 1" ... "base k" (Blender names the shape keys from it).
#include <string>

#include "core/anim/pca_animation.h"

namespace dfm {

struct PcaGltfOptions {
  std::string name = "animation";
  bool normals = true;  // NORMAL on the base and NORMAL deltas on the targets (needs triangles)
};

struct PcaGltfReport {
  int vertices = 0, triangles = 0, frames = 0, morph_targets = 0;
  // Normals at the frames: angle between the renormalized blended normal and the true unit normal of
  // the reconstructed frame, over every vertex of every frame (degrees; 0 without normals).
  double normal_mean_angle_deg = 0.0, normal_max_angle_deg = 0.0;
  // The same for fixed normals (N0 at every frame), the option 7.3.3 calls surprisingly good.
  double fixed_normal_mean_angle_deg = 0.0;
};

// Writes `path` (.glb, or .gltf + <stem>.bin) atomically. Throws dfm::Error naming the problem for an
// animation without triangles, inconsistent sizes, or a bad path.
PcaGltfReport export_pca_gltf(const std::string& path, const PcaAnimation& a, const PcaGltfOptions& options = {});

}  // namespace dfm
