#pragma once
// Checked reading of a scene file (private to scene_file.cpp): typed access to its JSON, where every
// problem throws dfm::Error naming the file and the field ("'rig.points[2].name' is not a string"), and
// the arrays of its binary sidecar, checked against the sidecar's size and checksum.
#include <string>
#include <utility>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "core/rig/pose_params.h"
#include "core/rig/rig.h"

namespace dfm {

// The sidecar's checksum as the scene records it ("fnv1a64"): FNV-1a 64 in 16 hex digits.
std::string sidecar_checksum(const std::string& bytes);

class SceneReader {
 public:
  using json = nlohmann::json;
  explicit SceneReader(std::string json_path) : path_(std::move(json_path)) {}

  [[noreturn]] void fail(const std::string& what) const;

  // ctx names the value in errors. field: obj[key], which must exist.
  const json& field(const json& obj, const char* key, const std::string& ctx) const;
  double number(const json& j, const std::string& ctx) const;  // finite
  long long integer(const json& j, const std::string& ctx, long long lo, long long hi) const;  // in [lo, hi]
  std::string string(const json& j, const std::string& ctx) const;
  bool boolean(const json& j, const std::string& ctx) const;
  const json& array(const json& j, const std::string& ctx, long long size = -1) const;  // size < 0: any
  Eigen::Vector3d vec3(const json& j, const std::string& ctx) const;
  Eigen::Quaterniond quat(const json& j, const std::string& ctx) const;  // w, x, y, z; not zero
  Eigen::Affine3d affine(const json& j, const std::string& ctx) const;   // 3 x 4, row-major

  // Reads the sidecar root["sidecar"] names, beside the JSON in json_dir, and checks its size and checksum.
  void load_sidecar(const json& root, const std::string& json_dir);
  // A sidecar array ({type, offset, rows, cols}): checks type, shape and bounds; cols < 0 accepts any
  // column count.
  Eigen::MatrixXd f64(const json& ref, const std::string& ctx, long long cols = -1) const;
  Eigen::MatrixXi i32(const json& ref, const std::string& ctx, long long cols = -1) const;
  // Every entry of M in [0, n).
  void check_indices(const Eigen::MatrixXi& M, long long n, const std::string& ctx) const;

  // Pose parameters sized to rig; solved transforms may name the rig's handles and `additional` more
  // (the additional handles, core/rig/additional_handles.h).
  PoseParams params(const json& j, const Rig& rig, const std::string& ctx, long long additional = 0) const;

 private:
  template <class Scalar>
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> matrix(const json& ref, const std::string& ctx,
                                                               long long cols) const;

  std::string path_, blob_path_;
  std::string blob_;
};

}  // namespace dfm
