#pragma once
// BVH motion (issue 32), read with Assimp: a BVH file carries a skeleton and its motion, no mesh.
//
// - Onto a rig: each scene bone takes the motion of the BVH joint of its name. The BVH's rest
//   skeleton is first brought onto the scene's by the similarity (rotation, uniform scale,
//   translation) that best maps the matched joints' rest positions to the bones' heads (Umeyama's
//   least squares), so a Z-up BVH in centimetres drives a Y-up rig in metres; its residual says how
//   well the two rest poses agree. A matched bone's joint matrix at time t is A S_k(t) A^-1, with
//   S_k(t) = G_k(t) G_k(rest)^-1 the BVH joint's motion and A that similarity; a bone without a match
//   follows its parent rigidly (rest relative to it). The keys, at the BVH's frames (frame i at
//   i * Frame Time s: Blender's frame f at (f - 1) * Frame Time), replace the scene's.
// - Alone: not yet. A scene here is a surface with handles, and a skeleton with no mesh has nothing to
//   bind or skin; `open FILE.bvh` says so, naming the file (import or open a rigged mesh, then
//   `load-motion FILE.bvh`).
#include <string>
#include <vector>

#include "core/scene/document.h"

namespace dfm {

struct BvhReport {
  std::vector<std::string> matched;     // scene bones that took a BVH joint's motion
  std::vector<std::string> bvh_only;    // BVH joints no scene bone is named after
  std::vector<std::string> scene_only;  // scene bones without a BVH joint (held at rest under their parent)
  double scale = 1;                     // the fitted similarity's scale (BVH units to the scene's)
  double residual = 0;                  // rms distance of the aligned rest joints from the bone heads,
                                        // as a fraction of the rig's size
  int keys = 0;
  double duration = 0;
  std::string text() const;
};

// The BVH's motion as keys for `scene`'s rig (the scene is not changed). Throws dfm::Error naming the
// file: not a BVH, what Assimp refuses, no animation, no joint named after a scene bone.
std::vector<SceneKey> bvh_motion_keys(const SceneData& scene, const std::string& path, BvhReport* report = nullptr);

// bvh_motion_keys, then the scene's keys replaced by them (its pose back to rest).
void apply_bvh_motion(SceneData& scene, const std::string& path, BvhReport* report = nullptr);

// Registers BVH with core/scene/scene_import.h: motion onto the document's rig (Document::load_motion)
// and, for `open FILE.bvh`, the refusal above naming the file.
void register_bvh_importers();

}  // namespace dfm
