#pragma once
// A rigged, animated FBX (.fbx) or Collada (.dae) file as a scene, read with Assimp (issue 32), as
// gltf_scene_import.h does for glTF: the skinned mesh welded, one bone per joint, the file's weights
// (the scene counts as bound), the first animation as pose keys.
//
// - Mesh: every mesh with bones (Assimp splits one mesh per material), welded by position. Assimp
//   skins a vertex v as G_j(t) offset_j v, without its mesh node's transform, so the rest pose is that
//   at the nodes' own transforms: the mesh sits at G_b offset_b for its first bone b. Meshes without
//   bones are skipped (said in the report).
// - Frame: Collada's up axis and unit Assimp applies (its root node). FBX: the axes its GlobalSettings
//   name (UpAxis, FrontAxis, CoordAxis and their signs) turned to y up, z front, x right, and lengths
//   in metres (UnitScaleFactor is centimetres per unit: Blender's scale-100 objects come back to
//   Blender's metres), so Blender's exports sit where glTF's do.
// - Bones: one per joint (a node a mesh's bone names), in the node tree's depth-first order, from the
//   bind pose the offset matrices give (bind_j = G_b offset_b offset_j^-1) by import_skeleton's rule
//   (rig_import.h). A leaf joint's child node that is not a joint (FBX's added `*_end` leaf bones) is
//   its bone's tail, and no bone is made of it. Names are the nodes' (Collada: their names, not ids).
// - Weights: every bone's (vertex, weight) list, rows normalized.
// - Animation: the first animation at each of its key times in seconds (ticks / ticks per second: in
//   Blender's FBX frame f is (f - 1) / fps, in its Collada f / fps), sampled as Assimp defines it; a
//   key reproduces each joint matrix C G_j(t) bind_j^-1 exactly (key_params).
// - Not imported (said in the report): meshes without bones, morph targets, other animations.
#include <string>

#include "core/export/rig_import.h"
#include "core/scene/document.h"

namespace dfm {

// Throws dfm::Error naming the file and the problem (not an FBX / Collada file, what Assimp refuses, no
// skinned mesh, a bone naming no node, weights out of range, a singular offset matrix, an animated scale).
SceneData import_assimp_scene(const std::string& path, RigImportReport* report = nullptr);

// Registers import_assimp_scene for .fbx and .dae, and a BVH opened alone (bvh_motion.h) for .bvh, with
// core/scene/scene_import.h; and BVH motion onto the document's rig (Document::load_motion).
void register_assimp_scene_importers();

}  // namespace dfm
