#include "core/scene/scene_reader.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <type_traits>

#include "core/util/error.h"
#include "core/util/hash.h"

namespace dfm {

using json = nlohmann::json;

namespace {

std::string hex64(std::uint64_t v) {
  char buf[19];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

}  // namespace

std::string sidecar_checksum(const std::string& bytes) { return hex64(fnv1a(bytes)); }

void SceneReader::fail(const std::string& what) const { throw file_error(path_, 0, what); }

const json& SceneReader::field(const json& obj, const char* key, const std::string& ctx) const {
  if (!obj.is_object()) fail("'" + ctx + "' is not an object");
  auto it = obj.find(key);
  if (it == obj.end()) fail("missing field '" + ctx + "." + key + "'");
  return *it;
}

double SceneReader::number(const json& j, const std::string& ctx) const {
  if (!j.is_number()) fail("'" + ctx + "' is not a number");
  const double x = j.get<double>();
  if (!std::isfinite(x)) fail("'" + ctx + "' is not finite");
  return x;
}

long long SceneReader::integer(const json& j, const std::string& ctx, long long lo, long long hi) const {
  if (!j.is_number_integer()) fail("'" + ctx + "' is not an integer");
  const long long x = j.get<long long>();
  if (x < lo || x > hi) fail("'" + ctx + "' = " + std::to_string(x) + " is out of range");
  return x;
}

std::string SceneReader::string(const json& j, const std::string& ctx) const {
  if (!j.is_string()) fail("'" + ctx + "' is not a string");
  return j.get<std::string>();
}

bool SceneReader::boolean(const json& j, const std::string& ctx) const {
  if (!j.is_boolean()) fail("'" + ctx + "' is not true/false");
  return j.get<bool>();
}

const json& SceneReader::array(const json& j, const std::string& ctx, long long size) const {
  if (!j.is_array()) fail("'" + ctx + "' is not an array");
  if (size >= 0 && static_cast<long long>(j.size()) != size)
    fail("'" + ctx + "' has " + std::to_string(j.size()) + " entries, expected " + std::to_string(size));
  return j;
}

Eigen::Vector3d SceneReader::vec3(const json& j, const std::string& ctx) const {
  array(j, ctx, 3);
  return {number(j[0], ctx), number(j[1], ctx), number(j[2], ctx)};
}

Eigen::Quaterniond SceneReader::quat(const json& j, const std::string& ctx) const {
  array(j, ctx, 4);
  Eigen::Quaterniond q(number(j[0], ctx), number(j[1], ctx), number(j[2], ctx), number(j[3], ctx));
  if (q.norm() < 1e-12) fail("'" + ctx + "' is a zero quaternion");
  return q;
}

Eigen::Affine3d SceneReader::affine(const json& j, const std::string& ctx) const {
  array(j, ctx, 12);
  Eigen::Affine3d T = Eigen::Affine3d::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) T.matrix()(r, c) = number(j[r * 4 + c], ctx);
  return T;
}

void SceneReader::load_sidecar(const json& root, const std::string& json_dir) {
  const json& sc = field(root, "sidecar", "scene");
  const std::string name = string(field(sc, "file", "sidecar"), "sidecar.file");
  if (name.empty() || name.find('/') != std::string::npos || name.find('\\') != std::string::npos ||
      name == "." || name == "..")
    fail("sidecar file name '" + name + "' must be a plain file name beside the scene");
  const long long size = integer(field(sc, "bytes", "sidecar"), "sidecar.bytes", 0, (1ll << 40));
  const std::string sum = string(field(sc, "fnv1a64", "sidecar"), "sidecar.fnv1a64");
  blob_path_ = (std::filesystem::path(json_dir) / name).string();
  std::error_code sec;
  const auto st = std::filesystem::status(blob_path_, sec);
  if (std::filesystem::exists(st) && !std::filesystem::is_regular_file(st))  // a folder or a pipe would hang or fail obscurely
    throw file_error(blob_path_, 0, "sidecar is not a regular file");
  std::ifstream in(blob_path_, std::ios::binary);
  if (!in) fail("cannot open its sidecar '" + blob_path_ + "'");
  std::error_code ec;
  const auto actual = std::filesystem::file_size(blob_path_, ec);
  if (ec) throw file_error(blob_path_, 0, "cannot read size: " + ec.message());
  if (static_cast<long long>(actual) != size)
    throw file_error(blob_path_, 0, "sidecar is " + std::to_string(actual) + " bytes, the scene expects " +
                                        std::to_string(size) + " (truncated or from another save)");
  blob_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (static_cast<long long>(blob_.size()) != size) throw file_error(blob_path_, 0, "short read");
  if (sidecar_checksum(blob_) != sum)
    throw file_error(blob_path_, 0, "checksum mismatch (sidecar corrupt or from another save)");
}

template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> SceneReader::matrix(const json& ref, const std::string& ctx,
                                                                          long long cols) const {
  const bool f64 = std::is_same<Scalar, double>::value;
  const std::string type = string(field(ref, "type", ctx), ctx + ".type");
  if (type != (f64 ? "f64" : "i32")) fail("'" + ctx + "' has type '" + type + "', expected " + (f64 ? "f64" : "i32"));
  const long long off = integer(field(ref, "offset", ctx), ctx + ".offset", 0, (1ll << 40));
  const long long rows = integer(field(ref, "rows", ctx), ctx + ".rows", 0, (1ll << 31) - 1);
  const long long nc = integer(field(ref, "cols", ctx), ctx + ".cols", 0, (1ll << 31) - 1);
  // An empty array may be 0 x 0 (never set) or 0 x cols; any other shape is wrong.
  if (cols >= 0 && nc != cols && (rows > 0 || nc != 0))
    fail("'" + ctx + "' has " + std::to_string(nc) + " columns, expected " + std::to_string(cols));
  const long long n = rows * nc;  // < 2^62
  if (off % static_cast<long long>(sizeof(Scalar)) != 0) fail("'" + ctx + "' offset is misaligned");
  if (n > 0 && (off > static_cast<long long>(blob_.size()) ||
                n > (static_cast<long long>(blob_.size()) - off) / static_cast<long long>(sizeof(Scalar))))
    throw file_error(blob_path_, 0, "array '" + ctx + "' (" + std::to_string(rows) + " x " + std::to_string(nc) +
                                        " at byte " + std::to_string(off) + ") runs past the end of the sidecar");
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> M(rows, nc);
  const char* p = blob_.data() + off;
  for (long long r = 0; r < rows; ++r)
    for (long long c = 0; c < nc; ++c, p += sizeof(Scalar)) {
      Scalar x;
      std::memcpy(&x, p, sizeof x);
      if constexpr (std::is_same<Scalar, double>::value)
        if (!std::isfinite(x)) throw file_error(blob_path_, 0, "array '" + ctx + "' holds NaN or infinity");
      M(r, c) = x;
    }
  return M;
}

Eigen::MatrixXd SceneReader::f64(const json& ref, const std::string& ctx, long long cols) const {
  return matrix<double>(ref, ctx, cols);
}

Eigen::MatrixXi SceneReader::i32(const json& ref, const std::string& ctx, long long cols) const {
  return matrix<int>(ref, ctx, cols);
}

void SceneReader::check_indices(const Eigen::MatrixXi& M, long long n, const std::string& ctx) const {
  if (M.size() > 0 && (M.minCoeff() < 0 || M.maxCoeff() >= n))
    fail("'" + ctx + "' has an index out of range (must be in [0, " + std::to_string(n) + "))");
}

PoseParams SceneReader::params(const json& j, const Rig& rig, const std::string& ctx, long long additional) const {
  PoseParams p;
  const long long nb = rig.skeleton.num_bones(), np = num_point_handles(rig), nc = num_cage_vertices(rig),
                  nr = static_cast<long long>(rig.regions.size());
  auto list = [&](const char* key, long long n, auto conv, auto& out) {
    const std::string c = ctx + "." + key;
    const json& a = array(field(j, key, ctx), c, n);
    for (size_t i = 0; i < a.size(); ++i) out.push_back(conv(a[i], c + "[" + std::to_string(i) + "]"));
  };
  list("bone_rotation", nb, [&](const json& x, const std::string& c) { return quat(x, c); }, p.bone_rotation);
  list("bone_translation", nb, [&](const json& x, const std::string& c) { return vec3(x, c); }, p.bone_translation);
  list("bone_twist_stretch", nb,
       [&](const json& x, const std::string& c) {
         array(x, c);  // twist, stretch and (since the twist at the first joint) that twist
         if (x.size() != 2 && x.size() != 3) fail("'" + c + "' has " + std::to_string(x.size()) + " entries, expected 2 or 3");
         return BoneTwistStretch{number(x[0], c), number(x[1], c), x.size() == 3 ? number(x[2], c) : 0.0};
       },
       p.bone_twist_stretch);
  list("point_translation", np, [&](const json& x, const std::string& c) { return vec3(x, c); }, p.point_translation);
  list("point_rotation", np, [&](const json& x, const std::string& c) { return quat(x, c); }, p.point_rotation);
  list("cage_translation", nc, [&](const json& x, const std::string& c) { return vec3(x, c); }, p.cage_translation);
  list("region_transform", nr, [&](const json& x, const std::string& c) { return affine(x, c); }, p.region_transform);
  if (j.contains("solved")) {  // optional: scenes saved before FAST posing have none
    const std::string c = ctx + ".solved";
    const json& a = array(j["solved"], c, -1);
    const long long nh = num_handles(rig) + additional;
    for (size_t i = 0; i < a.size(); ++i) {
      const std::string ci = c + "[" + std::to_string(i) + "]";
      const double h = number(field(a[i], "handle", ci), ci + ".handle");
      if (!(h >= 0 && h < nh) || h != std::floor(h))
        fail("'" + ci + ".handle' must be a handle index in [0, " + std::to_string(nh) + ")");
      p.solved[static_cast<int>(h)] = affine(field(a[i], "transform", ci), ci + ".transform");
    }
  }
  return p;
}

}  // namespace dfm
