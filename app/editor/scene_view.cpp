#include "app/editor/scene_view.h"

#include "core/scene/key_pairs.h"

#include "core/util/hash.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "app/editor/manifold_builder.h"
#include "app/editor/interval_prefetch.h"
#include "app/editor/slice_cache.h"
#include "app/editor/view_model.h"
#include "core/anim/interpolate.h"
#include "core/scene/key_surfaces.h"
#include "core/anim/interval_slice.h"
#include "core/anim/keyframes.h"
#include "core/anim/manifold.h"
#include "core/anim/manifold_normals.h"
#include "core/anim/slice.h"
#include "core/anim/slice_table.h"
#include "core/bind/weight_difference.h"
#include "core/mesh/mesh_info.h"
#include "core/rig/forward_kinematics.h"
#include "core/skin/skin.h"
#include "core/skin/stbs.h"

namespace dfm::editor {

namespace {
// No surface (an empty document, a file that failed to open): the grid lies about the origin, 2 units
// wide, and framing fits it.
const Eigen::AlignedBox3d kEmptyBox(Eigen::Vector3d(-1, 0, -1), Eigen::Vector3d(1, 0, 1));
}  // namespace

// Posing and slicing on the GPU (through the backend): the skin pass writes the posed surface (LBS/DQS/STBS in the vertex
// shader) and, with two or more keys, the slice pass cuts the animation manifold at the current time.
// The manifold is built on the CPU exactly as the saved frames are (key_surfaces: same track,
// inbetweens, method, mesh keys), and rebuilt only when the keys, weights or method change.
// A time slice inside an interval between consecutive distinct vertex times is drawn from that
// interval's cached topology (an interpolation in the vertex shader, welded, costing what posing
// costs); IntervalCachePolicy (slice_cache.h) says when the general per-tetrahedron pass runs instead.
struct SceneView::Deformer {
  // What the skin was bound from, compared by value when the revision changes: a re-bind writes
  // weights of the same size into the same storage, so their address says nothing.
  Eigen::MatrixXd skin_W, skin_E, skin_V;
  Eigen::MatrixXi skin_F;
  int k = 0;
  std::uint64_t skin_revision = ~0ull;
  std::unique_ptr<gl::SkinDeformer> skin;
  // The animation manifold (its signature covers key times, poses and meshes, weights, method).
  ManifoldBuilder builder;
  std::unique_ptr<gl::ManifoldSlicer> slice;
  // The general pass's positions predate the manifold (a drag frame drawn from the interval cache):
  // uploaded when that pass next slices, so a drag frame converts and uploads only the shown interval.
  bool slice_stale = false;
  std::shared_ptr<const Eigen::MatrixXd> normals4;  // the manifold's unit 4D vertex normals
  IntervalCachePolicy interval_policy{4};
  std::vector<std::unique_ptr<gl::IntervalSlicer>> interval_slots;  // one per policy slot
  std::vector<bool> slot_closed;  // per slot: its topology's closed_outward
  // Per slot: the topology it holds, and whether its positions predate the manifold (re-uploaded from
  // the topology when next shown: a manifold with the same tetrahedra and times cuts the same way).
  std::vector<std::shared_ptr<const IntervalSlice>> slot_topology;
  std::vector<bool> slot_stale;
  std::shared_ptr<const AnimationManifold> cut;  // the manifold the interval topologies were cut from
  IntervalPrefetch prefetch;  // the interval playback reaches next, built on a worker
  int shown_slot = -1;  // the interval slot on display, -1 for the general pass
  bool have_slice_time = false;  // the last frame was a time slice at slice_time
  double slice_time = 0;
  double interval_build_ms = 0;  // total for the current manifold
  bool has_manifold = false;
  std::uint64_t pose_sig = 0;
  bool prefer_pose = false;  // the pose was edited after the last time change: show it, not the slice
  bool gpu_output_stale = true;  // display_V_ must be read back before CPU use
};

namespace {
std::uint64_t pose_hash(std::uint64_t h, const Pose& p) {
  for (const auto& T : p.transforms) h = fnv1a(h, T.matrix().data(), sizeof(double) * 16);
  return h;
}
}  // namespace

SceneView::SceneView(gl::RenderBackend& gpu) : gpu_(gpu), deformer_(std::make_unique<Deformer>()) {}
SceneView::~SceneView() = default;

void SceneView::add_overlay_lines(const std::vector<gl::OverlayVertex>& pairs, float width) {
  extra_lines_.insert(extra_lines_.end(), pairs.begin(), pairs.end());
  extra_line_widths_.insert(extra_line_widths_.end(), pairs.size() / 2, width);
}

void SceneView::add_overlay_points(const std::vector<gl::OverlayVertex>& points, float size) {
  extra_points_.insert(extra_points_.end(), points.begin(), points.end());
  extra_point_size_ = size;
}

void SceneView::sync(const Document& doc, const ViewSettings& s) {
  const bool content = doc.revision() != synced_revision_;
  const bool time_changed = doc.time() != synced_time_;
  const bool settings_changed = s.weight_view != synced_settings_.weight_view ||
                                s.slice_axis != synced_settings_.slice_axis ||
                                s.sweep_value != synced_settings_.sweep_value;
  const bool sel_changed = doc.selection().handles != synced_selection_;
  if (time_changed) deformer_->prefer_pose = false;
  // While the manifold builds on its worker, keep polling it (the result uploads when it lands).
  if (content || time_changed || settings_changed || surface_requested_ || deformer_->builder.busy())
    update_surface(doc, s);
  surface_requested_ = false;
  // A sculpt session shows its result over the document's frame, re-uploaded when the session changes.
  const SculptSession* sculpt = doc.sculpt();
  bool sculpt_changed = false;
  if (sculpt && (sculpt->revision != shown_sculpt_ || !showing_preview_)) {
    show_preview(TriMesh{sculpt->result, sculpt->base.F, {}});
    shown_sculpt_ = sculpt->revision;
    sculpt_changed = true;
  } else if (!sculpt && shown_sculpt_ != 0) {
    shown_sculpt_ = 0;
    sculpt_changed = true;
    if (showing_preview_) {
      showing_preview_ = false;
      update_surface(doc, s);
    }
  }
  if (content || time_changed || settings_changed || sel_changed || sculpt_changed || !colors_valid_ ||
      s.sculpt_colors != synced_settings_.sculpt_colors)
    update_colors(doc, s);
  update_handles(doc, s);
  overlay_opacity_ = showing_slice_ && s.slice_axis == SliceAxis::T ? rig_overlay_opacity(doc, doc.time()) : 1.0f;
  synced_revision_ = doc.revision();
  synced_time_ = doc.time();
  synced_settings_ = s;
  synced_selection_ = doc.selection().handles;
}

const Eigen::MatrixXd& SceneView::display_vertices() {
  Deformer& d = *deformer_;
  if (d.gpu_output_stale && !display_is_rest_) {
    std::vector<gl::PosNormal> v;
    const bool cached = showing_slice_ && d.shown_slot >= 0;
    if (cached) v = d.interval_slots[d.shown_slot]->read_back();
    else if (showing_slice_ && d.slice) v = d.slice->read_back();
    else if (d.skin) v = d.skin->read_back();
    display_V_.resize(v.size(), 3);
    for (size_t i = 0; i < v.size(); ++i) display_V_.row(i) << v[i].position[0], v[i].position[1], v[i].position[2];
    if (cached) {
      display_F_ = d.interval_slots[d.shown_slot]->faces();
    } else if (showing_slice_) {
      display_F_.resize(v.size() / 3, 3);
      for (int f = 0; f < display_F_.rows(); ++f) display_F_.row(f) << 3 * f, 3 * f + 1, 3 * f + 2;
    }
  }
  d.gpu_output_stale = false;
  return display_V_;
}

const Eigen::MatrixXi& SceneView::display_faces() {
  display_vertices();  // a slice's faces come with its vertices
  return display_F_;
}

bool SceneView::surface_closed(const Document& doc) {
  const TriMesh& s = doc.surface();
  ClosedCache& c = surface_closed_;
  if (c.revision != doc.surface_weights_revision() || c.faces != s.F.data() || c.rows != s.F.rows()) {
    c = {doc.surface_weights_revision(), s.F.data(), s.F.rows(), is_closed_outward(s.V, s.F)};
  }
  return c.closed;
}

void SceneView::show_rest(const TriMesh& rest, bool closed) {
  display_closed_ = closed;
  display_V_ = rest.V;
  display_F_ = rest.F;
  display_is_rest_ = true;
  showing_slice_ = false;
  showing_animation_pose_ = false;
  display_count_ = rest.num_vertices();
  display_faces_ = rest.num_faces();
  gpu_.show_mesh(rest);
}

namespace {
bool pose_keys_only(const Document& doc) {
  for (const SceneKey& k : doc.keys())
    if (k.is_mesh()) return false;
  return true;
}
}  // namespace

void SceneView::update_surface(const Document& doc, const ViewSettings& s) {
  Deformer& d = *deformer_;
  showing_preview_ = false;
  const TriMesh& rest = doc.surface();
  error_.clear();
  bounds_.setEmpty();
  for (int i = 0; i < rest.V.rows(); ++i) bounds_.extend(Eigen::Vector3d(rest.V.row(i)));
  try {
    update_skin(doc);
    // Animation manifold (>= 2 keys, pose keys baked, mesh keys as they are), rebuilt when what it is
    // made of changes; one with a transition builds on a worker (the pose or rest shows meanwhile).
    if (d.builder.update(doc)) {
      if (!d.slice) d.slice = gpu_.make_slicer();
      const AnimationManifold& m = d.builder.manifold();
      d.normals4 = d.builder.normals();
      // A space-time drag frame (or any change that keeps the tetrahedra and every t) cuts each interval
      // the same way: the cached topologies stay, their positions re-upload when shown, and the general
      // slicer takes the new positions and normals only, when it next slices.
      const bool same_cut = d.cut && (d.builder.positions_only() ||
                                      (d.cut->times == m.times && d.cut->T.rows() == m.T.rows() && d.cut->V.rows() == m.V.rows() &&
                                       d.cut->V.col(3) == m.V.col(3) && d.cut->T == m.T));
      d.cut = d.builder.shared_manifold();
      if (!same_cut) d.slice->upload(m, *d.normals4);
      d.slice_stale = same_cut;
      if (same_cut) {
        d.slot_stale.assign(d.interval_slots.size(), true);
        d.prefetch.reset(d.cut, d.normals4, d.interval_policy.times());
      } else {
        const std::vector<double> vertex_times = manifold_vertex_times(m);
        d.interval_policy.reset(vertex_times, prism_intervals(m, vertex_times));
        d.prefetch.reset(d.cut, d.normals4, d.interval_policy.times());
        d.interval_slots.clear();
        d.interval_slots.resize(d.interval_policy.capacity());
        d.slot_closed.assign(d.interval_policy.capacity(), false);
        d.slot_topology.assign(d.interval_policy.capacity(), nullptr);
        d.slot_stale.assign(d.interval_policy.capacity(), false);
        d.interval_build_ms = 0;
      }
      d.shown_slot = -1;
      d.have_slice_time = false;
    }
    d.has_manifold = d.builder.has_manifold();
    error_ = d.builder.error();
    for (const std::string& n : d.builder.edit_notes()) error_ += (error_.empty() ? "" : "; ") + n;
    // Pose edits after the last scrub show the pose being edited; scrubbing shows the slice.
    const Pose pose = doc.pose();
    const std::uint64_t psig = pose_hash(kFnv1aBasis, pose);
    if (psig != d.pose_sig) {
      if (d.pose_sig != 0) d.prefer_pose = true;
      d.pose_sig = psig;
    }
    // A weight view on an animation of pose keys shows the animation skinned (the slice's vertices are
    // not the weights'): the same frame, up to the baked in-betweens' interpolation.
    const bool animate_skin = d.has_manifold && s.slice_axis == SliceAxis::T && !d.prefer_pose && d.skin &&
                              s.weight_view != WeightView::Off && pose_keys_only(doc);
    if (d.has_manifold && !animate_skin && (s.slice_axis != SliceAxis::T || !d.prefer_pose || !d.skin)) {
      show_slice(doc, s);
    } else if (d.skin) {
      const PoseParams params = animate_skin ? animation_params(doc, doc.time()) : doc.pose_params();
      d.skin->set_pose(doc.skin_pose(params),  // the additional handles' transforms too
                       stbs_handles(doc.rig(), params.bone_twist_stretch));
      d.skin->run(doc.method());
      showing_animation_pose_ = animate_skin;
      const gl::GeometryRef g = d.skin->output();
      gpu_.show_geometry(g);
      display_closed_ = surface_closed(doc);  // a pose keeps the rest's triangles
      display_count_ = g.vertex_count;
      display_faces_ = g.index_count / 3;
      showing_slice_ = false;
      d.shown_slot = -1;
      d.have_slice_time = false;
      display_F_ = rest.F;
    } else {
      show_rest(rest, surface_closed(doc));
      colors_valid_ = false;
      return;
    }
    display_is_rest_ = false;
    d.gpu_output_stale = true;
  } catch (const std::exception& e) {
    error_ = e.what();
    show_rest(rest, surface_closed(doc));
  }
  colors_valid_ = false;
}

namespace {
// GPU memory the interval cache may hold: a looping playback of every interval then uploads each once.
constexpr double kIntervalCacheBytes = 256.0 * (1 << 20);
constexpr int kMaxIntervalSlots = 64;
}  // namespace

// Enough slots for every interval of the manifold, as far as kIntervalCacheBytes allows for intervals
// the size of this one (at least the 4 it starts with).
void SceneView::grow_interval_cache(Deformer& d, const IntervalSlice& built) {
  const double bytes = built.num_vertices() * double(sizeof(gl::IntervalVertex)) + built.F.size() * 4.0;
  const int intervals = static_cast<int>(d.interval_policy.times().size()) - 1;
  const int fit = bytes > 0 ? static_cast<int>(std::min(kIntervalCacheBytes / bytes, double(kMaxIntervalSlots))) : 0;
  d.interval_policy.grow(std::min(intervals, fit));
  d.interval_slots.resize(d.interval_policy.capacity());
  d.slot_closed.resize(d.interval_policy.capacity(), false);
  d.slot_topology.resize(d.interval_policy.capacity());
  d.slot_stale.resize(d.interval_policy.capacity(), false);
}

// The manifold's slice on display: a time inside a cached (or worth caching) interval by
// interpolation, anything else by the general pass (IntervalCachePolicy, slice_cache.h).
void SceneView::show_slice(const Document& doc, const ViewSettings& s) {
  Deformer& d = *deformer_;
  const AnimationManifold& m = d.builder.manifold();
  const SliceAxis axis = s.slice_axis;
  double value = doc.time();
  // Before the first key and after the last the frame holds, as posed_surface and glTF sampling do.
  const std::vector<double>& span = d.interval_policy.times();
  if (axis == SliceAxis::T && !span.empty()) value = std::clamp(value, span.front(), span.back());
  if (axis != SliceAxis::T) {
    const int c = static_cast<int>(axis);
    const double lo = m.V.col(c).minCoeff(), hi = m.V.col(c).maxCoeff();
    value = lo + s.sweep_value * (hi - lo);
  }
  const bool time_axis = axis == SliceAxis::T;
  const double step = time_axis && d.have_slice_time ? value - d.slice_time : 0.0;
  SliceDecision route = d.interval_policy.choose(time_axis, value, step);
  if (route.route == SliceRoute::Build) {
    const auto b0 = std::chrono::steady_clock::now();
    try {
      const auto& times = d.interval_policy.times();
      std::optional<PreparedInterval> ready = d.prefetch.take(route.interval);
      auto topology = std::make_shared<const IntervalSlice>(
          ready ? std::move(ready->topology)
                : build_interval_slice(m, *d.normals4, times[route.interval], times[route.interval + 1]));
      auto& slot = d.interval_slots[route.slot];
      if (!slot) slot = gpu_.make_interval_slicer();
      slot->upload(*topology, m, *d.normals4, ready ? &ready->records : nullptr);
      d.slot_closed[route.slot] = topology->closed_outward;
      d.slot_topology[route.slot] = topology;
      d.slot_stale[route.slot] = false;
      grow_interval_cache(d, *topology);
    } catch (const std::exception&) {  // not a clean interval: the general pass draws it
      d.interval_policy.forget(route.slot);
      route = SliceDecision{};
    }
    d.interval_build_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - b0).count();
  }
  if (route.route != SliceRoute::General && d.slot_stale[route.slot] && d.slot_topology[route.slot]) {
    // Cut before this manifold's positions (a drag frame): the same topology, new positions.
    const auto b0 = std::chrono::steady_clock::now();
    d.interval_slots[route.slot]->upload(*d.slot_topology[route.slot], m, *d.normals4, nullptr);
    d.slot_stale[route.slot] = false;
    d.interval_build_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - b0).count();
  }
  if (route.route != SliceRoute::General) {
    gl::IntervalSlicer& slot = *d.interval_slots[route.slot];
    slot.evaluate(value);
    const gl::GeometryRef g = slot.output();
    gpu_.show_geometry(g);
    display_closed_ = d.slot_closed[route.slot];
    display_count_ = g.vertex_count;
    display_faces_ = static_cast<int>(slot.faces().rows());
    d.shown_slot = route.slot;
  } else {
    if (d.slice_stale) d.slice->upload_vertices(m, *d.normals4);
    d.slice_stale = false;
    const int tris = d.slice->slice(axis, value);
    gpu_.show_geometry(d.slice->output());
    display_closed_ = false;  // a triangle soup: no edges to check
    display_count_ = -1;  // welded on demand (display_vertex_count), not the soup's 3 corners a face
    general_axis_ = axis;
    general_value_ = value;
    display_faces_ = tris;
    d.shown_slot = -1;
  }
  d.have_slice_time = time_axis;
  d.slice_time = value;
  showing_slice_ = true;
  showing_animation_pose_ = false;
  // Playing on: the interval after this one builds meanwhile, unless it is cached or too short.
  const int here = time_axis ? open_interval_of(d.interval_policy.times(), value) : -1;
  if (here >= 0) {
    const int next = d.interval_policy.next_interval(here, step);
    if (!d.interval_policy.cached(next) && d.interval_policy.worth_building(next, step)) d.prefetch.request(next);
  }
}

// The GPU skin pass of the bound weights; none without weights (the rest surface shows then).
void SceneView::update_skin(const Document& doc) {
  Deformer& d = *deformer_;
  const TriMesh& rest = doc.surface();
  if (!doc.has_weights() || rest.num_vertices() == 0) {
    d.skin.reset();
    return;
  }
  if (d.skin && doc.revision() == d.skin_revision) return;
  const Eigen::MatrixXd& W = doc.skin_weights();  // with the additional weights' columns (the cache's key)
  // Every weight the bind computed (sparse rows on the GPU), unless the scene prunes to k.
  const int k = doc.bind_settings().max_influences;
  auto same = [](const auto& a, const auto& b) { return a.rows() == b.rows() && a.cols() == b.cols() && a == b; };
  const Eigen::MatrixXd& E = doc.skin_endpoints();
  const bool same_binding = d.skin && k == d.k && same(W, d.skin_W) && same(E, d.skin_E);
  if (!same_binding || !same(rest.V, d.skin_V) || !same(rest.F, d.skin_F)) {
    d.skin.reset();  // if the binding below throws, none: the rest shows with the error, and it is retried
    d.skin = gpu_.make_skin(make_skin_binding(rest.V, vertex_normals(rest.V, rest.F), doc.weights(), doc.rig(), k, E,
                                              doc.additional_weights()),
                            rest.F);
    d.skin_W = W;
    d.skin_E = E;
    d.skin_V = rest.V;
    d.skin_F = rest.F;
    d.k = k;
  }
  d.skin_revision = doc.revision();
}

int SceneView::display_vertex_count() const {
  if (display_count_ < 0) {
    display_count_ = deformer_->has_manifold
                         ? dfm::welded_slice_vertex_count(deformer_->builder.manifold(), general_axis_, general_value_)
                         : 0;
  }
  return display_count_;
}

bool SceneView::slice_from_cache() const { return showing_slice_ && deformer_->shown_slot >= 0; }
int SceneView::intervals_built() const { return deformer_->interval_policy.builds(); }
double SceneView::interval_build_ms() const { return deformer_->interval_build_ms; }
int SceneView::vertex_time_count() const { return static_cast<int>(deformer_->interval_policy.times().size()); }

bool SceneView::manifold_building() const { return deformer_->builder.busy(); }
const KeyPlacement* SceneView::pair_placement(const Document& doc) const {
  if (doc.keys().size() < 2) return nullptr;
  return deformer_->builder.transition_placement_from(doc.keys()[pair_interval(doc, doc.time())].time);
}
std::string SceneView::manifold_progress() const { return deformer_->builder.progress_text(); }

Eigen::AlignedBox3d SceneView::framing_bounds() const {
  Eigen::AlignedBox3d b = bounds_;
  for (const Eigen::MatrixXd* P : {&handle_pos_, &joint_pos_})
    for (int i = 0; i < P->rows(); ++i) b.extend(Eigen::Vector3d(P->row(i)));
  return b.isEmpty() ? kEmptyBox : b;
}

Pose SceneView::shown_pose(const Document& doc) const { return pose_on_screen(doc, synced_settings_.slice_axis); }

Pose SceneView::pose_on_screen(const Document& doc, SliceAxis axis) const {
  // A time slice shows the animation: the key poses interpolated at the time (core's animation_pose).
  if ((showing_slice_ || showing_animation_pose_) && axis == SliceAxis::T && deformer_->builder.track().size() >= 2) {
    try {
      return animation_pose(doc, doc.time());
    } catch (...) {
    }
  }
  return doc.pose();
}

void SceneView::update_colors(const Document& doc, const ViewSettings& s) {
  colors_valid_ = true;
  const int nv = doc.surface().num_vertices();
  const SculptSession* sculpt = doc.sculpt();
  const bool same_vertices = !showing_slice_ && (!sculpt || static_cast<int>(sculpt->region.size()) == nv);
  std::vector<Eigen::Vector4f> data;
  if (s.sculpt_colors && sculpt && showing_preview_) {
    data.assign(sculpt->region.size(), Eigen::Vector4f(0, 0, 0, 1));
    for (size_t v = 0; v < data.size(); ++v)
      if (sculpt->region[v]) data[v].x() = 0.55f;
    for (int v : sculpt->handle) data[v].x() = 1.0f;
  } else if (same_vertices && s.weight_view == WeightView::Selected && doc.has_weights() && !doc.selection().handles.empty()) {
    const int h = doc.selection().handles.front();
    if (h >= 0 && h < doc.weights().cols()) {
      data.resize(nv);
      for (int i = 0; i < nv; ++i) data[i] = Eigen::Vector4f(float(doc.weights()(i, h)), 0, 0, 1);
    }
  } else if (same_vertices && s.weight_view == WeightView::AllHandles && doc.has_weights()) {
    data = blend_handle_colors(doc.weights());
  } else if (same_vertices && s.weight_view == WeightView::Difference && doc.has_weights() &&
             doc.replaced_weights().rows() == doc.weights().rows() && doc.replaced_weights().cols() == doc.weights().cols()) {
    const int h = doc.selection().handles.empty() ? -1 : doc.selection().handles.front();
    const Eigen::VectorXd d = weight_difference(doc.weights(), doc.replaced_weights(), h);
    data.resize(nv);
    for (int i = 0; i < nv; ++i) data[i] = Eigen::Vector4f(float(d[i]), 0, 0, 1);
  } else if (same_vertices && s.weight_view == WeightView::Mask) {
    data.assign(nv, Eigen::Vector4f(0, 0, 0, 1));
    const Eigen::VectorXd& mask = doc.mask();
    if (mask.size() == nv)
      for (int i = 0; i < nv; ++i) data[i].x() = float(mask[i]);
    // Region handles show as their own value bands on top of the mask.
    for (size_t r = 0; r < doc.rig().regions.size(); ++r)
      for (int v : doc.rig().regions[r].vertices)
        if (v >= 0 && v < nv) data[v].x() = std::max(data[v].x(), 0.75f);
  }
  gpu_.set_surface_data(data);
}

void SceneView::draw(const Document& doc, const view::Camera& cam, const ViewSettings& s) {
  gl::SurfaceStyle style;
  style.wireframe = s.wireframe;
  style.mode = s.sculpt_colors && doc.sculpt() ? gl::SurfaceColorMode::Scalar
               : s.weight_view == WeightView::AllHandles ? gl::SurfaceColorMode::VertexColor
               : s.weight_view == WeightView::Off ? gl::SurfaceColorMode::Shaded
                                    : gl::SurfaceColorMode::Scalar;
  style.isolines = s.weight_view == WeightView::Selected ? 10.0f : 0.0f;
  style.cull_back_faces = display_closed_;
  if (s.grid) {
    const Eigen::AlignedBox3d b = bounds_.isEmpty() ? kEmptyBox : bounds_;
    const double diag = b.diagonal().norm();
    const double spacing = gl::nice_spacing(2.5 * diag, 24);
    const Eigen::Vector3d c = b.center();
    gpu_.draw_lines(cam, gl::grid_lines(c.x(), c.z(), b.min().y(), 1.6 * diag, spacing), 1.0f, true);
  }
  gpu_.draw_surface(cam, style);
  if (s.handles) draw_overlays(doc, cam);
  // Per-frame extras, grouped by width.
  for (size_t i = 0; i < extra_line_widths_.size();) {
    size_t j = i;
    while (j < extra_line_widths_.size() && extra_line_widths_[j] == extra_line_widths_[i]) ++j;
    std::vector<gl::OverlayVertex> seg(extra_lines_.begin() + 2 * i, extra_lines_.begin() + 2 * j);
    gpu_.draw_lines(cam, seg, extra_line_widths_[i], false);
    i = j;
  }
  gpu_.draw_points(cam, extra_points_, extra_point_size_, false);
  extra_lines_.clear();
  extra_line_widths_.clear();
  extra_points_.clear();
}

void SceneView::show_preview(const TriMesh& mesh) {
  show_rest(mesh, is_closed_outward(mesh.V, mesh.F));
  display_is_rest_ = false;  // not the rest surface: rest-only edits stay off
  deformer_->gpu_output_stale = false;  // display_V_ is the preview itself
  showing_preview_ = true;
}

void SceneView::clear_preview() {
  if (!showing_preview_ || shown_sculpt_ != 0) return;  // a sculpt session's result stays until it ends (sync)
  showing_preview_ = false;
  surface_requested_ = true;  // the next sync shows the document's frame again
}

void SceneView::show_pose() {
  if (deformer_) deformer_->prefer_pose = true;
  surface_requested_ = true;  // the next sync shows it even when nothing else changed
}

}  // namespace dfm::editor
