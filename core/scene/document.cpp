// The document: undo machinery, queries, files, bind results and view state (document.h). The commands
// on the surface and rig live in document_rig.cpp, posing and keys in document_posing.cpp.
#include "core/scene/document.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/rig/additional_handles.h"
#include "core/scene/document_parts.h"
#include "core/scene/scene_file.h"
#include "core/scene/scene_import.h"
#include "core/skin/stbs.h"
#include "core/util/error.h"

namespace dfm {

bool Camera::operator==(const Camera& o) const {
  return position == o.position && target == o.target && up == o.up && fov_deg == o.fov_deg && ortho == o.ortho;
}
bool BindSettings::operator==(const BindSettings& o) const {
  return volume == o.volume && max_influences == o.max_influences && monotone == o.monotone &&
         additional_weights == o.additional_weights;
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

// ---- undo machinery ------------------------------------------------------------------------------


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
  if (parts & 8u) swap(a.keys, b.keys), swap(a.space_time_edits, b.space_time_edits);
  if (parts & 16u) {
    swap(a.weights, b.weights);
    swap(a.replaced_weights, b.replaced_weights);
    swap(a.endpoint_weights, b.endpoint_weights);
    swap(a.additional_weights, b.additional_weights);
    swap(a.bind_stats, b.bind_stats);
  }
  if (parts & 32u) swap(a.mask, b.mask);
  if (parts & 64u) {
    swap(a.method, b.method);
    swap(a.endpoint_filters, b.endpoint_filters);
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
  if (parts & 8u) to.keys = from.keys, to.space_time_edits = from.space_time_edits;
  if (parts & 16u) {
    to.weights = from.weights;
    to.replaced_weights = from.replaced_weights;
    to.endpoint_weights = from.endpoint_weights;
    to.additional_weights = from.additional_weights;
    to.bind_stats = from.bind_stats;
  }
  if (parts & 32u) to.mask = from.mask;
  if (parts & 64u) {
    to.method = from.method;
    to.endpoint_filters = from.endpoint_filters;
    to.bind_settings = from.bind_settings;
    to.inbetweens = from.inbetweens;
  }
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
  after_change(parts);
}

void Document::rig_edit(const std::string& name, const std::string& merge_target,
                        const std::function<void(SceneData&)>& edit) {
  execute(name, kRig | kPose | kKeys | kWeights | kSettings, merge_target, [&](SceneData& s) {
    const int bones = s.rig.skeleton.num_bones();
    // The additional handles' transforms sit past the rig's (additional_handles.h): new handles would
    // take their indices, and their weights are cleared below anyway.
    drop_additional_transforms(s.pose, dfm::num_handles(s.rig));
    for (SceneKey& k : s.keys) drop_additional_transforms(k.params, dfm::num_handles(s.rig));
    edit(s);
    // Filters follow bone numbers: new bones are appended (no filter); a deletion renumbers, so clears them.
    if (s.rig.skeleton.num_bones() < bones) s.endpoint_filters.clear();
    s.pose = fit_pose_params(s.rig, std::move(s.pose));
    for (SceneKey& k : s.keys) k.params = fit_pose_params(s.rig, std::move(k.params));
    if (s.weights.size() > 0) {
      s.weights.resize(0, 0);
      s.replaced_weights.resize(0, 0);
      s.endpoint_weights.resize(0, 0);
      s.additional_weights.resize(0, 0);
      s.bind_stats = {};
      weights_note_ = "rig changed after bind (" + name + "): weights cleared, bind again";
    }
  });
}

void Document::touch_top_step() {
  if (!undo_.empty()) undo_.back()->serial = next_serial_++;
}

void Document::after_change(unsigned parts) {
  ++revision_;
  dyn_live_ = dyn_keep_;  // any edit but a dynamics step ends the live simulation
  dyn_keep_ = false;
  if (parts & (kSurface | kWeights)) ++surface_weights_revision_;
  if (parts & (kSurface | kRig)) ++surface_rig_revision_;
  if (parts & (kSurface | kRig | kWeights | kSettings)) ++skin_inputs_revision_;
  if (parts & kSurface) sculpt_clear();  // the session's vertices belong to the old surface
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
  after_change(to.back()->parts);
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
  start_document(std::move(d), path);
}

std::string Document::import_scene(const std::string& path) {
  const SceneImporter* import = scene_importer_for(path);
  if (!import) throw Error(path + ": no importer reads this kind of file");
  std::string report;
  SceneData d = (*import)(path, report);  // throws before anything changes
  start_document(std::move(d), "");
  return report;
}

std::string Document::load_motion(const std::string& path) {
  const MotionImporter* import = motion_importer_for(path);
  if (!import) throw Error(path + ": no importer reads motion from this kind of file");
  if (s_.rig.skeleton.num_bones() == 0) throw Error(path + ": motion needs bones to drive (the scene has none)");
  std::string report;
  std::vector<SceneKey> keys = (*import)(s_, path, report);  // throws before anything changes
  execute("motion " + std::filesystem::path(path).filename().string(), kKeys | kPose, "", [&](SceneData& s) {
    s.keys = std::move(keys);
    s.pose = rest_pose_params(s.rig);
  });
  return report;
}

void Document::start_document(SceneData d, const std::string& path) {
  s_ = std::move(d);
  path_ = path;
  weights_note_ = s_.weights.size() > 0 ? "" : "not bound yet";
  undo_.clear();
  redo_.clear();
  saved_serial_ = 0;
  gesture_merge_ok_ = false;
  if (fast_) fast_->invalidate();
  after_change();
}

std::string Document::title() const {
  if (!path_.empty()) return path_;
  return s_.surface_path.empty() ? std::string("untitled") : s_.surface_path;
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
  SceneData d;
  d.pose = fit_pose_params(d.rig, {});
  start_document(std::move(d), "");
}

// ---- bind results and settings ---------------------------------------------------------------------

void Document::set_weights(const Eigen::MatrixXd& W, const BindStats& stats, const Eigen::MatrixXd& endpoints,
                           const Eigen::MatrixXd& additional) {
  if (W.rows() != s_.surface.num_vertices() || W.cols() != num_handles())
    throw Error("weights are " + std::to_string(W.rows()) + " x " + std::to_string(W.cols()) + " but the scene has " +
                std::to_string(s_.surface.num_vertices()) + " vertices and " + std::to_string(num_handles()) +
                " handles");
  if (!W.allFinite()) throw Error("weights contain NaN or infinity");
  if (endpoints.size() > 0 &&
      (endpoints.rows() != W.rows() || endpoints.cols() != s_.rig.skeleton.num_bones() || !endpoints.allFinite() ||
       endpoints.minCoeff() < 0 || endpoints.maxCoeff() > 1))
    throw Error("endpoint weights must be #V x #bones (" + std::to_string(W.rows()) + " x " +
                std::to_string(s_.rig.skeleton.num_bones()) + ") in [0, 1], got " + std::to_string(endpoints.rows()) +
                " x " + std::to_string(endpoints.cols()));
  if (additional.size() > 0 && (additional.rows() != W.rows() || !additional.allFinite()))
    throw Error("additional weights must be #V x k (" + std::to_string(W.rows()) + " rows) and finite, got " +
                std::to_string(additional.rows()) + " x " + std::to_string(additional.cols()));
  execute("bind", kWeights | kPose | kKeys, "", [&](SceneData& s) {
    const bool same_shape = s.weights.rows() == W.rows() && s.weights.cols() == W.cols();
    // Solved transforms belong to the weight functions they were solved for: new additional weights
    // start unsolved (zero, additional_handles.h) in the pose and every key, until FAST solves them.
    const bool same_additional = s.additional_weights.rows() == additional.rows() &&
                                 s.additional_weights.cols() == additional.cols() && s.additional_weights == additional;
    if (!same_additional) {
      drop_additional_transforms(s.pose, dfm::num_handles(s.rig));
      for (SceneKey& k : s.keys) drop_additional_transforms(k.params, dfm::num_handles(s.rig));
    }
    s.replaced_weights = same_shape ? std::move(s.weights) : Eigen::MatrixXd();
    s.weights = W;
    s.endpoint_weights = endpoints;
    s.additional_weights = additional;
    s.bind_stats = stats;
    weights_note_.clear();
  });
}

void Document::set_bind_settings(const BindSettings& b) {
  if (b.max_influences < 0) throw Error("max influences must be >= 0");
  if (b.additional_weights < 0 || b.additional_weights > kMaxAdditionalWeights)
    throw Error("additional weights must be in 0.." + std::to_string(kMaxAdditionalWeights) + ", got " +
                std::to_string(b.additional_weights));
  if (b == s_.bind_settings) return;
  execute("bind settings", kSettings, "", [&](SceneData& s) { s.bind_settings = b; });
}

void Document::set_method(SkinMethod m) {
  if (m == s_.method) return;
  execute(std::string("method ") + skin_method_name(m), kSettings, "", [&](SceneData& s) { s.method = m; });
}

void Document::set_endpoint_filter(int bone, const EndpointFilter& filter) {
  const int nb = s_.rig.skeleton.num_bones();
  if (bone < 0 || bone >= nb) throw Error("no bone " + std::to_string(bone) + " (the rig has " + std::to_string(nb) + ")");
  const std::string name = handle_name(s_.rig, num_point_handles(s_.rig) + bone);
  check_endpoint_filter(filter, "endpoint filter of " + name);
  execute("endpoint filter " + name, kSettings, "endpoint filter " + std::to_string(bone), [&](SceneData& s) {
    if (static_cast<int>(s.endpoint_filters.size()) < nb) s.endpoint_filters.resize(nb);
    s.endpoint_filters[bone] = filter;
  });
}

const Eigen::MatrixXd& Document::skin_endpoints() const {
  const bool filtered = std::any_of(s_.endpoint_filters.begin(), s_.endpoint_filters.end(),
                                    [](const EndpointFilter& f) { return !f.empty(); });
  if (!filtered) return s_.endpoint_weights;
  if (endpoints_revision_ != skin_inputs_revision_) {
    const Eigen::MatrixXd E = s_.endpoint_weights.size() > 0
                                  ? s_.endpoint_weights
                                  : Eigen::MatrixXd(bone_endpoint_weights(s_.surface.V, s_.rig)
                                                        .middleCols(num_point_handles(s_.rig), s_.rig.skeleton.num_bones()));
    endpoints_ = filter_endpoints(E, s_.endpoint_filters);
    endpoints_revision_ = skin_inputs_revision_;
  }
  return endpoints_;
}

const Eigen::MatrixXd& Document::skin_weights() const {
  if (num_additional() == 0) return s_.weights;
  if (skin_weights_revision_ != skin_inputs_revision_) {
    skin_weights_ = with_additional_weights(s_.weights, s_.additional_weights);
    skin_weights_revision_ = skin_inputs_revision_;
  }
  return skin_weights_;
}

Pose Document::skin_pose(const PoseParams& params) const { return dfm::skin_pose(s_.rig, params, num_additional()); }

void Document::set_inbetweens(int n) {
  if (n < 0 || n > 1000) throw Error("in-betweens must be in 0..1000 (got " + std::to_string(n) + ")");
  if (n == s_.inbetweens) return;
  execute("in-betweens", kSettings, "", [&](SceneData& s) { s.inbetweens = n; });
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
