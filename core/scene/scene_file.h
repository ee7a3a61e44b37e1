#pragma once
// The scene file: versioned JSON (small, readable fields) plus a binary sidecar for large arrays
// (surface, tets, weights, mask, cages, regions, mesh keys). The JSON names the sidecar, its byte size and a
// checksum (FNV-1a 64), and every array's offset/shape inside it. Saves are atomic: the sidecar is
// written first, then the JSON (so a crash never leaves a JSON pointing at a missing sidecar).
// Writing is deterministic: save -> load -> save gives byte-identical files.
#include <string>

#include "core/scene/document.h"

namespace dfm {

// 1: the first format. 2: a key may hold a mesh ("keys[i].mesh": source, V, F), a mesh key.
// Files of every version up to this one load; saves write this one.
constexpr int kSceneFormatVersion = 2;

// "<dir>/x.scene.json" -> "<dir>/x.scene.bin" (any other name: path + ".bin").
std::string scene_sidecar_path(const std::string& json_path);
// "<dir>/x.scene.json" -> "<dir>/x.autosave.scene.json" (any other name: path + ".autosave.json").
std::string autosave_path(const std::string& scene_path);

void write_scene(const std::string& json_path, const SceneData& scene);
// Throws dfm::Error naming the file (JSON or sidecar) and the problem: bad JSON, unknown version,
// missing/short/corrupt sidecar (size or checksum mismatch), arrays out of range, indices out of
// range, NaN/inf, inconsistent sizes.
SceneData read_scene(const std::string& json_path);

}  // namespace dfm
