#pragma once
// The acceptance check of an export: re-import the file with read_gltf, skin it with glTF's own
// semantics at every key, and compare with the project's LBS using all weights.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/rig/pose.h"

namespace dfm {

struct GltfVerifyResult {
  double bbox_diagonal = 0.0;
  std::vector<double> key_errors;  // per key: max vertex distance (absolute)
  double max_error = 0.0;          // over the keys and the current pose
  double current_error = 0.0;      // the nodes' default transforms (animation ignored) vs `current`
};

// V: rest surface, W: full weights, keys: (time, pose) as exported. Throws dfm::Error if the file's
// vertex count or key times do not match.
GltfVerifyResult verify_gltf_export(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXd& W,
                                    const Pose& current, const std::vector<double>& key_times,
                                    const std::vector<Pose>& key_poses);

}  // namespace dfm
