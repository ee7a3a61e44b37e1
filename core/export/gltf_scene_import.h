#pragma once
// A rigged, animated glTF 2.0 file (.glb, .gltf) as a scene (issue 32): the skinned mesh, its skeleton as
// the editor's bones, the file's weights as the scene's weights (the scene counts as bound) and its
// animation as pose keys.
//
// - Mesh: the first node with a mesh and a skin; its vertices welded by position (glTF splits them at
//   normal and UV seams) so the surface is closed where the source is. The skinned mesh node's own
//   transform is ignored, as the specification says.
// - Bones: one per joint, in the skin's joint order (so a joint's weights are its bone's handle), from
//   the joint's bind position (the inverse bind matrix's inverse applied to the origin) by
//   import_skeleton's rule (rig_import.h; glTF has no end nodes). Names are the joint nodes' names
//   (without the "N:" prefix this program's export gives joint N).
// - Weights: every JOINTS_n / WEIGHTS_n set summed per joint, rows normalized.
// - Animation: the first animation sampled at each of its key times (glTF sampling: LINEAR, STEP and
//   CUBICSPLINE; a cubic curve also at kCubicSamplesPerInterval - 1 times inside each interval).
//   A key holds, per bone, the transform that reproduces the file's joint matrix G_j(t) IB_j exactly
//   under the editor's forward kinematics (a rotation about the bone's first joint and a translation,
//   relative to the parent bone). A joint whose animation scales is refused.
// - Not imported (said in the report): morph targets, other meshes, other animations, cameras, materials.
#include <string>
#include <vector>

#include "core/export/rig_import.h"
#include "core/scene/document.h"

namespace dfm {

using GltfImportReport = RigImportReport;

// Throws dfm::Error naming the file and the problem (no skinned mesh, a singular inverse bind matrix,
// joints or weights out of range, an animated scale, what read_gltf refuses).
SceneData import_gltf_scene(const std::string& path, GltfImportReport* report = nullptr);

// Registers import_gltf_scene for .glb and .gltf with core/scene/scene_import.h (the `open` command,
// the editor). Call once before opening files.
void register_gltf_scene_importer();

}  // namespace dfm
