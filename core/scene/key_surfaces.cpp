#include "core/scene/key_surfaces.h"

#include <algorithm>
#include <filesystem>
#include <string>

#include "core/scene/space_time_edit.h"

#include "core/anim/bake.h"
#include "core/anim/inbetween.h"
#include "core/anim/interpolate.h"
#include "core/sculpt/differential_blend.h"
#include "core/skin/skin.h"
#include "core/util/error.h"

namespace dfm {

namespace {

std::string key_name(const Document& doc, int i) {
  const SceneKey& k = doc.keys()[i];
  if (k.is_mesh()) {
    const std::string file = std::filesystem::path(k.mesh_path).filename().string();
    return file.empty() ? "mesh key " + std::to_string(i) : file;
  }
  return "key " + std::to_string(i);
}

// A local transition's in-betweens (Alexa 2002, 4.3): at each layer time u the per-vertex states of
// transition_states(offsets, u), blended in Laplacian coordinates (factored once for the interval).
std::vector<KeySurface> differential_inbetweens(const KeySurface& a, const KeySurface& b, int count,
                                                const Eigen::VectorXd& offsets) {
  std::vector<KeySurface> out;
  if (count <= 0) return out;
  const DifferentialBlend blend(a.V, b.V, a.F);
  for (int j = 1; j <= count; ++j) {
    const double u = double(j) / (count + 1);
    out.push_back({a.time + (b.time - a.time) * u, blend.at(transition_states(offsets, u)), a.F,
                   "local transition in-between of " + a.name + " and " + b.name});
  }
  return out;
}

}  // namespace

SkinBinding pose_binding(const Document& doc) {
  if (doc.surface().num_vertices() == 0) throw Error("pose keys need a surface: open a mesh first");
  if (!doc.has_weights())
    throw Error("pose keys need weights: " + (doc.weights_note().empty() ? std::string("not bound") : doc.weights_note()) +
                "; bind first");
  return make_skin_binding(doc.surface().V, Eigen::MatrixXd(), doc.weights(), doc.rig(),
                           doc.bind_settings().max_influences, doc.skin_endpoints(), doc.additional_weights());
}

KeyTrack pose_key_track(const Document& doc) {
  KeyTrack track;
  const std::vector<Pose> poses = doc.key_poses();
  for (size_t i = 0; i < poses.size(); ++i)
    if (!doc.keys()[i].is_mesh()) track.set({doc.keys()[i].time, poses[i]});
  return track;
}

PoseParams animation_params(const Document& doc, double t) {
  std::vector<const SceneKey*> keys;
  for (const SceneKey& k : doc.keys())
    if (!k.is_mesh()) keys.push_back(&k);
  if (keys.empty()) throw Error("the animation has no pose key");
  size_t i = 0;  // the last key at or before t (the first when t is before it)
  while (i + 1 < keys.size() && keys[i + 1]->time <= t) ++i;
  if (t <= keys[i]->time || i + 1 == keys.size()) return keys[i]->params;
  const double u = (t - keys[i]->time) / (keys[i + 1]->time - keys[i]->time);
  return interpolate_pose_params(doc.rig(), keys[i]->params, keys[i + 1]->params, u);
}

Pose animation_pose(const Document& doc, double t) { return evaluate_pose(doc.rig(), animation_params(doc, t)); }

Eigen::MatrixXd skin_params(const Document& doc, const SkinBinding& binding, const PoseParams& params) {
  return skin(doc.method(), binding, doc.skin_pose(params), stbs_handles(doc.rig(), params.bone_twist_stretch)).V;
}

namespace {

// The key surfaces with the rig's in-betweens inside each run of pose keys; key[i]: where key i landed.
std::vector<KeySurface> baked_key_surfaces(const Document& doc, std::vector<int>& key) {
  const std::vector<SceneKey>& keys = doc.keys();
  const int n = static_cast<int>(keys.size());
  std::vector<KeySurface> out;
  key.assign(n, -1);
  SkinBinding binding;
  bool have_binding = false;
  std::vector<Pose> poses;
  for (int i = 0; i < n;) {
    if (keys[i].is_mesh()) {
      key[i] = static_cast<int>(out.size());
      out.push_back({keys[i].time, keys[i].mesh.V, keys[i].mesh.F, key_name(doc, i)});
      ++i;
      continue;
    }
    // A run [i, j) of pose keys: baked together, in-betweens inside each of its intervals.
    int j = i;
    while (j < n && !keys[j].is_mesh()) ++j;
    if (!have_binding) {
      binding = pose_binding(doc);
      poses = doc.key_poses();
      have_binding = true;
    }
    KeyTrack track;
    for (int k = i; k < j; ++k) track.set({keys[k].time, poses[k]});
    const BakedLayers layers = bake_layers(bake_times(track, doc.inbetweens()),
                                           [&](double t) { return skin_params(doc, binding, animation_params(doc, t)); });
    int k = i;
    for (size_t l = 0; l < layers.times.size(); ++l) {
      const bool at_key = k < j && layers.times[l] == keys[k].time;
      if (at_key) key[k] = static_cast<int>(out.size());
      const std::string name = at_key ? key_name(doc, k++) : "in-between at t = " + std::to_string(layers.times[l]);
      out.push_back({layers.times[l], layers.positions[l], doc.surface().F, name});
    }
    i = j;
  }
  return out;
}

}  // namespace

std::vector<KeySurface> key_surfaces(const Document& doc) {
  std::vector<int> key;
  std::vector<KeySurface> baked = baked_key_surfaces(doc, key);
  // Intervals set to arap or linear: their in-betweens come from the two keys' meshes instead.
  const std::vector<SceneKey>& keys = doc.keys();
  std::vector<KeySurface> out;
  for (size_t i = 0; i < keys.size(); ++i) {
    out.push_back(std::move(baked[key[i]]));
    out.back().pairs_to_next = keys[i].pairs_to_next;
    if (i + 1 == keys.size()) break;
    const KeySurface& next = baked[key[i + 1]];
    if (keys[i].transition_to_next.size() == out.back().V.rows() && same_connectivity(out.back(), next)) {
      for (KeySurface& s : differential_inbetweens(out.back(), next, doc.inbetweens(), keys[i].transition_to_next))
        out.push_back(std::move(s));
    } else if (keys[i].inbetween != InbetweenMethod::Handles && same_connectivity(out.back(), next)) {
      for (KeySurface& s : mesh_inbetweens(out.back(), next, doc.inbetweens(), keys[i].inbetween)) out.push_back(std::move(s));
    } else {
      for (int l = key[i] + 1; l < key[i + 1]; ++l) out.push_back(std::move(baked[l]));
    }
  }
  return out;
}

BakedLayers baked_pose_frames(const Document& doc, int count) {
  if (count < 0 || count == 1) throw Error("frames to bake: 0 (the keys and in-betweens) or at least 2, got " + std::to_string(count));
  for (const SceneKey& k : doc.keys())
    if (k.is_mesh())
      throw Error("the animation has a mesh key (" + std::filesystem::path(k.mesh_path).filename().string() +
                  ") with its own triangles: baked frames need the surface's one connectivity");
  const KeyTrack track = pose_key_track(doc);
  if (track.size() < 2)
    throw Error("baking frames needs at least two pose keys (the document has " + std::to_string(track.size()) + ")");
  BakedLayers out;
  if (count == 0) {  // the animation's own layers, in-betweens as each interval sets them
    for (KeySurface& s : key_surfaces(doc)) {
      out.times.push_back(s.time);
      out.positions.push_back(std::move(s.V));
    }
    return out;
  }
  for (size_t i = 0; i + 1 < doc.keys().size(); ++i)
    if (doc.keys()[i].inbetween != InbetweenMethod::Handles)
      throw Error("key " + std::to_string(i) + "'s interval uses " + inbetween_method_name(doc.keys()[i].inbetween) +
                  " in-betweens: bake the keys and their in-betweens (a frame count of 0) instead of evenly spaced frames");
  const SkinBinding binding = pose_binding(doc);
  for (int i = 0; i < count; ++i) {
    out.times.push_back(i + 1 == count ? track.end() : track.start() + (track.end() - track.start()) * i / (count - 1));
    out.positions.push_back(skin_params(doc, binding, animation_params(doc, out.times.back())));
  }
  return out;
}

bool needs_transition(const std::vector<KeySurface>& keys) {
  for (size_t i = 0; i + 1 < keys.size(); ++i)
    if (!same_connectivity(keys[i], keys[i + 1])) return true;
  return false;
}

AnimationManifold document_manifold(const Document& doc, SequenceStats* stats,
                                    const std::function<bool(int, int)>& progress,
                                    std::vector<std::string>* edit_notes) {
  if (doc.keys().size() < 2)
    throw Error("an animation needs at least two keys (the document has " + std::to_string(doc.keys().size()) + ")");
  AnimationManifold m = build_manifold_sequence(key_surfaces(doc), TransitionOptions{}, stats, progress);
  std::vector<std::string> notes = apply_space_time_edits(m, doc.space_time_edits());
  if (edit_notes) *edit_notes = std::move(notes);
  return m;
}

AnimationManifold manifold_before_edit(const Document& doc, size_t count) {
  if (doc.keys().size() < 2) throw Error("a space-time edit needs an animation: key at least two poses");
  AnimationManifold m = build_manifold_sequence(key_surfaces(doc));
  const std::vector<SpaceTimeEdit>& all = doc.space_time_edits();
  apply_space_time_edits(m, std::vector<SpaceTimeEdit>(all.begin(), all.begin() + std::min(count, all.size())));
  return m;
}

}  // namespace dfm
