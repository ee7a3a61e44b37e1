#include "core/scene/scene_file.h"

#include <climits>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/anim/inbetween_method.h"
#include "core/rig/handle_constraint.h"
#include "core/scene/scene_reader.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace dfm {

using json = nlohmann::json;

namespace {

const char* kFormat = "deform-scene";

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
      list(p.bone_twist_stretch, [](const BoneTwistStretch& t) { return json::array({t.twist, t.stretch, t.twist_start}); });
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

const char* segmentation_name(VolumeOptions::Segmentation s) {
  return s == VolumeOptions::Segmentation::Threshold ? "threshold" : "cut";
}

// ---- reading ---------------------------------------------------------------------------------------

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

json parse_scene_json(const SceneReader& R, const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) R.fail("cannot open");
  json j;
  try {
    j = json::parse(in);
  } catch (const json::exception& e) {
    R.fail(std::string("not valid JSON: ") + e.what());
  }
  return j;
}

// The format tag and a version this program reads; returns the version.
long long scene_version(const SceneReader& R, const json& j) {
  if (!j.is_object()) R.fail("not a scene file (top level is not an object)");
  if (!j.contains("format") || !j["format"].is_string() || j["format"].get<std::string>() != kFormat)
    R.fail("not a scene file (missing \"format\": \"deform-scene\")");
  const long long version = R.integer(R.field(j, "version", "scene"), "version", 1, 1 << 30);
  if (version > kSceneFormatVersion)
    R.fail("scene format version " + std::to_string(version) + " is newer than this program reads (" +
           std::to_string(kSceneFormatVersion) + ")");
  return version;
}

void read_surface(const SceneReader& R, const json& j, SceneData& s) {
  const json& surf = R.field(j, "surface", "scene");
  s.surface_path = R.string(R.field(surf, "source", "surface"), "surface.source");
  s.surface.V = R.f64(R.field(surf, "V", "surface"), "surface.V", 3);
  s.surface.F = R.i32(R.field(surf, "F", "surface"), "surface.F", 3);
  s.surface.N = R.f64(R.field(surf, "N", "surface"), "surface.N", 3);
  const long long nv = s.surface.V.rows();
  R.check_indices(s.surface.F, nv, "surface.F");
  if (s.surface.N.size() > 0 && s.surface.N.rows() != nv) R.fail("'surface.N' must have one row per vertex");
}

void read_tets(const SceneReader& R, const json& j, SceneData& s) {
  const json& tets = R.field(j, "tets", "scene");
  s.tets.V = R.f64(R.field(tets, "V", "tets"), "tets.V", 3);
  s.tets.T = R.i32(R.field(tets, "T", "tets"), "tets.T", 4);
  s.tets.F = R.i32(R.field(tets, "F", "tets"), "tets.F", 3);
  R.check_indices(s.tets.T, s.tets.V.rows(), "tets.T");
  R.check_indices(s.tets.F, s.tets.V.rows(), "tets.F");
  const Eigen::MatrixXi s2t = R.i32(R.field(tets, "surface_to_tet", "tets"), "tets.surface_to_tet", 1);
  if (s2t.size() > 0 && s2t.rows() != s.surface.V.rows())
    R.fail("'tets.surface_to_tet' must have one entry per surface vertex");
  R.check_indices(s2t, s.tets.V.rows(), "tets.surface_to_tet");
  s.surface_to_tet = s2t.size() > 0 ? Eigen::VectorXi(s2t.col(0)) : Eigen::VectorXi();
}

void read_skeleton(const SceneReader& R, const json& rig, Skeleton& skeleton) {
  const json& sk = R.field(rig, "skeleton", "rig");
  const json& joints = R.array(R.field(sk, "joints", "rig.skeleton"), "rig.skeleton.joints");
  skeleton.joints.resize(joints.size(), joints.empty() ? 0 : 3);  // an empty skeleton is 0 x 0
  for (size_t i = 0; i < joints.size(); ++i)
    skeleton.joints.row(i) = R.vec3(joints[i], "rig.skeleton.joints[" + std::to_string(i) + "]").transpose();
  const json& bones = R.array(R.field(sk, "bones", "rig.skeleton"), "rig.skeleton.bones");
  const long long nj = static_cast<long long>(joints.size());
  for (size_t i = 0; i < bones.size(); ++i) {
    const std::string c = "rig.skeleton.bones[" + std::to_string(i) + "]";
    Bone b;
    b.a = static_cast<int>(R.integer(R.field(bones[i], "a", c), c + ".a", 0, nj - 1));
    b.b = static_cast<int>(R.integer(R.field(bones[i], "b", c), c + ".b", 0, nj - 1));
    if (b.a == b.b) R.fail("'" + c + "' joins a joint to itself");
    b.name = R.string(R.field(bones[i], "name", c), c + ".name");
    skeleton.bones.push_back(b);
  }
  try {
    compute_bone_parents(skeleton);
  } catch (const Error& e) {
    R.fail(e.what());
  }
}

void read_cages(const SceneReader& R, const json& rig, std::vector<Cage>& out) {
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
    out.push_back(std::move(cg));
  }
}

// Regions: surface vertex lists (nv surface vertices).
void read_regions(const SceneReader& R, const json& rig, long long nv, std::vector<Region>& out) {
  const json& regions = R.array(R.field(rig, "regions", "rig"), "rig.regions");
  for (size_t i = 0; i < regions.size(); ++i) {
    const std::string c = "rig.regions[" + std::to_string(i) + "]";
    Region g;
    g.name = R.string(R.field(regions[i], "name", c), c + ".name");
    const Eigen::MatrixXi v = R.i32(R.field(regions[i], "vertices", c), c + ".vertices", 1);
    R.check_indices(v, nv, c + ".vertices");
    g.vertices.assign(v.data(), v.data() + v.size());
    out.push_back(std::move(g));
  }
}

// The rig, in the order the fields have always been checked: points, skeleton, cages, regions,
// pseudo-edges (between points).
void read_rig(const SceneReader& R, const json& j, long long nv, Rig& out) {
  const json& rig = R.field(j, "rig", "scene");
  const json& pts = R.array(R.field(rig, "points", "rig"), "rig.points");
  for (size_t i = 0; i < pts.size(); ++i) {
    const std::string c = "rig.points[" + std::to_string(i) + "]";
    out.points.push_back({R.vec3(R.field(pts[i], "position", c), c + ".position"),
                          R.string(R.field(pts[i], "name", c), c + ".name")});
  }
  read_skeleton(R, rig, out.skeleton);
  read_cages(R, rig, out.cages);
  read_regions(R, rig, nv, out.regions);
  const json& pe = R.array(R.field(rig, "pseudo_edges", "rig"), "rig.pseudo_edges");
  const long long np = static_cast<long long>(out.points.size());
  for (size_t i = 0; i < pe.size(); ++i) {
    const std::string c = "rig.pseudo_edges[" + std::to_string(i) + "]";
    R.array(pe[i], c, 2);
    const int a = static_cast<int>(R.integer(pe[i][0], c, 0, np - 1)), b = static_cast<int>(R.integer(pe[i][1], c, 0, np - 1));
    if (a == b) R.fail("'" + c + "' joins a point to itself");
    out.pseudo_edges.push_back({a, b});
  }
}

// A local transition's offsets: one per vertex of the key's mesh, each in (-1, 1).
void read_transition(const SceneReader& R, const json& ref, const std::string& c, bool last, SceneKey& k) {
  if (last) R.fail("'" + c + ".transition': the last key has no next key to blend toward");
  const Eigen::MatrixXd o = R.f64(ref, c + ".transition", 1);
  if (!k.is_mesh() || o.rows() != k.mesh.V.rows())
    R.fail("'" + c + ".transition' must have one offset per vertex of the key's mesh");
  for (Eigen::Index v = 0; v < o.rows(); ++v)
    if (!(o(v, 0) > -1 && o(v, 0) < 1)) R.fail("'" + c + ".transition' offsets must lie in (-1, 1)");
  k.transition_to_next = o.col(0);
}

// Keys, strictly increasing in time; mesh keys need format version 2.
void read_keys(const SceneReader& R, const json& j, long long version, SceneData& s) {
  const json& keys = R.array(R.field(j, "keys", "scene"), "keys");
  for (size_t i = 0; i < keys.size(); ++i) {
    const std::string c = "keys[" + std::to_string(i) + "]";
    SceneKey k;
    k.time = R.number(R.field(keys[i], "time", c), c + ".time");
    if (!s.keys.empty() && !(k.time > s.keys.back().time)) R.fail("'" + c + ".time' is not after the previous key");
    k.params = R.params(R.field(keys[i], "params", c), s.rig, c + ".params", s.additional_weights.cols());
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
    if (keys[i].is_object() && keys[i].contains("pairs")) {
      if (i + 1 == keys.size()) R.fail("'" + c + ".pairs': the last key has no next key to pair with");
      const json& pairs = R.array(keys[i]["pairs"], c + ".pairs");
      k.pairs_to_next.resize(static_cast<Eigen::Index>(pairs.size()), 6);
      for (size_t r = 0; r < pairs.size(); ++r) {
        const std::string cr = c + ".pairs[" + std::to_string(r) + "]";
        R.array(pairs[r], cr, 6);
        for (int col = 0; col < 6; ++col) k.pairs_to_next(static_cast<Eigen::Index>(r), col) = R.number(pairs[r][col], cr);
      }
    }
    if (keys[i].is_object() && keys[i].contains("transition")) read_transition(R, keys[i]["transition"], c, i + 1 == keys.size(), k);
    s.keys.push_back(std::move(k));
  }
}

// Optional: scenes from before FAST posing pose by hand.
void read_posing(const SceneReader& R, const json& j, SceneData& s) {
  if (!j.contains("posing")) return;
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
  // Optional: scenes from before dynamics keep its defaults (off).
  if (p.contains("dynamics")) s.posing.dynamics = R.boolean(p["dynamics"], "posing.dynamics");
  if (p.contains("dt")) s.posing.dt = R.number(p["dt"], "posing.dt");
  if (p.contains("damping")) s.posing.damping = R.number(p["damping"], "posing.damping");
  if (p.contains("density")) s.posing.density = R.number(p["density"], "posing.density");
  if (!(s.posing.dt > 0 && s.posing.dt <= 1)) R.fail("'posing.dt' must be in (0, 1]");
  if (!(s.posing.damping >= 0)) R.fail("'posing.damping' must be >= 0");
  if (!(s.posing.density > 0)) R.fail("'posing.density' must be > 0");
}

// Optional (scenes from before they were saved keep the defaults): the robust volume's segmentation.
void read_volume_segmentation(const SceneReader& R, const json& bs, VolumeOptions& v) {
  if (bs.contains("segmentation")) {
    const std::string seg = R.string(bs["segmentation"], "bind_settings.segmentation");
    if (seg == "cut") v.segmentation = VolumeOptions::Segmentation::Cut;
    else if (seg == "threshold") v.segmentation = VolumeOptions::Segmentation::Threshold;
    else R.fail("'bind_settings.segmentation' must be cut or threshold");
  }
  if (!bs.contains("cut")) return;
  const json& cut = bs["cut"];
  if (!cut.is_object()) R.fail("'bind_settings.cut' must be an object");
  const auto read = [&](const char* key, double& out) {
    out = R.number(R.field(cut, key, "bind_settings.cut"), std::string("bind_settings.cut.") + key);
  };
  read("gamma", v.cut.gamma);
  read("sigma", v.cut.sigma);
  read("surface_factor", v.cut.surface_factor);
  // The graph cut's own ranges (graph_cut_segmentation.h), checked here so a bad file fails on load.
  if (!(v.cut.gamma >= 0) || !(v.cut.sigma > 0) || !(v.cut.surface_factor >= 0))
    R.fail("'bind_settings.cut' needs gamma >= 0, sigma > 0 and surface_factor >= 0");
}

void read_bind_settings(const SceneReader& R, const json& j, BindSettings& out) {
  const json& bs = R.field(j, "bind_settings", "scene");
  out.volume.tetgen_switches = R.string(R.field(bs, "tetgen_switches", "bind_settings"), "bind_settings.tetgen_switches");
  const std::string robust = R.string(R.field(bs, "robust", "bind_settings"), "bind_settings.robust");
  if (robust == "auto") out.volume.robust = VolumeOptions::Robust::Auto;
  else if (robust == "never") out.volume.robust = VolumeOptions::Robust::Never;
  else if (robust == "always") out.volume.robust = VolumeOptions::Robust::Always;
  else R.fail("'bind_settings.robust' must be auto, never or always");
  out.max_influences =
      static_cast<int>(R.integer(R.field(bs, "max_influences", "bind_settings"), "bind_settings.max_influences", 0, 1 << 20));
  // Optional: scenes from before monotone weights bind without them.
  out.monotone = bs.contains("monotone") && R.boolean(bs["monotone"], "bind_settings.monotone");
  // Optional: scenes from before additional weights bind without them.
  out.additional_weights =
      bs.contains("additional_weights")
          ? static_cast<int>(R.integer(bs["additional_weights"], "bind_settings.additional_weights", 0, kMaxAdditionalWeights))
          : 0;
  read_volume_segmentation(R, bs, out.volume);
}

// The bind's additional weights (optional: #surface vertices x k, finite), before the weights they
// belong to are read: the poses' solved transforms may name their handles. read_bind_results checks
// that the weights are there.
void read_additional_weights(const SceneReader& R, const json& j, SceneData& s) {
  if (!j.contains("additional_weights")) return;
  s.additional_weights = R.f64(j["additional_weights"], "additional_weights");
  const Eigen::MatrixXd& A = s.additional_weights;
  if (A.size() > 0 && (A.rows() != s.surface.V.rows() || A.cols() > kMaxAdditionalWeights))
    R.fail("'additional_weights' is " + std::to_string(A.rows()) + " x " + std::to_string(A.cols()) +
           ", expected #vertices x k = " + std::to_string(s.surface.V.rows()) + " x (at most " +
           std::to_string(kMaxAdditionalWeights) + ")");
}

// The bind's weights (empty, or #surface vertices x #handles) and statistics.
void read_bind_results(const SceneReader& R, const json& j, SceneData& s) {
  const long long nv = s.surface.V.rows();
  s.weights = R.f64(R.field(j, "weights", "scene"), "weights");
  if (s.weights.size() > 0 && (s.weights.rows() != nv || s.weights.cols() != num_handles(s.rig)))
    R.fail("'weights' is " + std::to_string(s.weights.rows()) + " x " + std::to_string(s.weights.cols()) +
           ", expected #vertices x #handles = " + std::to_string(nv) + " x " + std::to_string(num_handles(s.rig)));
  // Optional: scenes from before the bind's endpoint weights (STBS then projects onto the bones).
  if (j.contains("endpoint_weights")) {
    s.endpoint_weights = R.f64(j["endpoint_weights"], "endpoint_weights");
    const Eigen::MatrixXd& E = s.endpoint_weights;
    if (E.size() > 0 && (s.weights.size() == 0 || E.rows() != nv || E.cols() != s.rig.skeleton.num_bones() ||
                         E.minCoeff() < 0 || E.maxCoeff() > 1))
      R.fail("'endpoint_weights' is " + std::to_string(E.rows()) + " x " + std::to_string(E.cols()) +
             ", expected #vertices x #bones = " + std::to_string(nv) + " x " +
             std::to_string(s.rig.skeleton.num_bones()) + " in [0, 1] beside the weights");
  }
  if (s.additional_weights.size() > 0 && s.weights.size() == 0)
    R.fail("'additional_weights' without 'weights': they belong to a bind");
  const json& st = R.field(j, "bind_stats", "scene");
  s.bind_stats.seconds = R.number(R.field(st, "seconds", "bind_stats"), "bind_stats.seconds");
  s.bind_stats.tet_vertices =
      static_cast<int>(R.integer(R.field(st, "tet_vertices", "bind_stats"), "bind_stats.tet_vertices", 0, INT_MAX));
  s.bind_stats.tets = static_cast<int>(R.integer(R.field(st, "tets", "bind_stats"), "bind_stats.tets", 0, INT_MAX));
  const json& notes = R.array(R.field(st, "notes", "bind_stats"), "bind_stats.notes");
  for (const json& n : notes) s.bind_stats.notes.push_back(R.string(n, "bind_stats.notes[]"));
}

// Optional (scenes before Fig. 6.9's filters have none): per bone a list of [x, y] points.
void read_endpoint_filters(const SceneReader& R, const json& j, SceneData& s) {
  if (!j.contains("endpoint_filters")) return;
  const json& a = R.array(j["endpoint_filters"], "endpoint_filters", s.rig.skeleton.num_bones());
  for (size_t b = 0; b < a.size(); ++b) {
    const std::string c = "endpoint_filters[" + std::to_string(b) + "]";
    EndpointFilter f;
    for (size_t i = 0; i < R.array(a[b], c).size(); ++i) {
      const std::string ci = c + "[" + std::to_string(i) + "]";
      const json& p = R.array(a[b][i], ci, 2);
      f.emplace_back(R.number(p[0], ci), R.number(p[1], ci));
    }
    try {
      check_endpoint_filter(f, c);
    } catch (const Error& e) {
      R.fail(e.what());
    }
    s.endpoint_filters.push_back(std::move(f));
  }
}

void read_mask(const SceneReader& R, const json& j, SceneData& s) {
  const Eigen::MatrixXd mask = R.f64(R.field(j, "mask", "scene"), "mask", 1);
  if (mask.size() > 0 && mask.rows() != s.surface.V.rows()) R.fail("'mask' must have one value per surface vertex");
  if (mask.size() > 0 && (mask.minCoeff() < 0 || mask.maxCoeff() > 1)) R.fail("'mask' values must lie in [0, 1]");
  s.mask = mask.size() > 0 ? Eigen::VectorXd(mask.col(0)) : Eigen::VectorXd();
}

// Camera, time and selection.
void read_view(const SceneReader& R, const json& j, SceneData& s) {
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

namespace {

// Keys in time order: time and params; a mesh key's surface (version 2); the in-between and the
// picked pairs to the next key when set.
// Space-time edits (optional: scenes before issue 35 have none).
json space_time_edits_json(const std::vector<SpaceTimeEdit>& edits) {
  json out = json::array();
  for (const SpaceTimeEdit& e : edits) {
    json dabs = json::array();
    for (const Eigen::Vector3d& d : e.region.dabs) dabs.push_back(vec3(d));
    out.push_back({{"center", vec3(e.region.center)},
                   {"dabs", dabs},
                   {"radius", e.region.radius},
                   {"t0", e.region.t0},
                   {"t1", e.region.t1},
                   {"handle", vec3(e.handle.point)},
                   {"handle_time", e.handle.time},
                   {"move", vec3(e.move)},
                   {"rotation", quat(e.rotation)},
                   {"retime", e.retime},
                   {"weights", laplacian_weights_name(e.weights)},
                   {"time_scale", e.time_scale},
                   {"volume", e.preserve_volume},
                   {"refine", e.refine}});
  }
  return out;
}

void read_space_time_edits(const SceneReader& R, const json& j, SceneData& s) {
  if (!j.contains("space_time_edits")) return;
  const json& a = R.array(j["space_time_edits"], "space_time_edits");
  for (size_t i = 0; i < a.size(); ++i) {
    const std::string c = "space_time_edits[" + std::to_string(i) + "]";
    SpaceTimeEdit e;
    e.region.center = R.vec3(R.field(a[i], "center", c), c + ".center");
    if (a[i].contains("dabs")) {  // absent before brushed regions
      const json& dabs = R.array(a[i]["dabs"], c + ".dabs");
      for (size_t k = 0; k < dabs.size(); ++k) e.region.dabs.push_back(R.vec3(dabs[k], c + ".dabs[" + std::to_string(k) + "]"));
    }
    e.region.radius = R.number(R.field(a[i], "radius", c), c + ".radius");
    e.region.t0 = R.number(R.field(a[i], "t0", c), c + ".t0");
    e.region.t1 = R.number(R.field(a[i], "t1", c), c + ".t1");
    e.handle.point = R.vec3(R.field(a[i], "handle", c), c + ".handle");
    e.handle.time = R.number(R.field(a[i], "handle_time", c), c + ".handle_time");
    e.move = R.vec3(R.field(a[i], "move", c), c + ".move");
    e.rotation = R.quat(R.field(a[i], "rotation", c), c + ".rotation").normalized();
    if (a[i].contains("retime")) e.retime = R.number(a[i]["retime"], c + ".retime");  // absent before retime
    try {
      e.weights = parse_laplacian_weights(R.string(R.field(a[i], "weights", c), c + ".weights"));
    } catch (const Error& err) {
      R.fail("'" + c + ".weights': " + err.what());
    }
    e.time_scale = R.number(R.field(a[i], "time_scale", c), c + ".time_scale");
    e.preserve_volume = R.boolean(R.field(a[i], "volume", c), c + ".volume");
    if (a[i].contains("refine")) e.refine = R.boolean(a[i]["refine"], c + ".refine");  // absent before 4.5
    try {
      check_space_time_edit(e);
    } catch (const Error& err) {
      R.fail("'" + c + "': " + err.what());
    }
    s.space_time_edits.push_back(e);
  }
}

json keys_json(const std::vector<SceneKey>& scene_keys, BlobWriter& blob) {
  json keys = json::array();
  for (const SceneKey& k : scene_keys) {
    json key = {{"time", k.time}, {"params", params_json(k.params)}};
    // Version 2: a mesh key's own surface (a pose key has no "mesh").
    if (k.is_mesh()) key["mesh"] = {{"source", k.mesh_path}, {"V", blob.add(k.mesh.V)}, {"F", blob.add(k.mesh.F)}};
    // Optional: the in-between to the next key, when it is not the default.
    if (k.inbetween != InbetweenMethod::Handles) key["inbetween"] = inbetween_method_name(k.inbetween);
    // Optional: picked pairs to the next key, [x0, y0, z0, x1, y1, z1] each.
    if (k.pairs_to_next.rows() > 0) {
      key["pairs"] = json::array();
      for (Eigen::Index r = 0; r < k.pairs_to_next.rows(); ++r) {
        json row = json::array();
        for (int c = 0; c < 6; ++c) row.push_back(k.pairs_to_next(r, c));
        key["pairs"].push_back(row);
      }
    }
    // Optional: the local transition's per-vertex offsets to the next key (differential_blend.h).
    if (k.transition_to_next.size() > 0) key["transition"] = blob.add(k.transition_to_next);
    keys.push_back(key);
  }
  return keys;
}

// One list of [x, y] points a bone (read_endpoint_filters reads them back).
json endpoint_filters_json(const SceneData& s) {
  json filters = json::array();
  for (int b = 0; b < s.rig.skeleton.num_bones(); ++b) {
    json points = json::array();
    if (b < static_cast<int>(s.endpoint_filters.size()))
      for (const Eigen::Vector2d& p : s.endpoint_filters[b]) points.push_back(json::array({p.x(), p.y()}));
    filters.push_back(points);
  }
  return filters;
}

}  // namespace

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
  j["keys"] = keys_json(s.keys, blob);
  if (!s.space_time_edits.empty()) j["space_time_edits"] = space_time_edits_json(s.space_time_edits);
  j["method"] = skin_method_name(s.method);
  j["inbetweens"] = s.inbetweens;
  if (!s.endpoint_filters.empty()) j["endpoint_filters"] = endpoint_filters_json(s);
  {
    json states = json::array();
    for (HandleConstraint c : s.posing.states) states.push_back(constraint_state_name(c));
    j["posing"] = {{"fast", s.posing.fast}, {"iterations", s.posing.iterations}, {"states", states},
                   {"dynamics", s.posing.dynamics}, {"dt", s.posing.dt}, {"damping", s.posing.damping},
                   {"density", s.posing.density}};
  }
  j["bind_settings"] = {{"tetgen_switches", s.bind_settings.volume.tetgen_switches},
                        {"robust", robust_name(s.bind_settings.volume.robust)},
                        {"max_influences", s.bind_settings.max_influences},
                        {"monotone", s.bind_settings.monotone},
                        {"additional_weights", s.bind_settings.additional_weights},
                        {"segmentation", segmentation_name(s.bind_settings.volume.segmentation)},
                        {"cut", {{"gamma", s.bind_settings.volume.cut.gamma},
                                 {"sigma", s.bind_settings.volume.cut.sigma},
                                 {"surface_factor", s.bind_settings.volume.cut.surface_factor}}}};
  j["weights"] = blob.add(s.weights);
  if (s.endpoint_weights.size() > 0) j["endpoint_weights"] = blob.add(s.endpoint_weights);
  if (s.additional_weights.size() > 0) j["additional_weights"] = blob.add(s.additional_weights);
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
                  {"fnv1a64", sidecar_checksum(blob.bytes())}};
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
  const json j = parse_scene_json(R, path);
  const long long version = scene_version(R, j);
  R.load_sidecar(j, std::filesystem::path(path).parent_path().string());

  // Fields in the order they have always been checked (the first problem is the one reported).
  SceneData s;
  read_surface(R, j, s);
  read_tets(R, j, s);
  read_rig(R, j, s.surface.V.rows(), s.rig);
  read_additional_weights(R, j, s);  // before the poses: their solved transforms may name its handles
  s.pose = R.params(R.field(j, "pose", "scene"), s.rig, "pose", s.additional_weights.cols());
  read_keys(R, j, version, s);
  read_space_time_edits(R, j, s);
  try {
    s.method = parse_skin_method(R.string(R.field(j, "method", "scene"), "method"));
  } catch (const Error& e) {
    R.fail(std::string("'method': ") + e.what());
  }
  s.inbetweens = static_cast<int>(R.integer(R.field(j, "inbetweens", "scene"), "inbetweens", 0, 1000));
  read_endpoint_filters(R, j, s);
  read_posing(R, j, s);
  read_bind_settings(R, j, s.bind_settings);
  read_bind_results(R, j, s);
  read_mask(R, j, s);
  read_view(R, j, s);
  return s;
}

}  // namespace dfm
