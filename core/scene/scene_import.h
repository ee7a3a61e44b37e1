#pragma once
// File formats that other modules turn into whole scenes (core/export's glTF, FBX and Collada import): the `open`
// command, File > Open and `deform-editor FILE` read them through this table, so core/scene needs no
// reader of its own for them. A program registers what it links (gltf_scene_import.h's
// register_gltf_scene_importer, assimp_scene_import.h's register_assimp_scene_importers) before it
// opens files.
#include <functional>
#include <string>
#include <vector>

#include "core/scene/document.h"

namespace dfm {

// Reads `path` as a scene; `report` gets what was imported (lines for the notes). Throws dfm::Error.
using SceneImporter = std::function<SceneData(const std::string& path, std::string& report)>;

// extension: lower case, without the dot ("glb"). A later registration replaces an earlier one.
void register_scene_importer(const std::string& extension, SceneImporter importer);
// The importer for a path's extension, or null.
const SceneImporter* scene_importer_for(const std::string& path);

// Motion files (core/export's BVH) read onto a scene's rig: keys that replace the scene's, and in
// `report` what matched (Document::load_motion, the load-motion command). Throws dfm::Error.
using MotionImporter = std::function<std::vector<SceneKey>(const SceneData& scene, const std::string& path, std::string& report)>;
void register_motion_importer(const std::string& extension, MotionImporter importer);
const MotionImporter* motion_importer_for(const std::string& path);

}  // namespace dfm
