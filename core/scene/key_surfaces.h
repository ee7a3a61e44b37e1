#pragma once
// The document's keys as the surfaces the animation passes through, and the animation manifold
// through them: the one place the editor's view, the script (save-posed, save-frames) and the UI's
// saves turn keys into a manifold.
//
// Consecutive pose keys are baked (bake_layers at bake_times with doc.inbetweens(), each layer the
// animation_pose skinned with the document's method and weights: one layer per key plus the
// in-betweens inside each interval of two pose keys); a mesh key contributes its own mesh at its time. build_manifold_sequence then joins
// neighbours with the same triangle list by the exact prism build and the others by a transition.
#include <functional>
#include <vector>

#include "core/anim/bake.h"
#include "core/anim/keyframes.h"
#include "core/anim/manifold_sequence.h"
#include "core/scene/document.h"
#include "core/skin/skin.h"

namespace dfm {

// The key surfaces in time order. Pose keys need weights: without them (or with no surface) throws
// dfm::Error saying why ("pose keys need weights: not bound yet; bind first").
std::vector<KeySurface> key_surfaces(const Document& doc);

// The pose keys as a track (their times and evaluated poses), mesh keys left out.
KeyTrack pose_key_track(const Document& doc);

// The pose the animation has at time t: between two pose keys (mesh keys left out) their parameters
// interpolated (interpolate_pose_params: rotations in their own frames) and evaluated by forward
// kinematics, so every bone stays on its parent's end between keys; a key's own pose at its time;
// the first or last key's before or after them. Throws dfm::Error without pose keys.
Pose animation_pose(const Document& doc, double t);
// The skin binding of the document's weights, positions only (its bind settings' influences). Throws
// dfm::Error without a surface or weights ("pose keys need weights: ...; bind first").
SkinBinding pose_binding(const Document& doc);
// The parameters behind it (twist and stretch included: the animation's layers skin with them).
PoseParams animation_params(const Document& doc, double t);
// The surface posed by `params` with the document's method, twist and stretch (STBS reads them;
// every method moves a stretched bone's children): what the animation's layers and frames hold.
Eigen::MatrixXd skin_params(const Document& doc, const SkinBinding& binding, const PoseParams& params);

// The pose keys as frames of the surface's one connectivity (for `deform compress`), skinned with the
// document's method and weights. count = 0: the keys plus doc.inbetweens() in-betweens inside each
// interval (bake_layers); count >= 2: that many evenly spaced times from the first key to the last.
// Throws dfm::Error with fewer than two pose keys, with a mesh key (it has its own triangles), without
// weights, or for count 1 or < 0.
BakedLayers baked_pose_frames(const Document& doc, int count);

// True when some neighbouring key surfaces differ in connectivity (a transition joins them: seconds).
bool needs_transition(const std::vector<KeySurface>& keys);

// build_manifold_sequence(key_surfaces(doc)), then the document's space-time edits replayed onto it
// (apply_space_time_edits); needs >= 2 keys. `progress` as there (false cancels). `edit_notes`, when
// given, receives the stale edits skipped.
AnimationManifold document_manifold(const Document& doc, SequenceStats* stats = nullptr,
                                    const std::function<bool(int, int)>& progress = {},
                                    std::vector<std::string>* edit_notes = nullptr);

// The keys' manifold with only the first `count` space-time edits replayed: what edit `count` is made
// on (edit-region's and edit-drag's checks, the editor's retime drag). Throws dfm::Error with fewer
// than two keys.
AnimationManifold manifold_before_edit(const Document& doc, size_t count);

}  // namespace dfm
