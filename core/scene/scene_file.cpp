#include "core/scene/scene_file.h"

#include <cmath>
#include <climits>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/anim/inbetween_method.h"
#include "core/rig/handle_constraint.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/util/hash.h"

namespace dfm {

using json = nlohmann::json;

namespace {

const char* kFormat = "deform-scene";

std::string hex64(std::uint64_t v) {
  char buf[19];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

bool ends_with(const std::string& s, const std::string& suf) {
  return s.size() >= suf.size() && s.compare(s.size() - suf.size(), suf.size(), suf) == 0;
}

// ---- writing ---------------------------------------------------------------------------------------

// The sidecar: arrays appended row-major, little-endian, each 8-byte aligned.
class BlobWriter {
 public:
  template <class Derived>
  json add(const Eigen::MatrixBase<Derived>& M) {
    using Scalar = typename Derived::Scalar;
    static_assert(std::is_same<Scalar, double>::value || std::is_same<Scalar, int>::value, "f64 or i32");
    while (bytes_.size() % 8) bytes_.push_back('\0');
    json ref = {{"offset", bytes_.size()},
                {"rows", M.rows()},
                {"cols", M.cols()},
                {"type", std::is_same<Scalar, double>::value ? "f64" : "i32"}};
    for (Eigen::Index r = 0; r < M.rows(); ++r)
      for (Eigen::Index c = 0; c < M.cols(); ++c) {
        const Scalar x = M(r, c);
        char b[sizeof(Scalar)];
        std::memcpy(b, &x, sizeof x);  // little-endian hosts only (x86-64 / arm64)
        bytes_.append(b, sizeof b);
      }
    return ref;
  }
  json add_indices(const std::vector<int>& v) {
    return add(Eigen::Map<const Eigen::VectorXi>(v.data(), static_cast<Eigen::Index>(v.size())));
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

json vec3(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }
json quat(const Eigen::Quaterniond& q) { return json::array({q.w(), q.x(), q.y(), q.z()}); }
json affine(const Eigen::Affine3d& T) {
  json a = json::array();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) a.push_back(T.matrix()(r, c));
  return a;
}

json params_json(const PoseParams& p) {
  json j;
  auto list = [](const auto& v, auto f) {
    json a = json::array();
    for (const auto& x : v) a.push_back(f(x));
    return a;
  };
  j["bone_rotation"] = list(p.bone_rotation, quat);
  j["bone_translation"] = list(p.bone_translation, vec3);
  j["bone_twist_stretch"] =
      list(p.bone_twist_stretch, [](const BoneTwistStretch& t) { return json::array({t.twist, t.stretch}); });
  j["point_translation"] = list(p.point_translation, vec3);
  j["point_rotation"] = list(p.point_rotation, quat);
  j["cage_translation"] = list(p.cage_translation, vec3);
  j["region_transform"] = list(p.region_transform, affine);
  if (!p.solved.empty()) {
    json solved = json::array();
    for (const auto& [h, T] : p.solved) solved.push_back({{"handle", h}, {"transform", affine(T)}});
    j["solved"] = solved;
  }
  return j;
}

const char* robust_name(VolumeOptions::Robust r) {
  switch (r) {
    case VolumeOptions::Robust::Auto: return "auto";
    case VolumeOptions::Robust::Never: return "never";
    case VolumeOptions::Robust::Always: return "always";
  }
  return "auto";
}

// ---- reading ---------------------------------------------------------------------------------------

class SceneReader {
 public:
  SceneReader(std::string json_path) : path_(std::move(json_path)) {}

  [[noreturn]] void fail(const std::string& what) const { throw file_error(path_, 0, what); }

  const json& field(const json& obj, const char* key, const std::string& ctx) const {
    if (!obj.is_object()) fail("'" + ctx + "' is not an object");
    auto it = obj.find(key);
    if (it == obj.end()) fail("missing field '" + ctx + "." + key + "'");
    return *it;
  }
  double number(const json& j, const std::string& ctx) const {
    if (!j.is_number()) fail("'" + ctx + "' is not a number");
    const double x = j.get<double>();
    if (!std::isfinite(x)) fail("'" + ctx + "' is not finite");
    return x;
  }
  long long integer(const json& j, const std::string& ctx, long long lo, long long hi) const {
    if (!j.is_number_integer()) fail("'" + ctx + "' is not an integer");
    const long long x = j.get<long long>();
    if (x < lo || x > hi) fail("'" + ctx + "' = " + std::to_string(x) + " is out of range");
    return x;
  }
  std::string string(const json& j, const std::string& ctx) const {
    if (!j.is_string()) fail("'" + ctx + "' is not a string");
    return j.get<std::string>();
  }
  bool boolean(const json& j, const std::string& ctx) const {
    if (!j.is_boolean()) fail("'" + ctx + "' is not true/false");
    return j.get<bool>();
  }
  const json& array(const json& j, const std::string& ctx, long long size = -1) const {
    if (!j.is_array()) fail("'" + ctx + "' is not an array");
    if (size >= 0 && static_cast<long long>(j.size()) != size)
      fail("'" + ctx + "' has " + std::to_string(j.size()) + " entries, expected " + std::to_string(size));
    return j;
  }
  Eigen::Vector3d vec3(const json& j, const std::string& ctx) const {
    array(j, ctx, 3);
    return {number(j[0], ctx), number(j[1], ctx), number(j[2], ctx)};
  }
  Eigen::Quaterniond quat(const json& j, const std::string& ctx) const {
    array(j, ctx, 4);
    Eigen::Quaterniond q(number(j[0], ctx), number(j[1], ctx), number(j[2], ctx), number(j[3], ctx));
    if (q.norm() < 1e-12) fail("'" + ctx + "' is a zero quaternion");
    return q;
  }
  Eigen::Affine3d affine(const json& j, const std::string& ctx) const {
    array(j, ctx, 12);
    Eigen::Affine3d T = Eigen::Affine3d::Identity();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) T.matrix()(r, c) = number(j[r * 4 + c], ctx);
    return T;
  }

  void load_sidecar(const json& root, const std::string& json_dir) {
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
    if (hex64(fnv1a(blob_)) != sum)
      throw file_error(blob_path_, 0, "checksum mismatch (sidecar corrupt or from another save)");
  }

  // A sidecar array: checks type, shape and bounds; `cols` < 0 accepts any column count.
  template <class Scalar>
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> matrix(const json& ref, const std::string& ctx, long long cols) const {
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
  Eigen::MatrixXd f64(const json& ref, const std::string& ctx, long long cols = -1) const {
    return matrix<double>(ref, ctx, cols);
  }
  Eigen::MatrixXi i32(const json& ref, const std::string& ctx, long long cols = -1) const {
    return matrix<int>(ref, ctx, cols);
  }
  void check_indices(const Eigen::MatrixXi& M, long long n, const std::string& ctx) const {
    if (M.size() > 0 && (M.minCoeff() < 0 || M.maxCoeff() >= n))
      fail("'" + ctx + "' has an index out of range (must be in [0, " + std::to_string(n) + "))");
  }

  PoseParams params(const json& j, const Rig& rig, const std::string& ctx) const {
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
           array(x, c, 2);
           return BoneTwistStretch{number(x[0], c), number(x[1], c)};
         },
         p.bone_twist_stretch);
    list("point_translation", np, [&](const json& x, const std::string& c) { return vec3(x, c); }, p.point_translation);
    list("point_rotation", np, [&](const json& x, const std::string& c) { return quat(x, c); }, p.point_rotation);
    list("cage_translation", nc, [&](const json& x, const std::string& c) { return vec3(x, c); }, p.cage_translation);
    list("region_transform", nr, [&](const json& x, const std::string& c) { return affine(x, c); }, p.region_transform);
    if (j.contains("solved")) {  // optional: scenes saved before FAST posing have none
      const std::string c = ctx + ".solved";
      const json& a = array(j["solved"], c, -1);
      const long long nh = num_handles(rig);
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

 private:
  std::string path_, blob_path_;
  std::string blob_;
};

// A mesh key's surface: shapes, indices and finite coordinates. Whether it can key a transition
// (closed, oriented, not self-intersecting) is checked where transitions are built, which names it.
void read_mesh_key(const SceneReader& R, const json& m, const std::string& ctx, SceneKey& k) {
  k.mesh_path = R.string(R.field(m, "source", ctx), ctx + ".source");
  k.mesh.V = R.f64(R.field(m, "V", ctx), ctx + ".V", 3);
  k.mesh.F = R.i32(R.field(m, "F", ctx), ctx + ".F", 3);
  if (k.mesh.V.rows() == 0 || k.mesh.F.rows() == 0) R.fail("'" + ctx + "' has no triangles");
  if (!k.mesh.V.allFinite()) R.fail("'" + ctx + ".V' has a coordinate that is not finite");
  R.check_indices(k.mesh.F, k.mesh.V.rows(), ctx + ".F");
}

}  // namespace

std::string scene_sidecar_path(const std::string& json_path) {
  if (ends_with(json_path, ".json")) return json_path.substr(0, json_path.size() - 5) + ".bin";
  return json_path + ".bin";
}

std::string autosave_path(const std::string& scene_path) {
  if (ends_with(scene_path, ".scene.json"))
    return scene_path.substr(0, scene_path.size() - 11) + ".autosave.scene.json";
  return scene_path + ".autosave.json";
}

void write_scene(const std::string& json_path, const SceneData& s) {
  BlobWriter blob;
  json j;
  j["format"] = kFormat;
  j["version"] = kSceneFormatVersion;

  j["surface"] = {{"source", s.surface_path}, {"V", blob.add(s.surface.V)}, {"F", blob.add(s.surface.F)},
                  {"N", blob.add(s.surface.N)}};
  j["tets"] = {{"V", blob.add(s.tets.V)}, {"T", blob.add(s.tets.T)}, {"F", blob.add(s.tets.F)},
               {"surface_to_tet", blob.add(s.surface_to_tet)}};

  json rig;
  rig["points"] = json::array();
  for (const PointHandle& p : s.rig.points) rig["points"].push_back({{"name", p.name}, {"position", vec3(p.position)}});
  json joints = json::array();
  for (int i = 0; i < s.rig.skeleton.num_joints(); ++i) joints.push_back(vec3(s.rig.skeleton.joints.row(i).transpose()));
  json bones = json::array();
  for (const Bone& b : s.rig.skeleton.bones) bones.push_back({{"a", b.a}, {"b", b.b}, {"name", b.name}});
  rig["skeleton"] = {{"joints", joints}, {"bones", bones}};
  rig["cages"] = json::array();
  for (const Cage& c : s.rig.cages)
    rig["cages"].push_back(
        {{"name", c.name}, {"V", blob.add(c.mesh.V)}, {"F", blob.add(c.mesh.F)}, {"edges", blob.add(c.edges)}});
  rig["regions"] = json::array();
  for (const Region& r : s.rig.regions)
    rig["regions"].push_back({{"name", r.name}, {"vertices", blob.add_indices(r.vertices)}});
  rig["pseudo_edges"] = json::array();
  for (auto [a, b] : s.rig.pseudo_edges) rig["pseudo_edges"].push_back({a, b});
  j["rig"] = rig;

  j["pose"] = params_json(s.pose);
  j["keys"] = json::array();
  for (const SceneKey& k : s.keys) {
    json key = {{"time", k.time}, {"params", params_json(k.params)}};
    // Version 2: a mesh key's own surface (a pose key has no "mesh").
    if (k.is_mesh()) key["mesh"] = {{"source", k.mesh_path}, {"V", blob.add(k.mesh.V)}, {"F", blob.add(k.mesh.F)}};
    // Optional: the in-between to the next key, when it is not the default.
    if (k.inbetween != InbetweenMethod::Handles) key["inbetween"] = inbetween_method_name(k.inbetween);
    j["keys"].push_back(key);
  }
  j["method"] = skin_method_name(s.method);
  j["inbetweens"] = s.inbetweens;
  {
    json states = json::array();
    for (HandleConstraint c : s.posing.states) states.push_back(constraint_state_name(c));
    j["posing"] = {{"fast", s.posing.fast}, {"iterations", s.posing.iterations}, {"states", states}};
  }
  j["bind_settings"] = {{"tetgen_switches", s.bind_settings.volume.tetgen_switches},
                        {"robust", robust_name(s.bind_settings.volume.robust)},
                        {"max_influences", s.bind_settings.max_influences}};
  j["weights"] = blob.add(s.weights);
  j["bind_stats"] = {{"seconds", s.bind_stats.seconds},
                     {"tet_vertices", s.bind_stats.tet_vertices},
                     {"tets", s.bind_stats.tets},
                     {"notes", s.bind_stats.notes}};
  j["mask"] = blob.add(s.mask);
  j["camera"] = {{"position", vec3(s.camera.position)}, {"target", vec3(s.camera.target)},
                 {"up", vec3(s.camera.up)}, {"fov_deg", s.camera.fov_deg}, {"ortho", s.camera.ortho}};
  j["time"] = s.time;
  j["selection"] = {{"handles", s.selection.handles}, {"joint", s.selection.joint}};

  const std::string sidecar = scene_sidecar_path(json_path);
  j["sidecar"] = {{"file", std::filesystem::path(sidecar).filename().string()},
                  {"bytes", blob.bytes().size()},
                  {"fnv1a64", hex64(fnv1a(blob.bytes()))}};
  // Both files are written to temps before either replaces its previous version, so a full disk or a
  // refused folder leaves the previous scene loadable. Sidecar renamed first: a crash between the two
  // renames leaves the old JSON, whose checksum then rejects the new sidecar with a clear message
  // instead of silently mixing two saves.
  const std::string text = j.dump(1) + "\n";
  write_files_atomic(
      {{sidecar, [&](std::ostream& o) { o.write(blob.bytes().data(), blob.bytes().size()); }, true},
       {json_path, [&](std::ostream& o) { o << text; }, false}});
}

SceneData read_scene(const std::string& path) {
  require_readable_file(path);
  SceneReader R(path);
  json j;
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) R.fail("cannot open");
    try {
      j = json::parse(in);
    } catch (const json::exception& e) {
      R.fail(std::string("not valid JSON: ") + e.what());
    }
  }
  if (!j.is_object()) R.fail("not a scene file (top level is not an object)");
  if (!j.contains("format") || !j["format"].is_string() || j["format"].get<std::string>() != kFormat)
    R.fail("not a scene file (missing \"format\": \"deform-scene\")");
  const long long version = R.integer(R.field(j, "version", "scene"), "version", 1, 1 << 30);
  if (version > kSceneFormatVersion)
    R.fail("scene format version " + std::to_string(version) + " is newer than this program reads (" +
           std::to_string(kSceneFormatVersion) + ")");
  R.load_sidecar(j, std::filesystem::path(path).parent_path().string());

  SceneData s;
  const json& surf = R.field(j, "surface", "scene");
  s.surface_path = R.string(R.field(surf, "source", "surface"), "surface.source");
  s.surface.V = R.f64(R.field(surf, "V", "surface"), "surface.V", 3);
  s.surface.F = R.i32(R.field(surf, "F", "surface"), "surface.F", 3);
  s.surface.N = R.f64(R.field(surf, "N", "surface"), "surface.N", 3);
  const long long nv = s.surface.V.rows();
  R.check_indices(s.surface.F, nv, "surface.F");
  if (s.surface.N.size() > 0 && s.surface.N.rows() != nv) R.fail("'surface.N' must have one row per vertex");

  const json& tets = R.field(j, "tets", "scene");
  s.tets.V = R.f64(R.field(tets, "V", "tets"), "tets.V", 3);
  s.tets.T = R.i32(R.field(tets, "T", "tets"), "tets.T", 4);
  s.tets.F = R.i32(R.field(tets, "F", "tets"), "tets.F", 3);
  R.check_indices(s.tets.T, s.tets.V.rows(), "tets.T");
  R.check_indices(s.tets.F, s.tets.V.rows(), "tets.F");
  const Eigen::MatrixXi s2t = R.i32(R.field(tets, "surface_to_tet", "tets"), "tets.surface_to_tet", 1);
  if (s2t.size() > 0 && s2t.rows() != nv) R.fail("'tets.surface_to_tet' must have one entry per surface vertex");
  R.check_indices(s2t, s.tets.V.rows(), "tets.surface_to_tet");
  s.surface_to_tet = s2t.size() > 0 ? Eigen::VectorXi(s2t.col(0)) : Eigen::VectorXi();

  const json& rig = R.field(j, "rig", "scene");
  const json& pts = R.array(R.field(rig, "points", "rig"), "rig.points");
  for (size_t i = 0; i < pts.size(); ++i) {
    const std::string c = "rig.points[" + std::to_string(i) + "]";
    s.rig.points.push_back({R.vec3(R.field(pts[i], "position", c), c + ".position"),
                            R.string(R.field(pts[i], "name", c), c + ".name")});
  }
  const json& sk = R.field(rig, "skeleton", "rig");
  const json& joints = R.array(R.field(sk, "joints", "rig.skeleton"), "rig.skeleton.joints");
  s.rig.skeleton.joints.resize(joints.size(), joints.empty() ? 0 : 3);  // an empty skeleton is 0 x 0
  for (size_t i = 0; i < joints.size(); ++i)
    s.rig.skeleton.joints.row(i) = R.vec3(joints[i], "rig.skeleton.joints[" + std::to_string(i) + "]").transpose();
  const json& bones = R.array(R.field(sk, "bones", "rig.skeleton"), "rig.skeleton.bones");
  const long long nj = static_cast<long long>(joints.size());
  for (size_t i = 0; i < bones.size(); ++i) {
    const std::string c = "rig.skeleton.bones[" + std::to_string(i) + "]";
    Bone b;
    b.a = static_cast<int>(R.integer(R.field(bones[i], "a", c), c + ".a", 0, nj - 1));
    b.b = static_cast<int>(R.integer(R.field(bones[i], "b", c), c + ".b", 0, nj - 1));
    if (b.a == b.b) R.fail("'" + c + "' joins a joint to itself");
    b.name = R.string(R.field(bones[i], "name", c), c + ".name");
    s.rig.skeleton.bones.push_back(b);
  }
  try {
    compute_bone_parents(s.rig.skeleton);
  } catch (const Error& e) {
    R.fail(e.what());
  }
  const json& cages = R.array(R.field(rig, "cages", "rig"), "rig.cages");
  for (size_t i = 0; i < cages.size(); ++i) {
    const std::string c = "rig.cages[" + std::to_string(i) + "]";
    Cage cg;
    cg.name = R.string(R.field(cages[i], "name", c), c + ".name");
    cg.mesh.V = R.f64(R.field(cages[i], "V", c), c + ".V", 3);
    cg.mesh.F = R.i32(R.field(cages[i], "F", c), c + ".F", 3);
    cg.edges = R.i32(R.field(cages[i], "edges", c), c + ".edges", 2);
    R.check_indices(cg.mesh.F, cg.mesh.V.rows(), c + ".F");
    R.check_indices(cg.edges, cg.mesh.V.rows(), c + ".edges");
    s.rig.cages.push_back(std::move(cg));
  }
  const json& regions = R.array(R.field(rig, "regions", "rig"), "rig.regions");
  for (size_t i = 0; i < regions.size(); ++i) {
    const std::string c = "rig.regions[" + std::to_string(i) + "]";
    Region g;
    g.name = R.string(R.field(regions[i], "name", c), c + ".name");
    const Eigen::MatrixXi v = R.i32(R.field(regions[i], "vertices", c), c + ".vertices", 1);
    R.check_indices(v, nv, c + ".vertices");
    g.vertices.assign(v.data(), v.data() + v.size());
    s.rig.regions.push_back(std::move(g));
  }
  const json& pe = R.array(R.field(rig, "pseudo_edges", "rig"), "rig.pseudo_edges");
  const long long np = static_cast<long long>(s.rig.points.size());
  for (size_t i = 0; i < pe.size(); ++i) {
    const std::string c = "rig.pseudo_edges[" + std::to_string(i) + "]";
    R.array(pe[i], c, 2);
    const int a = static_cast<int>(R.integer(pe[i][0], c, 0, np - 1)), b = static_cast<int>(R.integer(pe[i][1], c, 0, np - 1));
    if (a == b) R.fail("'" + c + "' joins a point to itself");
    s.rig.pseudo_edges.push_back({a, b});
  }

  s.pose = R.params(R.field(j, "pose", "scene"), s.rig, "pose");
  const json& keys = R.array(R.field(j, "keys", "scene"), "keys");
  for (size_t i = 0; i < keys.size(); ++i) {
    const std::string c = "keys[" + std::to_string(i) + "]";
    SceneKey k;
    k.time = R.number(R.field(keys[i], "time", c), c + ".time");
    if (!s.keys.empty() && !(k.time > s.keys.back().time)) R.fail("'" + c + ".time' is not after the previous key");
    k.params = R.params(R.field(keys[i], "params", c), s.rig, c + ".params");
    if (keys[i].is_object() && keys[i].contains("mesh")) {
      if (version < 2) R.fail("'" + c + ".mesh' needs scene format version 2 (the file says " + std::to_string(version) + ")");
      read_mesh_key(R, keys[i]["mesh"], c + ".mesh", k);
    }
    if (keys[i].is_object() && keys[i].contains("inbetween")) {
      try {
        k.inbetween = parse_inbetween_method(R.string(keys[i]["inbetween"], c + ".inbetween"));
      } catch (const Error& e) {
        R.fail("'" + c + ".inbetween': " + e.what());
      }
    }
    s.keys.push_back(std::move(k));
  }
  try {
    s.method = parse_skin_method(R.string(R.field(j, "method", "scene"), "method"));
  } catch (const Error& e) {
    R.fail(std::string("'method': ") + e.what());
  }
  s.inbetweens = static_cast<int>(R.integer(R.field(j, "inbetweens", "scene"), "inbetweens", 0, 1000));
  if (j.contains("posing")) {  // optional: scenes from before FAST posing pose by hand
    const json& p = j["posing"];
    s.posing.fast = R.boolean(R.field(p, "fast", "posing"), "posing.fast");
    s.posing.iterations = static_cast<int>(R.integer(R.field(p, "iterations", "posing"), "posing.iterations", 1, 1000));
    const json& st = R.array(R.field(p, "states", "posing"), "posing.states");
    for (size_t i = 0; i < st.size(); ++i) {
      const std::string c = "posing.states[" + std::to_string(i) + "]";
      try {
        s.posing.states.push_back(parse_constraint_state(R.string(st[i], c)));
      } catch (const Error& e) {
        R.fail("'" + c + "': " + e.what());
      }
    }
    if (!s.posing.states.empty() && static_cast<long long>(s.posing.states.size()) != num_handles(s.rig))
      R.fail("'posing.states' has " + std::to_string(s.posing.states.size()) + " entries for " +
             std::to_string(num_handles(s.rig)) + " handles");
  }
  const json& bs = R.field(j, "bind_settings", "scene");
  s.bind_settings.volume.tetgen_switches =
      R.string(R.field(bs, "tetgen_switches", "bind_settings"), "bind_settings.tetgen_switches");
  const std::string robust = R.string(R.field(bs, "robust", "bind_settings"), "bind_settings.robust");
  if (robust == "auto") s.bind_settings.volume.robust = VolumeOptions::Robust::Auto;
  else if (robust == "never") s.bind_settings.volume.robust = VolumeOptions::Robust::Never;
  else if (robust == "always") s.bind_settings.volume.robust = VolumeOptions::Robust::Always;
  else R.fail("'bind_settings.robust' must be auto, never or always");
  s.bind_settings.max_influences =
      static_cast<int>(R.integer(R.field(bs, "max_influences", "bind_settings"), "bind_settings.max_influences", 0, 1 << 20));

  s.weights = R.f64(R.field(j, "weights", "scene"), "weights");
  if (s.weights.size() > 0 && (s.weights.rows() != nv || s.weights.cols() != num_handles(s.rig)))
    R.fail("'weights' is " + std::to_string(s.weights.rows()) + " x " + std::to_string(s.weights.cols()) +
           ", expected #vertices x #handles = " + std::to_string(nv) + " x " + std::to_string(num_handles(s.rig)));
  const json& st = R.field(j, "bind_stats", "scene");
  s.bind_stats.seconds = R.number(R.field(st, "seconds", "bind_stats"), "bind_stats.seconds");
  s.bind_stats.tet_vertices =
      static_cast<int>(R.integer(R.field(st, "tet_vertices", "bind_stats"), "bind_stats.tet_vertices", 0, INT_MAX));
  s.bind_stats.tets = static_cast<int>(R.integer(R.field(st, "tets", "bind_stats"), "bind_stats.tets", 0, INT_MAX));
  const json& notes = R.array(R.field(st, "notes", "bind_stats"), "bind_stats.notes");
  for (const json& n : notes) s.bind_stats.notes.push_back(R.string(n, "bind_stats.notes[]"));

  const Eigen::MatrixXd mask = R.f64(R.field(j, "mask", "scene"), "mask", 1);
  if (mask.size() > 0 && mask.rows() != nv) R.fail("'mask' must have one value per surface vertex");
  if (mask.size() > 0 && (mask.minCoeff() < 0 || mask.maxCoeff() > 1)) R.fail("'mask' values must lie in [0, 1]");
  s.mask = mask.size() > 0 ? Eigen::VectorXd(mask.col(0)) : Eigen::VectorXd();

  const json& cam = R.field(j, "camera", "scene");
  s.camera.position = R.vec3(R.field(cam, "position", "camera"), "camera.position");
  s.camera.target = R.vec3(R.field(cam, "target", "camera"), "camera.target");
  s.camera.up = R.vec3(R.field(cam, "up", "camera"), "camera.up");
  s.camera.fov_deg = R.number(R.field(cam, "fov_deg", "camera"), "camera.fov_deg");
  s.camera.ortho = R.boolean(R.field(cam, "ortho", "camera"), "camera.ortho");
  s.time = R.number(R.field(j, "time", "scene"), "time");
  const json& sel = R.field(j, "selection", "scene");
  const json& sh = R.array(R.field(sel, "handles", "selection"), "selection.handles");
  for (const json& h : sh)
    s.selection.handles.push_back(static_cast<int>(R.integer(h, "selection.handles[]", 0, num_handles(s.rig) - 1)));
  s.selection.joint = static_cast<int>(
      R.integer(R.field(sel, "joint", "selection"), "selection.joint", -1, s.rig.skeleton.num_joints() - 1));
  return s;
}

}  // namespace dfm
