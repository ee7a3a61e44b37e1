#include "core/export/gltf_verify.h"

#include <cmath>

#include "core/export/gltf_import.h"
#include "core/skin/lbs.h"
#include "core/util/error.h"

namespace dfm {

GltfVerifyResult verify_gltf_export(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXd& W,
                                    const Pose& current, const std::vector<double>& key_times,
                                    const std::vector<Pose>& key_poses) {
  if (key_times.size() != key_poses.size()) throw Error("verify: key times and poses differ in count");
  GltfDocument doc = read_gltf(path);
  if (doc.skinned_node < 0) throw file_error(path, 0, "no skinned mesh to verify");
  if (doc.skinned.V.rows() != V.rows()) throw file_error(path, 0, "vertex count differs from the exported surface");
  GltfVerifyResult r;
  r.bbox_diagonal = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  // glTF positions are single precision: skin the file's own rest positions, compare with ours.
  for (size_t k = 0; k < key_times.size(); ++k) {
    const Eigen::MatrixXd U = gltf_skinned_positions(doc, key_times[k]);
    const double e = (U - lbs(V, W, key_poses[k])).rowwise().norm().maxCoeff();
    r.key_errors.push_back(e);
    r.max_error = std::max(r.max_error, e);
  }
  doc.channels.clear();
  r.current_error = (gltf_skinned_positions(doc, 0.0) - lbs(V, W, current)).rowwise().norm().maxCoeff();
  r.max_error = std::max(r.max_error, r.current_error);
  return r;
}

}  // namespace dfm
