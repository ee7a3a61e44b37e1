#include "core/scene/document.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "core/anim/transition.h"
#include "core/mesh/io.h"
#include "core/rig/rig_io.h"
#include "core/scene/scene_file.h"
#include "core/util/error.h"

namespace dfm {

bool Camera::operator==(const Camera& o) const {
  return position == o.position && target == o.target && up == o.up && fov_deg == o.fov_deg && ortho == o.ortho;
}
bool BindSettings::operator==(const BindSettings& o) const {
  return volume.tetgen_switches == o.volume.tetgen_switches && volume.robust == o.volume.robust &&
         max_influences == o.max_influences;
}
bool BindStats::operator==(const BindStats& o) const {
  return seconds == o.seconds && tet_vertices == o.tet_vertices && tets == o.tets && notes == o.notes;
}

PoseParams fit_pose_params(const Rig& rig, PoseParams p) {
  const size_t nb = rig.skeleton.num_bones(), np = num_point_handles(rig), nc = num_cage_vertices(rig),
               nr = rig.regions.size();
  p.bone_rotation.resize(nb, Eigen::Quaterniond::Identity());
  p.bone_translation.resize(nb, Eigen::Vector3d::Zero());
  p.bone_twist_stretch.resize(nb, BoneTwistStretch{});
  p.point_translation.resize(np, Eigen::Vector3d::Zero());
  p.point_rotation.resize(np, Eigen::Quaterniond::Identity());
  p.cage_translation.resize(nc, Eigen::Vector3d::Zero());
  p.region_transform.resize(nr, Eigen::Affine3d::Identity());
  return p;
}

TriMesh tet_boundary_surface(const TetMesh& tets, Eigen::VectorXi* to_tet) {
  // Outward faces of a positively oriented tet (v3 lies on the positive side of (v0,v1,v2)).
  static const int kFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  std::map<std::array<int, 3>, std::pair<int, std::array<int, 3>>> count;  // sorted key -> (n, oriented)
  for (int t = 0; t < tets.num_tets(); ++t)
    for (const auto& f : kFaces) {
      std::array<int, 3> o{tets.T(t, f[0]), tets.T(t, f[1]), tets.T(t, f[2])}, k = o;
      std::sort(k.begin(), k.end());
      auto& e = count[k];
      e.first++;
      e.second = o;
    }
  std::vector<std::array<int, 3>> faces;
  for (const auto& [k, e] : count)
    if (e.first == 1) faces.push_back(e.second);
  std::vector<int> remap(tets.num_vertices(), -1), back;
  for (auto& f : faces)
    for (int& v : f) {
      if (remap[v] < 0) {
        remap[v] = static_cast<int>(back.size());
        back.push_back(v);
      }
      v = remap[v];
    }
  TriMesh m;
  m.V.resize(back.size(), 3);
  for (size_t i = 0; i < back.size(); ++i) m.V.row(i) = tets.V.row(back[i]);
  m.F.resize(faces.size(), 3);
  for (size_t i = 0; i < faces.size(); ++i) m.F.row(i) << faces[i][0], faces[i][1], faces[i][2];
  if (to_tet) *to_tet = Eigen::Map<Eigen::VectorXi>(back.data(), back.size());
  return m;
}

// ---- undo machinery ------------------------------------------------------------------------------

enum Document::Part : unsigned {
  kSurface = 1u << 0,  // surface, surface_path, tets, surface_to_tet
  kRig = 1u << 1,
  kPose = 1u << 2,
  kKeys = 1u << 3,
  kWeights = 1u << 4,  // weights, bind_stats (and the weights note)
  kMask = 1u << 5,
  kSettings = 1u << 6,  // method, bind settings, in-betweens
};

struct Document::Step {
  std::string name;
  unsigned parts = 0;
  std::string merge_target;
  std::uint64_t serial = 0;
  SceneData saved;  // only `parts` are meaningful: swapped with the document on undo/redo
  std::string weights_note;
};

namespace {
void swap_parts(SceneData& a, SceneData& b, unsigned parts) {
  using std::swap;
  if (parts & 1u) {
    swap(a.surface, b.surface);
    swap(a.surface_path, b.surface_path);
    swap(a.tets, b.tets);
    swap(a.surface_to_tet, b.surface_to_tet);
  }
  if (parts & 2u) swap(a.rig, b.rig);
  if (parts & 4u) swap(a.pose, b.pose), swap(a.posing, b.posing);
  if (parts & 8u) swap(a.keys, b.keys);
  if (parts & 16u) {
    swap(a.weights, b.weights);
    swap(a.bind_stats, b.bind_stats);
  }
  if (parts & 32u) swap(a.mask, b.mask);
  if (parts & 64u) {
    swap(a.method, b.method);
    swap(a.bind_settings, b.bind_settings);
    swap(a.inbetweens, b.inbetweens);
  }
}

void copy_parts(const SceneData& from, SceneData& to, unsigned parts) {
  if (parts & 1u) {
    to.surface = from.surface;
    to.surface_path = from.surface_path;
    to.tets = from.tets;
    to.surface_to_tet = from.surface_to_tet;
  }
  if (parts & 2u) to.rig = from.rig;
  if (parts & 4u) to.pose = from.pose, to.posing = from.posing;
  if (parts & 8u) to.keys = from.keys;
  if (parts & 16u) {
    to.weights = from.weights;
    to.bind_stats = from.bind_stats;
  }
  if (parts & 32u) to.mask = from.mask;
  if (parts & 64u) {
    to.method = from.method;
    to.bind_settings = from.bind_settings;
    to.inbetweens = from.inbetweens;
  }
}

void check_finite(const Eigen::Vector3d& p, const char* what) {
  if (!p.allFinite()) throw Error(std::string(what) + " is not finite");
}

template <class T>
void erase_at(std::vector<T>& v, int i) {
  if (i >= 0 && i < static_cast<int>(v.size())) v.erase(v.begin() + i);
}
}  // namespace

Document::Document() { s_.pose = fit_pose_params(s_.rig, {}); }
Document::~Document() = default;

void Document::execute(const std::string& name, unsigned parts, const std::string& merge_target,
                       const std::function<void(SceneData&)>& edit) {
  const bool merge = gesture_open_ && gesture_merge_ok_ && !merge_target.empty() && !undo_.empty() &&
                     undo_.back()->merge_target == merge_target && (undo_.back()->parts & parts) == parts;
  if (merge) {
    // The step already holds the state from before the gesture: edit in place, restoring on failure.
    SceneData backup;
    copy_parts(s_, backup, parts);
    try {
      edit(s_);
    } catch (...) {
      swap_parts(s_, backup, parts);
      throw;
    }
    undo_.back()->serial = next_serial_++;
  } else {
    auto step = std::make_unique<Step>();
    step->name = name;
    step->parts = parts;
    step->merge_target = merge_target;
    step->weights_note = weights_note_;
    copy_parts(s_, step->saved, parts);
    try {
      edit(s_);
    } catch (...) {
      swap_parts(s_, step->saved, parts);
      weights_note_ = step->weights_note;
      throw;
    }
    step->serial = next_serial_++;
    undo_.push_back(std::move(step));
    gesture_merge_ok_ = gesture_open_;
  }
  redo_.clear();
  after_change();
}

void Document::rig_edit(const std::string& name, const std::string& merge_target,
                        const std::function<void(SceneData&)>& edit) {
  execute(name, kRig | kPose | kKeys | kWeights, merge_target, [&](SceneData& s) {
    edit(s);
    s.pose = fit_pose_params(s.rig, std::move(s.pose));
    for (SceneKey& k : s.keys) k.params = fit_pose_params(s.rig, std::move(k.params));
    if (s.weights.size() > 0) {
      s.weights.resize(0, 0);
      s.bind_stats = {};
      weights_note_ = "rig changed after bind (" + name + "): weights cleared, bind again";
    }
  });
}

void Document::after_change() {
  ++revision_;
  // Selection is view state: keep it valid whatever changed underneath.
  const int n = num_handles();
  auto& h = s_.selection.handles;
  h.erase(std::remove_if(h.begin(), h.end(), [n](int i) { return i < 0 || i >= n; }), h.end());
  if (s_.selection.joint >= s_.rig.skeleton.num_joints()) s_.selection.joint = -1;
}

bool Document::can_undo() const { return !undo_.empty(); }
bool Document::can_redo() const { return !redo_.empty(); }
std::string Document::undo_name() const { return undo_.empty() ? "" : undo_.back()->name; }
std::string Document::redo_name() const { return redo_.empty() ? "" : redo_.back()->name; }
int Document::undo_depth() const { return static_cast<int>(undo_.size()); }

// Undo and redo are the same move: swap the step's saved parts with the document's, then file the
// step on the other stack.
void Document::replay_step(std::vector<std::unique_ptr<Step>>& from, std::vector<std::unique_ptr<Step>>& to) {
  if (from.empty()) return;
  auto step = std::move(from.back());
  from.pop_back();
  swap_parts(s_, step->saved, step->parts);
  std::swap(weights_note_, step->weights_note);
  to.push_back(std::move(step));
  gesture_merge_ok_ = false;
  after_change();
}

void Document::undo() { replay_step(undo_, redo_); }
void Document::redo() { replay_step(redo_, undo_); }

void Document::begin_gesture() {
  gesture_open_ = true;
  gesture_merge_ok_ = false;
}
void Document::end_gesture() {
  gesture_open_ = false;
  gesture_merge_ok_ = false;
}

bool Document::dirty() const {
  const std::uint64_t cur = undo_.empty() ? 0 : undo_.back()->serial;
  return cur != saved_serial_;
}

// ---- queries ---------------------------------------------------------------------------------------

int Document::num_handles() const { return dfm::num_handles(s_.rig); }

Pose Document::pose() const { return evaluate_pose(s_.rig, s_.pose); }

bool Document::has_weights() const {
  return s_.weights.size() > 0 && s_.weights.rows() == s_.surface.num_vertices() && s_.weights.cols() == num_handles();
}

int Document::key_at(double t) const {
  for (int i = 0; i < static_cast<int>(s_.keys.size()); ++i)
    if (std::abs(s_.keys[i].time - t) <= 1e-9) return i;
  return -1;
}

std::vector<Pose> Document::key_poses() const {
  std::vector<Pose> out;
  for (const SceneKey& k : s_.keys) out.push_back(evaluate_pose(s_.rig, k.params));
  return out;
}

bool Document::has_mesh_keys() const {
  return std::any_of(s_.keys.begin(), s_.keys.end(), [](const SceneKey& k) { return k.is_mesh(); });
}

std::vector<double> Document::key_times() const {
  std::vector<double> t;
  for (const SceneKey& k : s_.keys) t.push_back(k.time);
  return t;
}

Eigen::Vector3d Document::handle_pivot(int h) const {
  const HandleRef r = handle_ref(s_.rig, h);
  switch (r.kind) {
    case HandleKind::Point: return s_.rig.points[r.index].position;
    case HandleKind::Bone: return s_.rig.skeleton.joints.row(s_.rig.skeleton.bones[r.index].a).transpose();
    case HandleKind::CageVertex: return s_.rig.cages[r.cage].mesh.V.row(r.index).transpose();
    case HandleKind::Region: {
      const Region& g = s_.rig.regions[r.index];
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (int v : g.vertices) c += s_.surface.V.row(v).transpose();
      return g.vertices.empty() ? c : Eigen::Vector3d(c / double(g.vertices.size()));
    }
  }
  return Eigen::Vector3d::Zero();
}

// ---- files -----------------------------------------------------------------------------------------

void Document::load_scene(const std::string& path) {
  SceneData d = read_scene(path);  // throws before anything changes
  s_ = std::move(d);
  path_ = path;
  weights_note_ = s_.weights.size() > 0 ? "" : "not bound yet";
  undo_.clear();
  redo_.clear();
  saved_serial_ = 0;
  gesture_merge_ok_ = false;
  after_change();
}

void Document::save_scene(const std::string& path) {
  write_scene(path, s_);
  path_ = path;
  saved_serial_ = undo_.empty() ? 0 : undo_.back()->serial;
}

std::string Document::autosave() const {
  const std::string p = autosave_path(path_.empty() ? std::string("untitled.scene.json") : path_);
  write_scene(p, s_);
  return p;
}

void Document::clear() {
  s_ = SceneData{};
  s_.pose = fit_pose_params(s_.rig, {});
  path_.clear();
  weights_note_ = "not bound yet";
  undo_.clear();
  redo_.clear();
  saved_serial_ = 0;
  gesture_merge_ok_ = false;
  after_change();
}

// ---- edits: surface and rig ------------------------------------------------------------------------

void Document::open_mesh(const std::string& path) {
  if (is_tet_mesh_path(path)) {
    TetMesh tm = read_tet_mesh(path);
    if (tm.num_tets() == 0) throw file_error(path, 0, "tet mesh has no tetrahedra");
    Eigen::VectorXi to_tet;
    TriMesh surf = tet_boundary_surface(tm, &to_tet);
    execute("open " + std::filesystem::path(path).filename().string(),
            kSurface | kRig | kPose | kKeys | kWeights | kMask, "", [&](SceneData& s) {
              s.surface = std::move(surf);
              s.surface_path = path;
              s.tets = std::move(tm);
              s.surface_to_tet = std::move(to_tet);
              s.weights.resize(0, 0);
              s.bind_stats = {};
              s.mask.resize(0);
              s.rig.regions.clear();
              s.pose = fit_pose_params(s.rig, std::move(s.pose));
              for (SceneKey& k : s.keys) k.params = fit_pose_params(s.rig, std::move(k.params));
              weights_note_ = "not bound yet";
            });
    return;
  }
  TriMesh m = read_surface(path);
  if (m.num_faces() == 0) throw file_error(path, 0, "mesh has no triangles");
  set_surface(m, path);
}

void Document::set_surface(const TriMesh& surface, const std::string& source_name) {
  if (surface.num_faces() > 0 && (surface.F.minCoeff() < 0 || surface.F.maxCoeff() >= surface.num_vertices()))
    throw Error(source_name + ": face index out of range");
  if (!surface.V.allFinite()) throw Error(source_name + ": vertex position is not finite");
  execute("open " + std::filesystem::path(source_name).filename().string(),
          kSurface | kRig | kPose | kKeys | kWeights | kMask, "", [&](SceneData& s) {
            s.surface = surface;
            s.surface_path = source_name;
            s.tets = TetMesh{};
            s.surface_to_tet.resize(0);
            s.weights.resize(0, 0);
            s.bind_stats = {};
            s.mask.resize(0);
            s.rig.regions.clear();
            s.pose = fit_pose_params(s.rig, std::move(s.pose));
            for (SceneKey& k : s.keys) k.params = fit_pose_params(s.rig, std::move(k.params));
            weights_note_ = "not bound yet";
          });
}

void Document::load_skeleton(const std::string& path) {
  const TgfData tgf = read_tgf(path);
  Rig probe = s_.rig;
  add_tgf_to_rig(probe, tgf, path);  // validates before the undo step is recorded
  rig_edit("load skeleton " + std::filesystem::path(path).filename().string(), "",
           [&](SceneData& s) { s.rig = std::move(probe); });
}

void Document::load_cage(const std::string& path) {
  Cage c;
  c.mesh = read_surface(path);
  if (c.mesh.num_vertices() == 0) throw file_error(path, 0, "cage has no vertices");
  c.name = std::filesystem::path(path).stem().string();
  add_cage(c);
}

void Document::add_cage(const Cage& cage) {
  if (!cage.mesh.V.allFinite()) throw Error("cage '" + cage.name + "': vertex position is not finite");
  const int n = cage.mesh.num_vertices();
  if (cage.mesh.num_faces() > 0 && (cage.mesh.F.minCoeff() < 0 || cage.mesh.F.maxCoeff() >= n))
    throw Error("cage '" + cage.name + "': face index out of range");
  if (cage.edges.size() > 0 && (cage.edges.minCoeff() < 0 || cage.edges.maxCoeff() >= n))
    throw Error("cage '" + cage.name + "': edge index out of range");
  // New cage vertices go after the existing ones, so their pose entries append at the end.
  const int before = num_cage_vertices(s_.rig);
  rig_edit("add cage", "", [&](SceneData& s) {
    s.rig.cages.push_back(cage);
    auto fix = [&](PoseParams& p) {
      p.cage_translation.resize(before, Eigen::Vector3d::Zero());
      p.cage_translation.insert(p.cage_translation.end(), n, Eigen::Vector3d::Zero());
    };
    fix(s.pose);
    for (SceneKey& k : s.keys) fix(k.params);
  });
}

int Document::add_point(const Eigen::Vector3d& p, const std::string& name) {
  check_finite(p, "point handle position");
  const int idx = num_point_handles(s_.rig);
  rig_edit("add point", "", [&](SceneData& s) { s.rig.points.push_back({p, name}); });
  s_.selection = Selection{{idx}, -1};
  return idx;
}

void Document::move_point(int point, const Eigen::Vector3d& p) {
  if (point < 0 || point >= num_point_handles(s_.rig)) throw Error("no point handle " + std::to_string(point));
  check_finite(p, "point handle position");
  rig_edit("move point", "move point " + std::to_string(point),
           [&](SceneData& s) { s.rig.points[point].position = p; });
}

int Document::add_bone_chain(const std::vector<Eigen::Vector3d>& joints, int parent_joint) {
  const int nj = s_.rig.skeleton.num_joints();
  if (parent_joint >= nj) throw Error("no joint " + std::to_string(parent_joint));
  const int needed = parent_joint >= 0 ? 1 : 2;
  if (static_cast<int>(joints.size()) < needed)
    throw Error("a bone chain needs at least " + std::to_string(needed) + " joint position(s)");
  for (const auto& j : joints) check_finite(j, "joint position");
  const int first_bone = s_.rig.skeleton.num_bones();
  // New bones are appended; existing bone pose entries keep their indices.
  rig_edit("add bones", "", [&](SceneData& s) {
    Skeleton& sk = s.rig.skeleton;
    Eigen::MatrixXd J(nj + joints.size(), 3);
    if (nj) J.topRows(nj) = sk.joints;
    for (size_t i = 0; i < joints.size(); ++i) J.row(nj + i) = joints[i].transpose();
    sk.joints = J;
    int prev = parent_joint;
    for (size_t i = 0; i < joints.size(); ++i) {
      const int cur = nj + static_cast<int>(i);
      if (prev >= 0) sk.bones.push_back({prev, cur, -1, ""});
      prev = cur;
    }
    compute_bone_parents(sk);
  });
  s_.selection = Selection{{num_point_handles(s_.rig) + first_bone}, -1};
  return first_bone;
}

void Document::move_joint(int joint, const Eigen::Vector3d& p) {
  if (joint < 0 || joint >= s_.rig.skeleton.num_joints()) throw Error("no joint " + std::to_string(joint));
  check_finite(p, "joint position");
  rig_edit("move joint", "move joint " + std::to_string(joint),
           [&](SceneData& s) { s.rig.skeleton.joints.row(joint) = p.transpose(); });
}

void Document::move_cage_vertex(int cage, int vertex, const Eigen::Vector3d& p) {
  if (cage < 0 || cage >= static_cast<int>(s_.rig.cages.size())) throw Error("no cage " + std::to_string(cage));
  if (vertex < 0 || vertex >= s_.rig.cages[cage].mesh.num_vertices())
    throw Error("cage " + std::to_string(cage) + " has no vertex " + std::to_string(vertex));
  check_finite(p, "cage vertex position");
  rig_edit("move cage vertex", "move cage vertex " + std::to_string(cage) + " " + std::to_string(vertex),
           [&](SceneData& s) { s.rig.cages[cage].mesh.V.row(vertex) = p.transpose(); });
}

void Document::delete_handles(std::vector<int> handles) {
  const int n = num_handles();
  for (int h : handles)
    if (h < 0 || h >= n) throw Error("no handle " + std::to_string(h));
  std::set<int> points, bones, cages, regions;
  for (int h : handles) {
    HandleRef r = handle_ref(s_.rig, h);
    switch (r.kind) {
      case HandleKind::Point: points.insert(r.index); break;
      case HandleKind::Bone: bones.insert(r.index); break;
      case HandleKind::CageVertex: cages.insert(r.cage); break;
      case HandleKind::Region: regions.insert(r.index); break;
    }
  }
  if (handles.empty()) return;
  rig_edit("delete handles", "", [&](SceneData& s) {
    Rig& rig = s.rig;
    auto each_params = [&](const std::function<void(PoseParams&)>& f) {
      f(s.pose);
      for (SceneKey& k : s.keys) f(k.params);
    };
    // Cage vertex ranges must be computed before cages are erased.
    std::vector<std::pair<int, int>> cage_ranges;  // [begin, end) in the concatenated cage vertices
    int base = 0;
    for (int c = 0; c < static_cast<int>(rig.cages.size()); ++c) {
      int nv = rig.cages[c].mesh.num_vertices();
      if (cages.count(c)) cage_ranges.push_back({base, base + nv});
      base += nv;
    }
    for (auto it = cage_ranges.rbegin(); it != cage_ranges.rend(); ++it)
      each_params([&](PoseParams& p) {
        if (static_cast<int>(p.cage_translation.size()) >= it->second)
          p.cage_translation.erase(p.cage_translation.begin() + it->first, p.cage_translation.begin() + it->second);
      });
    for (auto it = cages.rbegin(); it != cages.rend(); ++it) rig.cages.erase(rig.cages.begin() + *it);
    for (auto it = regions.rbegin(); it != regions.rend(); ++it) {
      rig.regions.erase(rig.regions.begin() + *it);
      each_params([&](PoseParams& p) { erase_at(p.region_transform, *it); });
    }
    for (auto it = points.rbegin(); it != points.rend(); ++it) {
      const int i = *it;
      rig.points.erase(rig.points.begin() + i);
      each_params([&](PoseParams& p) {
        erase_at(p.point_translation, i);
        erase_at(p.point_rotation, i);
      });
      std::vector<std::pair<int, int>> kept;
      for (auto [a, b] : rig.pseudo_edges) {
        if (a == i || b == i) continue;
        kept.push_back({a > i ? a - 1 : a, b > i ? b - 1 : b});
      }
      rig.pseudo_edges = kept;
    }
    if (!bones.empty()) {
      Skeleton& sk = rig.skeleton;
      for (auto it = bones.rbegin(); it != bones.rend(); ++it) {
        sk.bones.erase(sk.bones.begin() + *it);
        each_params([&](PoseParams& p) {
          erase_at(p.bone_rotation, *it);
          erase_at(p.bone_translation, *it);
          erase_at(p.bone_twist_stretch, *it);
        });
      }
      // Drop joints no bone uses any more.
      std::vector<int> remap(sk.num_joints(), -1);
      for (const Bone& b : sk.bones) remap[b.a] = remap[b.b] = 0;
      int k = 0;
      for (int& r : remap)
        if (r == 0) r = k++;
      Eigen::MatrixXd J(k, 3);
      for (int j = 0; j < static_cast<int>(remap.size()); ++j)
        if (remap[j] >= 0) J.row(remap[j]) = sk.joints.row(j);
      sk.joints = J;
      for (Bone& b : sk.bones) {
        b.a = remap[b.a];
        b.b = remap[b.b];
      }
      compute_bone_parents(sk);
    }
  });
  s_.selection = Selection{};
}

void Document::rename_handle(int handle, const std::string& name) {
  const HandleRef r = handle_ref(s_.rig, handle);
  // A rename changes no geometry: it must not invalidate the weights.
  execute("rename", kRig, "", [&](SceneData& s) {
    switch (r.kind) {
      case HandleKind::Point: s.rig.points[r.index].name = name; break;
      case HandleKind::Bone: s.rig.skeleton.bones[r.index].name = name; break;
      case HandleKind::CageVertex: s.rig.cages[r.cage].name = name; break;
      case HandleKind::Region: s.rig.regions[r.index].name = name; break;
    }
  });
}

void Document::add_pseudo_edge(int a, int b) {
  const int np = num_point_handles(s_.rig);
  if (a < 0 || b < 0 || a >= np || b >= np || a == b)
    throw Error("a pseudo-edge needs two different point handles (got " + std::to_string(a) + ", " +
                std::to_string(b) + ")");
  for (auto [x, y] : s_.rig.pseudo_edges)
    if ((x == a && y == b) || (x == b && y == a)) return;
  // Pseudo-edges only change rotation inference at pose time, not the weights.
  execute("add pseudo-edge", kRig, "", [&](SceneData& s) { s.rig.pseudo_edges.push_back({a, b}); });
}

void Document::remove_pseudo_edge(int a, int b) {
  auto& pe = s_.rig.pseudo_edges;
  auto it = std::find_if(pe.begin(), pe.end(), [&](auto e) {
    return (e.first == a && e.second == b) || (e.first == b && e.second == a);
  });
  if (it == pe.end()) throw Error("no pseudo-edge between points " + std::to_string(a) + " and " + std::to_string(b));
  const long at = it - pe.begin();
  execute("remove pseudo-edge", kRig, "", [&](SceneData& s) { s.rig.pseudo_edges.erase(s.rig.pseudo_edges.begin() + at); });
}

// ---- painting -------------------------------------------------------------------------------------

void Document::paint_mask(const std::vector<int>& vertices, const std::vector<double>& values) {
  const int nv = s_.surface.num_vertices();
  if (vertices.size() != values.size()) throw Error("paint mask: vertex and value counts differ");
  for (int v : vertices)
    if (v < 0 || v >= nv) throw Error("paint mask: no surface vertex " + std::to_string(v));
  for (double x : values)
    if (!std::isfinite(x)) throw Error("paint mask: value is not finite");
  if (vertices.empty()) return;
  execute("paint mask", kMask, "paint mask", [&](SceneData& s) {
    if (s.mask.size() != nv) s.mask = Eigen::VectorXd::Zero(nv);
    for (size_t i = 0; i < vertices.size(); ++i) s.mask[vertices[i]] = std::clamp(values[i], 0.0, 1.0);
  });
}

int Document::add_region(const std::string& name) {
  const int idx = static_cast<int>(s_.rig.regions.size());
  rig_edit("add region", "", [&](SceneData& s) { s.rig.regions.push_back({{}, name}); });
  s_.selection = Selection{{handle_index(s_.rig, {HandleKind::Region, idx})}, -1};
  return idx;
}

void Document::paint_region(int region, const std::vector<int>& vertices, bool erase) {
  if (region < 0 || region >= static_cast<int>(s_.rig.regions.size()))
    throw Error("no region " + std::to_string(region));
  const int nv = s_.surface.num_vertices();
  for (int v : vertices)
    if (v < 0 || v >= nv) throw Error("paint region: no surface vertex " + std::to_string(v));
  std::set<int> set(s_.rig.regions[region].vertices.begin(), s_.rig.regions[region].vertices.end());
  const size_t before = set.size();
  for (int v : vertices) erase ? (void)set.erase(v) : (void)set.insert(v);
  if (set.size() == before) return;  // nothing changed: keep the weights
  rig_edit(erase ? "erase region" : "paint region", "paint region " + std::to_string(region),
           [&](SceneData& s) { s.rig.regions[region].vertices.assign(set.begin(), set.end()); });
}

// ---- bind results and settings ---------------------------------------------------------------------

void Document::set_weights(const Eigen::MatrixXd& W, const BindStats& stats) {
  if (W.rows() != s_.surface.num_vertices() || W.cols() != num_handles())
    throw Error("weights are " + std::to_string(W.rows()) + " x " + std::to_string(W.cols()) + " but the scene has " +
                std::to_string(s_.surface.num_vertices()) + " vertices and " + std::to_string(num_handles()) +
                " handles");
  if (!W.allFinite()) throw Error("weights contain NaN or infinity");
  execute("bind", kWeights, "", [&](SceneData& s) {
    s.weights = W;
    s.bind_stats = stats;
    weights_note_.clear();
  });
}

void Document::set_bind_settings(const BindSettings& b) {
  if (b.max_influences < 0) throw Error("max influences must be >= 0");
  if (b == s_.bind_settings) return;
  execute("bind settings", kSettings, "", [&](SceneData& s) { s.bind_settings = b; });
}

void Document::set_method(SkinMethod m) {
  if (m == s_.method) return;
  execute(std::string("method ") + skin_method_name(m), kSettings, "", [&](SceneData& s) { s.method = m; });
}

void Document::set_inbetweens(int n) {
  if (n < 0 || n > 1000) throw Error("in-betweens must be in 0..1000 (got " + std::to_string(n) + ")");
  if (n == s_.inbetweens) return;
  execute("in-betweens", kSettings, "", [&](SceneData& s) { s.inbetweens = n; });
}

// ---- posing ----------------------------------------------------------------------------------------

namespace {
void check_params_fit(const Rig& rig, const PoseParams& p) {
  const size_t nb = rig.skeleton.num_bones(), np = num_point_handles(rig), nc = num_cage_vertices(rig);
  if (p.bone_rotation.size() != nb || p.bone_translation.size() != nb || p.point_translation.size() != np ||
      p.point_rotation.size() != np || p.cage_translation.size() != nc ||
      p.region_transform.size() != rig.regions.size() ||
      (!p.bone_twist_stretch.empty() && p.bone_twist_stretch.size() != nb))
    throw Error("pose parameters do not match the rig's handles");
  auto finite_q = [](const Eigen::Quaterniond& q) { return q.coeffs().allFinite() && q.norm() > 1e-12; };
  for (const auto& q : p.bone_rotation)
    if (!finite_q(q)) throw Error("pose: bone rotation is not a valid quaternion");
  for (const auto& q : p.point_rotation)
    if (!finite_q(q)) throw Error("pose: point rotation is not a valid quaternion");
  for (const auto* v : {&p.bone_translation, &p.point_translation, &p.cage_translation})
    for (const auto& x : *v)
      if (!x.allFinite()) throw Error("pose: translation is not finite");
  for (const auto& T : p.region_transform)
    if (!T.matrix().allFinite()) throw Error("pose: region transform is not finite");
}

// World rotation of a bone's parent chain (forward kinematics composes T_parent * R_b).
Eigen::Quaterniond parent_world_rotation(const Skeleton& sk, const PoseParams& p, int bone) {
  Eigen::Quaterniond R = Eigen::Quaterniond::Identity();
  for (int b = sk.bones[bone].parent; b >= 0; b = sk.bones[b].parent) R = p.bone_rotation[b].normalized() * R;
  return R;
}
}  // namespace

void Document::set_pose_params(const PoseParams& p) {
  PoseParams q = p;
  if (q.bone_twist_stretch.empty()) q.bone_twist_stretch.assign(s_.rig.skeleton.num_bones(), BoneTwistStretch{});
  check_params_fit(s_.rig, q);
  execute("pose", kPose, "pose", [&](SceneData& s) { s.pose = std::move(q); });
}

void Document::translate_handle(int handle, const Eigen::Vector3d& d) { move_handle(handle, d, s_.posing.fast); }

void Document::move_handle(int handle, const Eigen::Vector3d& d, bool solve) {
  check_finite(d, "translation");
  const HandleRef r = handle_ref(s_.rig, handle);
  execute("translate " + handle_name(s_.rig, handle), kPose, "transform " + std::to_string(handle),
          [&](SceneData& s) {
            PoseParams& p = s.pose;
            switch (r.kind) {
              case HandleKind::Point: p.point_translation[r.index] += d; break;
              case HandleKind::Bone:
                // A bone's translation lives in its parent's frame; `d` is in world space.
                p.bone_translation[r.index] += parent_world_rotation(s.rig.skeleton, p, r.index).inverse() * d;
                break;
              case HandleKind::CageVertex: {
                int base = 0;
                for (int c = 0; c < r.cage; ++c) base += s.rig.cages[c].mesh.num_vertices();
                p.cage_translation[base + r.index] += d;
                break;
              }
              case HandleKind::Region: p.region_transform[r.index].pretranslate(d); break;
            }
            if (solve) solve_fast(s);
          });
}

void Document::rotate_handle(int handle, const Eigen::Quaterniond& q_in) {
  if (!q_in.coeffs().allFinite() || q_in.norm() < 1e-12) throw Error("rotation is not a valid quaternion");
  const Eigen::Quaterniond q = q_in.normalized();
  const HandleRef r = handle_ref(s_.rig, handle);
  if (r.kind == HandleKind::CageVertex)
    throw Error("cage vertex handles only translate (" + handle_name(s_.rig, handle) + ")");
  const Eigen::Vector3d pivot = handle_pivot(handle);
  execute("rotate " + handle_name(s_.rig, handle), kPose, "transform " + std::to_string(handle),
          [&](SceneData& s) {
            PoseParams& p = s.pose;
            switch (r.kind) {
              case HandleKind::Point: p.point_rotation[r.index] = (q * p.point_rotation[r.index]).normalized(); break;
              case HandleKind::Bone: {
                // World-space rotation q of the bone = parent * (Rp^-1 q Rp) * R_b in its parent's frame.
                const Eigen::Quaterniond Rp = parent_world_rotation(s.rig.skeleton, p, r.index);
                p.bone_rotation[r.index] = (Rp.inverse() * q * Rp * p.bone_rotation[r.index]).normalized();
                break;
              }
              case HandleKind::Region: {
                Eigen::Affine3d& T = p.region_transform[r.index];
                const Eigen::Vector3d c = T * pivot;  // rotate about the region's current centroid
                T = Eigen::Translation3d(c) * q * Eigen::Translation3d(-c) * T;
                break;
              }
              case HandleKind::CageVertex: break;
            }
            if (s.posing.fast) solve_fast(s);
          });
}

void Document::reset_pose() {
  PoseParams rest = fit_pose_params(s_.rig, {});
  execute("reset pose", kPose, "", [&](SceneData& s) { s.pose = std::move(rest); });
}

std::vector<HandleConstraint> Document::handle_states() const {
  if (static_cast<int>(s_.posing.states.size()) == num_handles()) return s_.posing.states;
  return default_constraint_states(s_.rig);
}

void Document::solve_fast(SceneData& s) {
  if (!has_weights()) return;
  if (!fast_) fast_ = std::make_unique<FastPosing>();
  const std::vector<HandleConstraint> states =
      static_cast<int>(s.posing.states.size()) == dfm::num_handles(s.rig) ? s.posing.states : default_constraint_states(s.rig);
  last_fast_ = fast_->solve(s.rig, s.surface.V, s.surface.F, s.weights, states, s.posing.iterations, s.pose);
}

void Document::set_posing(const PosingSettings& p) {
  if (p.iterations < 1 || p.iterations > 1000) throw Error("FAST iterations must be in [1, 1000]");
  if (!p.states.empty() && static_cast<int>(p.states.size()) != num_handles())
    throw Error("handle states: " + std::to_string(p.states.size()) + " for " + std::to_string(num_handles()) + " handles");
  execute("posing settings", kPose, "", [&](SceneData& s) {
    s.posing = p;
    if (s.posing.fast) solve_fast(s);
  });
}

void Document::set_handle_state(int handle, HandleConstraint state) {
  if (handle < 0 || handle >= num_handles()) throw Error("no handle " + std::to_string(handle));
  PosingSettings p = s_.posing;
  p.states = handle_states();
  p.states[handle] = state;
  execute(std::string("set ") + handle_name(s_.rig, handle) + " " + constraint_state_name(state), kPose, "",
          [&](SceneData& s) {
            s.posing = p;
            if (s.posing.fast) solve_fast(s);
          });
}

void Document::drag_handle(int handle, const Eigen::Vector3d& delta) {
  if (!has_weights()) throw Error("drag: bind first (FAST solves with the weights)");
  move_handle(handle, delta, true);
}

// ---- keys ------------------------------------------------------------------------------------------

void Document::set_key(double t) {
  if (!std::isfinite(t)) throw Error("key time is not finite");
  const int at = key_at(t);
  execute(at >= 0 ? "replace key" : "set key", kKeys, "", [&](SceneData& s) {
    if (at >= 0) {
      s.keys[at].params = s.pose;
      s.keys[at].mesh = TriMesh{};  // a mesh key replaced by a pose key
      s.keys[at].mesh_path.clear();
      return;
    }
    SceneKey k{t, s.pose, {}, {}};
    auto it = std::lower_bound(s.keys.begin(), s.keys.end(), t, [](const SceneKey& a, double x) { return a.time < x; });
    s.keys.insert(it, std::move(k));
  });
}

void Document::key_mesh(const TriMesh& mesh, const std::string& path, double t) {
  if (!std::isfinite(t)) throw Error("key time is not finite");
  if (mesh.num_vertices() == 0 || mesh.num_faces() == 0) throw Error(path + ": mesh has no triangles");
  TriMesh m{mesh.V, mesh.F, {}};  // positions and triangles: the manifold needs no normals
  check_transition_key(m, path);  // throws naming the file before anything changes
  const int at = key_at(t);
  const std::string name = "key mesh " + std::filesystem::path(path).filename().string();
  execute(at >= 0 ? "replace key (" + name + ")" : name, kKeys, "", [&](SceneData& s) {
    if (at >= 0) {
      s.keys[at].mesh = std::move(m);
      s.keys[at].mesh_path = path;
      return;
    }
    SceneKey k{t, fit_pose_params(s.rig, {}), std::move(m), path};
    auto it = std::lower_bound(s.keys.begin(), s.keys.end(), t, [](const SceneKey& a, double x) { return a.time < x; });
    s.keys.insert(it, std::move(k));
  });
}

void Document::key_mesh_file(const std::string& path, double t) {
  if (!std::isfinite(t)) throw Error("key time is not finite");
  key_mesh(read_surface(path), path, t);
}

void Document::delete_key(int index) {
  if (index < 0 || index >= static_cast<int>(s_.keys.size())) throw Error("no key " + std::to_string(index));
  execute("delete key", kKeys, "", [&](SceneData& s) { s.keys.erase(s.keys.begin() + index); });
}

void Document::move_key(int index, double t) {
  if (index < 0 || index >= static_cast<int>(s_.keys.size())) throw Error("no key " + std::to_string(index));
  if (!std::isfinite(t)) throw Error("key time is not finite");
  const int other = key_at(t);
  if (other >= 0 && other != index) throw Error("a key already sits at time " + std::to_string(t));
  execute("move key", kKeys, "move key", [&](SceneData& s) {
    s.keys[index].time = t;
    std::stable_sort(s.keys.begin(), s.keys.end(), [](const SceneKey& a, const SceneKey& b) { return a.time < b.time; });
  });
}

void Document::go_to_key(int index) {
  if (index < 0 || index >= static_cast<int>(s_.keys.size())) throw Error("no key " + std::to_string(index));
  if (s_.keys[index].is_mesh())
    throw Error("key " + std::to_string(index) + " is a mesh key (" + s_.keys[index].mesh_path + "): it has no pose");
  PoseParams p = s_.keys[index].params;
  execute("go to key", kPose, "", [&](SceneData& s) { s.pose = std::move(p); });
}

// ---- view state ------------------------------------------------------------------------------------

void Document::set_time(double t) {
  if (!std::isfinite(t)) throw Error("time is not finite");
  s_.time = t;
}

void Document::set_camera(const Camera& c) {
  if (!c.position.allFinite() || !c.target.allFinite() || !c.up.allFinite() || !std::isfinite(c.fov_deg))
    throw Error("camera is not finite");
  s_.camera = c;
}

void Document::set_selection(const Selection& sel) {
  const int n = num_handles();
  for (int h : sel.handles)
    if (h < 0 || h >= n) throw Error("no handle " + std::to_string(h) + " (the scene has " + std::to_string(n) + ")");
  if (sel.joint >= s_.rig.skeleton.num_joints()) throw Error("no joint " + std::to_string(sel.joint));
  s_.selection = sel;
}

}  // namespace dfm
