#pragma once
// The editor's document: the single source of truth for one scene.
//
// Every edit goes through a Document member that records one undo step (a command that swaps the
// parts of the scene it touched with a saved copy, so undo/redo are cheap and exact). Queries are const.
// The UI and the script runner call the same members, so a script reproduces what a user does.
//
// Undo granularity: a drag or a brush stroke is one step. Wrap it in begin_gesture()/end_gesture();
// successive edits of the same kind on the same target inside one gesture merge into one step.
//
// View state (camera, current time, selection) is saved with the scene but is NOT undoable and does
// not mark the document dirty, as in Blender/Maya: scrubbing or orbiting never fills the undo stack.
//
// Rig edits after a bind (adding, moving or deleting any handle, painting a region) clear the weights,
// because they no longer match the rig; the step's undo restores them. weights_note() says why.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/anim/inbetween_method.h"
#include "core/bind/bind_volume.h"
#include "core/bind/weight_tools.h"
#include "core/mesh/mesh.h"
#include "core/pose/fast_posing.h"
#include "core/pose/pose_dynamics.h"
#include "core/rig/pose.h"
#include "core/rig/pose_params.h"
#include "core/rig/rig.h"
#include "core/scene/sculpt_session.h"
#include "core/scene/space_time_edit.h"
#include "core/scene/weight_brush.h"
#include "core/skin/endpoint_filter.h"
#include "core/skin/skin.h"  // SkinMethod

namespace dfm {

struct Camera {
  Eigen::Vector3d position{0, 0, 3};
  Eigen::Vector3d target{0, 0, 0};
  Eigen::Vector3d up{0, 1, 0};
  double fov_deg = 45;     // vertical field of view (perspective)
  bool ortho = false;
  bool operator==(const Camera& o) const;
};

// The most additional weight functions a bind makes (BindSettings::additional_weights).
constexpr int kMaxAdditionalWeights = 100;

// Options the bind is run with (the UI converts these to the bind module's options).
struct BindSettings {
  VolumeOptions volume;
  int max_influences = 0;  // 0 = keep all; else keep the k largest weights per vertex (skin pruning)
  bool monotone = false;   // monotone weights: no local extrema away from the handles (BbwOptions::monotone)
  // Additional weight functions (Jacobson 2013, 7.3.3; core/bind/additional_weights.h): k abstract
  // handles FAST solves and nobody sets, computed with the bind (0: none). See additional_handles.h.
  int additional_weights = 0;
  bool operator==(const BindSettings& o) const;
};

// What the last bind reported (shown in the UI, saved with the weights).
struct BindStats {
  double seconds = 0;
  int tet_vertices = 0;
  int tets = 0;
  std::vector<std::string> notes;
  bool operator==(const BindStats& o) const;
};

// A key: the artist's pose parameters at a time (evaluate_pose() turns it into a Pose per handle), or
// a whole mesh (any connectivity) that the animation passes through at that time (a "mesh key"; the
// animation manifold joins it to its neighbours by a transition, see core/anim/manifold_sequence.h).
// A mesh key keeps params sized to the rig like every key (unused by the animation).
struct SceneKey {
  double time = 0;
  PoseParams params;
  TriMesh mesh;           // empty (no vertices): a pose key; else closed, checked by check_transition_key
  std::string mesh_path;  // where the mesh came from (informational; the data is in the scene)
  // From this key to the next (inbetween.h); arap and linear apply when both keys have one connectivity.
  InbetweenMethod inbetween = InbetweenMethod::Handles;
  // Picked pairs for a transition to the next key (transition.h, "The warp"): one a row, x0 y0 z0 on
  // this key, x1 y1 z1 on the next; #pairs x 6, or none.
  Eigen::MatrixXd pairs_to_next = Eigen::MatrixXd(0, 6);
  // Local transition to the next key (Alexa 2002, 4.3; differential_blend.h's transition_states): one
  // offset in (-1, 1) per vertex, > 0 arrives early, < 0 late; empty: none. When set and the two keys
  // share one connectivity, the interval's in-betweens are the differential blend at those states
  // (whatever `inbetween` says); an offset vector of another size than the keys' is ignored.
  Eigen::VectorXd transition_to_next;
  bool is_mesh() const { return mesh.num_vertices() > 0; }
};

// Posing by dragging (FAST, Jacobson 2013 ch. 7): when `fast` is on and the surface is bound, every
// translate or rotate of a handle re-solves the handles that are not pinned. states: one per handle
// (rig.h order); a vector of another size (the rig changed) means the defaults of
// default_constraint_states.
struct PosingSettings {
  bool fast = false;
  int iterations = 8;  // local-global iterations per edit (per drawn frame while dragging)
  std::vector<HandleConstraint> states;
  // Secondary dynamics (Jacobson 2013, 7.7; core/pose/pose_dynamics.h): a drag steps a simulation
  // whose free handles lag, overshoot and settle. dt: the time step (s; the editor steps once per
  // drawn frame, so 1/60 matches a 60 Hz display), damping (1/s) and density as FastDynamicsOptions.
  bool dynamics = false;
  double dt = 1.0 / 60;
  double damping = 4.0;
  double density = 1.0;
  bool operator==(const PosingSettings& o) const {
    return fast == o.fast && iterations == o.iterations && states == o.states && dynamics == o.dynamics &&
           dt == o.dt && damping == o.damping && density == o.density;
  }
};

struct Selection {
  std::vector<int> handles;  // global handle indices (rig.h order), first = active
  int joint = -1;            // a selected skeleton joint (joint editing before bind), -1 none
  bool operator==(const Selection& o) const { return handles == o.handles && joint == o.joint; }
};

// Everything a scene file holds. Plain data; Document owns one and guards its invariants:
//   pose / every key's params are sized to the rig; mask has #surface V entries (or is empty);
//   weights are empty or #surface V x num_handles(rig); keys are sorted by time, times distinct;
//   a mesh key's mesh passed check_transition_key (closed, oriented, finite, valid indices).
struct SceneData {
  TriMesh surface;
  std::string surface_path;  // where the surface came from (informational; the data is in the scene)
  TetMesh tets;              // optional tet-mesh input (empty when the surface was given)
  // For tet input: the tet vertex each surface vertex is (surface = compacted boundary of tets).
  Eigen::VectorXi surface_to_tet;
  Rig rig;
  PoseParams pose;
  PosingSettings posing;
  SkinMethod method = SkinMethod::LBS;
  BindSettings bind_settings;
  int inbetweens = 4;       // animation manifold: baked layers strictly inside each key interval
  Eigen::MatrixXd weights;  // #V x #handles, or empty (not bound / invalidated)
  // #V x #bones STBS endpoint weights from the bind (core/bind/endpoint_weights.h), or empty: STBS then
  // projects onto each bone (weights not from a bind, scenes saved before).
  Eigen::MatrixXd endpoint_weights;
  // #V x k additional weights from the bind (BindSettings::additional_weights then), or empty. Their
  // handles' transforms are PoseParams::solved[num_handles(rig) + e] (core/rig/additional_handles.h).
  Eigen::MatrixXd additional_weights;
  // Per bone, the curve its endpoint weights pass through (endpoint_filter.h; Fig. 6.9), or fewer
  // entries / empty ones: the identity. A skinning setting, kept across binds.
  std::vector<EndpointFilter> endpoint_filters;
  BindStats bind_stats;
  // The weights the last bind replaced, when it kept their shape (a Rebind of an imported character's
  // own weights, or of an earlier bind), or empty: what the weight view's difference compares against.
  // Not saved with the scene.
  Eigen::MatrixXd replaced_weights;
  std::vector<SceneKey> keys;
  // Space-time edits of the keys' manifold, replayed in order (space_time_edit.h); undone with the keys.
  std::vector<SpaceTimeEdit> space_time_edits;
  Eigen::VectorXd mask;     // shape-preservation mask per surface vertex in [0,1] (painted)
  Camera camera;
  double time = 0;
  Selection selection;
};

// What a translate or drag did to a handle (the script prints it, the editor's status line shows it).
// A bone attached to another (a parent, or a root sharing its joint: bone_attachments) never
// translates: it turns about its first joint toward the drag, or, when it is position-constrained
// with a free bone above it and FAST solves (a drag, or translate with FAST on), the drag moves its
// tip's target and FAST runs the chain as IK.
enum class DragKind { Moved, Rotated, Ik };
struct DragReport {
  DragKind kind = DragKind::Moved;
  std::string message;  // e.g. "l_forearm turned about its first joint (its chain is pinned; ...)"
};

// Pose params with every vector sized to `rig` (existing entries kept, missing ones identity).
PoseParams fit_pose_params(const Rig& rig, PoseParams p);

class Document {
 public:
  Document();
  ~Document();
  Document(const Document&) = delete;
  Document& operator=(const Document&) = delete;

  // ---- queries ---------------------------------------------------------------------------------
  const SceneData& data() const { return s_; }
  const TriMesh& surface() const { return s_.surface; }
  const std::string& surface_path() const { return s_.surface_path; }
  bool has_tets() const { return s_.tets.num_tets() > 0; }
  const TetMesh& tets() const { return s_.tets; }
  const Rig& rig() const { return s_.rig; }
  int num_handles() const;
  const PoseParams& pose_params() const { return s_.pose; }
  const PosingSettings& posing() const { return s_.posing; }
  // posing().states fitted to the rig (the defaults where the sizes differ).
  std::vector<HandleConstraint> handle_states() const;
  // Timings of the last FAST solve (precompute and switch are nonzero only when that solve rebuilt them).
  const FastSolveReport& last_fast_solve() const { return last_fast_; }
  Pose pose() const;  // evaluate_pose(rig, pose_params)
  SkinMethod method() const { return s_.method; }
  int inbetweens() const { return s_.inbetweens; }
  const BindSettings& bind_settings() const { return s_.bind_settings; }
  bool has_weights() const;  // weights present and matching the surface and rig
  const Eigen::MatrixXd& weights() const { return s_.weights; }
  // The weights the last bind replaced (same shape as weights()), or empty.
  const Eigen::MatrixXd& replaced_weights() const { return s_.replaced_weights; }
  // The bind's STBS endpoint weights (#V x #bones), or empty: STBS projects onto each bone.
  const Eigen::MatrixXd& endpoint_weights() const { return s_.endpoint_weights; }
  // The bind's additional weights (#V x num_additional()), or empty.
  const Eigen::MatrixXd& additional_weights() const { return s_.additional_weights; }
  int num_additional() const { return has_weights() ? static_cast<int>(s_.additional_weights.cols()) : 0; }
  // [weights | additional weights]: what skinning and FAST use (cached per change of the weights).
  const Eigen::MatrixXd& skin_weights() const;
  // skin_pose (additional_handles.h) of `params`: one transform per rig handle, then per additional one.
  Pose skin_pose(const PoseParams& params) const;
  const std::vector<EndpointFilter>& endpoint_filters() const { return s_.endpoint_filters; }
  // The endpoint weights skinning uses (#V x #bones): the bind's, or the projection onto each bone,
  // through each bone's filter; empty when there is no filter and no bind's (skin.h then projects).
  // Cached per change of the surface, rig, weights or settings (not recomputed per pose edit).
  const Eigen::MatrixXd& skin_endpoints() const;
  const BindStats& bind_stats() const { return s_.bind_stats; }
  // Why the weights are absent ("not bound yet", "rig changed after bind: ..."); "" when bound.
  const std::string& weights_note() const { return weights_note_; }
  const std::vector<SceneKey>& keys() const { return s_.keys; }
  const std::vector<SpaceTimeEdit>& space_time_edits() const { return s_.space_time_edits; }
  // Index of the key at time t (|dt| <= 1e-9), or -1.
  int key_at(double t) const;
  // Every key's params evaluated to a Pose, in time order (a mesh key gives its unused params' pose:
  // check keys()[i].is_mesh()).
  std::vector<Pose> key_poses() const;
  bool has_mesh_keys() const;
  std::vector<double> key_times() const;
  const Eigen::VectorXd& mask() const { return s_.mask; }
  const Camera& camera() const { return s_.camera; }
  double time() const { return s_.time; }
  const Selection& selection() const { return s_.selection; }
  // Rest-state position of a handle's pivot: point position, bone's first joint, cage vertex,
  // region centroid. Throws dfm::Error for a bad index.
  Eigen::Vector3d handle_pivot(int handle) const;

  // ---- documents and files -----------------------------------------------------------------------
  const std::string& path() const { return path_; }  // "" until saved or loaded
  // What a window title shows: path(), else the mesh file the document was started from
  // (open_mesh), else "untitled".
  std::string title() const;
  bool dirty() const;
  // Replace everything with a scene file (clears undo). Throws dfm::Error; the document is unchanged then.
  void load_scene(const std::string& path);
  // A file a registered importer reads as a whole scene (scene_import.h: rigged glTF): a new, unsaved
  // document. Returns the importer's report. Throws dfm::Error when no importer reads the extension.
  std::string import_scene(const std::string& path);
  // Motion a registered importer reads onto the rig (scene_import.h: BVH by bone name) replaces the
  // keys, the pose back to rest; one undo step. Returns the importer's report (names matched and not).
  // Throws dfm::Error (no importer for the extension, no bones, the file's problem); nothing changes then.
  std::string load_motion(const std::string& path);
  // Atomic save (sidecar first, then JSON); sets path() and clears dirty.
  void save_scene(const std::string& path);
  // Writes autosave_path(path()) (or autosave_path("untitled.scene.json") in the working directory if
  // never saved); does not touch path() or dirty. Returns the file written.
  std::string autosave() const;
  // Start over: empty scene, empty undo.
  void clear();
  // A new document from a surface (.obj .off .ply .stl) or tet mesh (.mesh .node .ele): no handles,
  // no keys, every setting as in a fresh document, undo cleared, path() empty (Save asks for a name),
  // title() the file. Throws dfm::Error naming the file; the document is unchanged then. The editor
  // asks before discarding unsaved changes; a script does not.
  void open_mesh(const std::string& path);

  // ---- undo ----------------------------------------------------------------------------------------
  bool can_undo() const;
  bool can_redo() const;
  std::string undo_name() const;  // name of the step undo() would revert ("" if none)
  std::string redo_name() const;
  void undo();  // no-op when nothing to undo
  void redo();
  int undo_depth() const;
  // A drag or brush stroke: while open, edits with the same merge target fold into one undo step.
  void begin_gesture();
  void end_gesture();

  // ---- edits (each is one undo step; all throw dfm::Error on bad input, leaving the doc unchanged) ---
  // "Replace surface...": the surface (or tet mesh) from a file under the same rig, for a remeshed
  // character. Keeps the rig, pose, keys and settings; clears weights (bind again), mask and regions
  // (their vertex indices belong to the old surface). One undo step.
  void replace_surface(const std::string& path);
  void set_surface(const TriMesh& surface, const std::string& source_name);  // the same, from data
  // Adds a .tgf's bones (joint chains) and point handles to the rig.
  void load_skeleton(const std::string& path);
  // Adds a cage (any surface file; open or partial cages allowed).
  void load_cage(const std::string& path);
  void add_cage(const Cage& cage);

  int add_point(const Eigen::Vector3d& p, const std::string& name = "");  // returns its point index
  void move_point(int point, const Eigen::Vector3d& p);                   // merges within a gesture
  // Adds a chain of bones through `joints` (k joints -> k-1 bones). parent_joint >= 0 reuses an existing
  // joint as the chain's first joint (so the chain hangs off that joint). Returns the first new bone index.
  int add_bone_chain(const std::vector<Eigen::Vector3d>& joints, int parent_joint = -1);
  void move_joint(int joint, const Eigen::Vector3d& p);  // merges within a gesture
  void move_cage_vertex(int cage, int vertex, const Eigen::Vector3d& p);  // merges within a gesture
  // Deletes handles by global index (points, bones -- and joints no other bone uses --, whole cages
  // when any of their vertices is given, regions). Pseudo-edges and selection are updated.
  void delete_handles(std::vector<int> handles);
  void rename_handle(int handle, const std::string& name);  // cage vertex -> renames its cage
  void add_pseudo_edge(int point_a, int point_b);
  void remove_pseudo_edge(int point_a, int point_b);

  // Brush: sets mask[v] = values[i] for each vertex (values clamped to [0,1]). Merges within a gesture.
  void paint_mask(const std::vector<int>& vertices, const std::vector<double>& values);
  int add_region(const std::string& name = "");  // an empty region handle; returns its region index
  // Adds (erase=false) or removes vertices of a region. Merges within a gesture.
  void paint_region(int region, const std::vector<int>& vertices, bool erase);

  // The result of a bind (run elsewhere): #V x num_handles, rows should sum to 1.
  // endpoints: the bind's STBS endpoint weights (#V x #bones, in [0, 1]) or empty (the projection).
  // additional: the bind's additional weights (#V x k, finite), or empty.
  void set_weights(const Eigen::MatrixXd& W, const BindStats& stats, const Eigen::MatrixXd& endpoints = {},
                   const Eigen::MatrixXd& additional = {});
  void set_bind_settings(const BindSettings& s);
  void set_method(SkinMethod m);
  // Bone `bone`'s endpoint filter (checked by check_endpoint_filter; empty: none). Merges within a gesture.
  void set_endpoint_filter(int bone, const EndpointFilter& filter);
  void set_inbetweens(int n);  // 0..1000

  // Weight tools (core/bind/weight_tools.h), each one undo step on the weights; they need weights
  // (dfm::Error otherwise) and keep the rows of the vertices the bind constrained to a handle
  // (surface_weight_constraints). `locked`: handle indices whose columns are kept bit for bit.
  LimitReport weights_limit(const LimitOptions& opts);
  NormalizeReport weights_normalize(const std::vector<int>& locked);
  void weights_smooth(const SmoothOptions& opts, const std::vector<int>& locked);
  MirrorReport weights_mirror(const MirrorOptions& opts);
  // Handles whose largest weight is below threshold (empty without weights).
  std::vector<ZeroWeightHandle> weights_report(double threshold = 1e-3) const;
  // Weight brush (weight_brush.h): one dab on `handle`'s weights, `locked` handles and the bind's
  // constrained rows kept; with mirror_x also the same dab at the centre's reflection across x = 0 on
  // the handle's mirror (weight_mirror.h's pairing). Merges within a gesture. Returns the rows changed.
  int paint_weights(int handle, const Eigen::Vector3d& center, const WeightBrush& brush, const std::vector<int>& locked,
                    bool mirror_x);

  // Posing (no effect on weights). Translate/rotate act on the pose of one handle:
  //   point: translation / explicit rotation about the point; bone: translation / rotation about its
  //   first joint relative to the parent; cage vertex: translation (rotation: error); region: affine
  //   about its centroid. Both merge within a gesture.
  void set_pose_params(const PoseParams& p);
  DragReport translate_handle(int handle, const Eigen::Vector3d& delta);
  void rotate_handle(int handle, const Eigen::Quaterniond& q);
  // A bone's twist (radians, about its axis, at its second joint) and stretch (length factor > 0)
  // (Jacobson 2013 ch. 6; STBS spreads them along the bone, every method moves its children by them).
  // Merges within a gesture. Throws dfm::Error: no such bone, not finite, stretch not positive.
  void set_bone_twist_stretch(int bone, const BoneTwistStretch& ts);
  void reset_pose();
  // FAST settings and handle states (one undo step; re-solves the pose when FAST is on and bound).
  void set_posing(const PosingSettings& p);
  void set_handle_state(int handle, HandleConstraint state);
  // A drag: translate_handle, then the FAST solve whether or not posing().fast is on (what the Pose
  // tool's drag and the script's `drag` do). Needs weights (dfm::Error otherwise). Merges in a gesture.
  DragReport drag_handle(int handle, const Eigen::Vector3d& delta);
  // With posing().dynamics on, a drag (drag_handle, or translate/rotate_handle with FAST on) takes one time
  // step of a simulation started at the pose before it, instead of the static solve. The simulation
  // stays live until it settles (vertex speed under 1e-3 diagonals a second, or 30 s simulated) or
  // any other edit, undo included, ends it; its steps change the pose without undo steps of their
  // own, so undoing the drag restores the pose from before it (redo: the pose at the undo).
  bool dynamics_live() const { return dyn_live_; }
  // One more time step (the editor: once per drawn frame without a drag). Returns dynamics_live().
  bool step_dynamics();
  // Steps until settled, at most max_steps (< 0: no limit but the 30 s). Returns the steps taken.
  int settle_dynamics(int max_steps = -1);
  // Runs the keyed animation through the dynamics at `fps` from `from` to `to` (NaN: the keys' first
  // and last time): each frame's key parameters (animation_params) are the constraints, free handles
  // follow by momentum from rest at `from` (its static FAST solve). Keys every frame as pose keys,
  // replacing the keys in [from, to]: one undo step. Needs weights and pose keys (no mesh key in the
  // range); fps in (0, 1000]. Returns the frames keyed.
  int simulate(double fps, double from, double to);

  // Keys: set_key stores the current pose params at time t (replacing a key at the same time, a mesh
  // key included).
  void set_key(double t);
  // A mesh key: the animation passes through `mesh` at time t (replacing a key at the same time).
  // The mesh is checked first (check_transition_key: closed, oriented, finite, valid indices, not
  // self-intersecting); a bad mesh throws dfm::Error naming `path` and leaves the document unchanged.
  void key_mesh(const TriMesh& mesh, const std::string& path, double t);
  // read_surface(path) then key_mesh: what `key-mesh FILE [T]` and the timeline's "Key mesh..." do.
  void key_mesh_file(const std::string& path, double t);
  void delete_key(int index);
  // How the animation passes from key `index` to the next one (one undo step).
  void set_key_inbetween(int index, InbetweenMethod method);
  // The picked pairs from key `index` to the next (#pairs x 6, finite; one undo step). Whether each
  // point lies on its key is the transition's check (scene/key_pairs.h checks it first).
  void set_key_pairs(int index, const Eigen::MatrixXd& pairs);
  // The local transition from mesh key `index` to the next (both mesh keys of one connectivity): the
  // offsets of `vertices` set to `values` (each in (-1, 1)). Merges within a gesture (a brush stroke).
  void paint_transition(int index, const std::vector<int>& vertices, const std::vector<double>& values);
  // Clears key `index`'s local transition (its in-betweens return to its method). One undo step.
  void clear_transition(int index);
  void move_key(int index, double new_time);  // throws if another key sits at new_time
  // Space-time edits (space_time_edit.h), stored with the keys. add: one step. set: replaces edit
  // `index` and merges within a gesture, also with the add that made it (a drag of its handle is one step). clear: one step (none when
  // there are none). All check the edit's numbers (check_space_time_edit) first.
  void add_space_time_edit(const SpaceTimeEdit& e);
  void set_space_time_edit(int index, const SpaceTimeEdit& e);
  void clear_space_time_edits();
  // Applies the key's params as the current pose (a pose edit). A mesh key has no pose: dfm::Error.
  void go_to_key(int index);

  // ---- sculpting (sculpt_session.h; document_sculpt.cpp) ----------------------------------------------
  // The session is tool state: not saved, not undoable, ended by sculpt_key, sculpt_clear, a change of
  // the surface (undo included), load, open and clear. Points and radii are world units measured on
  // the session's result as it stands (what the viewport shows). Each throws dfm::Error on bad input,
  // leaving the session unchanged.
  const SculptSession* sculpt() const { return sculpt_.get(); }
  // Adds to (erase: removes from) the free region the vertices within `radius` of `center`. Starts a
  // session on the mesh key at time() if there is one, else on the rest surface.
  int sculpt_region(const Eigen::Vector3d& center, double radius, bool erase);
  // The handle: the free region's vertices within `radius` of `center` (none: dfm::Error).
  int sculpt_handle(const Eigen::Vector3d& center, double radius);
  void sculpt_order(int order);  // 2 or 3; the move is kept and solved again
  // Adds `delta` to the handle's translation and solves (the factorization is cached per region,
  // handle and order: a move is one back substitution).
  void sculpt_move(const Eigen::Vector3d& delta);
  // Keys the result as a mesh key at time t (one undo step, as key_mesh) and ends the session.
  void sculpt_key(double t);
  void sculpt_clear();
  // Seconds the last factorization took (0 before any).
  double sculpt_factor_seconds() const;

  // ---- view state (saved, not undoable, does not mark dirty) ---------------------------------------
  void set_time(double t);
  void set_camera(const Camera& c);
  void set_selection(const Selection& s);  // handles out of range -> dfm::Error

  // Bumped on every change of scene content (edits, undo, redo, load): lets the UI re-upload buffers.
  std::uint64_t revision() const { return revision_; }
  // Bumped only when the surface or the weights change (caches keyed on them need not hash them).
  std::uint64_t surface_weights_revision() const { return surface_weights_revision_; }

 private:
  struct Step;
  enum Part : unsigned;
  void execute(const std::string& name, unsigned parts, const std::string& merge_target,
               const std::function<void(SceneData&)>& edit);
  void rig_edit(const std::string& name, const std::string& merge_target,
                const std::function<void(SceneData&)>& edit);
  void after_change(unsigned parts = ~0u);
  // load_scene, open_mesh, clear: `d` becomes the whole document, with a fresh undo history.
  void start_document(SceneData d, const std::string& path);
  // replace_surface / set_surface: the new surface (and tets) with weights, mask and regions cleared.
  void install_surface(TriMesh surface, const std::string& path, TetMesh tets, Eigen::VectorXi surface_to_tet);
  void store_weights(const std::string& name, Eigen::MatrixXd W);  // weights_*: one step, none if unchanged
  DragReport move_handle(int handle, const Eigen::Vector3d& delta, bool solve);  // translate_handle, drag_handle
  // Re-solves s.pose's non-pinned handles (no-op without weights); inside an edit.
  void solve_fast(SceneData& s);
  // One dynamics step of s.pose (starting a simulation at s.pose when none is live); inside an edit.
  void step_dynamics_in(SceneData& s);
  FastDynamicsOptions dynamics_options(const PosingSettings& p) const;
  // The top undo step now stands for a state the file does not hold (an edit folded into it).
  void touch_top_step();

  SceneData s_;
  std::string path_;
  std::string weights_note_ = "not bound yet";
  std::vector<std::unique_ptr<Step>> undo_, redo_;
  void replay_step(std::vector<std::unique_ptr<Step>>& from, std::vector<std::unique_ptr<Step>>& to);
  std::uint64_t next_serial_ = 1, saved_serial_ = 0, revision_ = 0, surface_weights_revision_ = 0;
  std::unique_ptr<FastPosing> fast_;  // caches only: not part of the scene or of undo
  std::unique_ptr<PoseDynamics> dyn_;  // the live drag's simulation (not part of the scene or of undo)
  bool dyn_live_ = false;
  // What dyn_ was built for: a drag on the same inputs restarts it without the precompute.
  struct DynamicsInputs {
    std::uint64_t surface_weights = 0, surface_rig = 0;
    PosingSettings posing;
    bool operator==(const DynamicsInputs& o) const {
      return surface_weights == o.surface_weights && surface_rig == o.surface_rig && posing == o.posing;
    }
  } dyn_inputs_;
  bool dyn_keep_ = false;  // the edit in progress is a dynamics step: after_change keeps dyn_live_
  struct PaintCache;  // what the weight brush reads of the surface and rig (document_weights.cpp)
  std::shared_ptr<const PaintCache> paint_cache_;
  std::uint64_t surface_rig_revision_ = 0;  // bumped when the surface or the rig changes
  std::uint64_t skin_inputs_revision_ = 0;  // ... or the weights or settings (skin_endpoints' cache)
  mutable std::uint64_t endpoints_revision_ = ~0ull;
  mutable Eigen::MatrixXd endpoints_;
  mutable std::uint64_t skin_weights_revision_ = ~0ull;
  mutable Eigen::MatrixXd skin_weights_;
  FastSolveReport last_fast_;
  std::unique_ptr<SculptSession> sculpt_;
  struct SculptSolver;  // the factored region choice (document_sculpt.cpp)
  std::shared_ptr<const SculptSolver> sculpt_solver_;
  std::uint64_t sculpt_revision_ = 0;
  SculptSession& sculpt_session();  // the session, started if none
  void sculpt_commit();             // the result becomes the base (a region or handle change after a move)
  bool gesture_open_ = false;
  bool gesture_merge_ok_ = false;  // the top step was made inside the current gesture
};

}  // namespace dfm
