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
// - Alone (`open FILE.bvh`): a scene of bones and keys, no mesh. One bone per joint (a node with a
//   channel), from its rest position (the OFFSETs summed) by import_skeleton's rule (rig_import.h): a
//   leaf ends at its End Site; the file's axes and units as stored. Each frame a key reproducing
//   G_k(t) G_k(rest)^-1. Bind a surface to it, or use load-motion onto a rigged scene.
#include <string>
#include <vector>

#include "core/export/rig_import.h"
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

// The BVH alone as a scene: bones and keys, no surface, no weights. Throws dfm::Error naming the file.
SceneData import_bvh_skeleton(const std::string& path, RigImportReport* report = nullptr);

// Registers BVH with core/scene/scene_import.h: motion onto the document's rig (Document::load_motion)
// and, for `open FILE.bvh`, import_bvh_skeleton.
void register_bvh_importers();

}  // namespace dfm
