#pragma once
// glTF export of an editor document (File > Export, `deform export SCENE`): its surface, rig, weights,
// current pose and keys go through export_gltf (gltf_export.h).
//
// Additional weights (Jacobson 2013, 7.3.3; core/rig/additional_handles.h) are BAKED, not exported as
// joints: glTF asks a vertex's joint weights to sum to 1 (additional weights do not) and a joint node
// holds only a TRS (an additional handle's transform is any affine, zero when unsolved). The file's
// joints are the rig's handles with the bind's weights; the document's surface with the additional
// handles goes in GltfExportInput::exact, so with residual morph targets on
// (residual_morph_tolerance > 0, what File > Export and `deform export --residual-morphs` use) the file
// shows it at every key and at the current pose, blending the correction linearly in between.
#include <string>

#include "core/export/gltf_export.h"
#include "core/scene/document.h"

namespace dfm {

// The document as export input: name = the scene file's (else the surface file's) stem, or "mesh";
// surface = doc.surface() (a tet input's boundary surface), weights = doc.weights(), current = doc.pose(),
// keys = doc.key_times() / doc.key_poses(). Throws dfm::Error when the document has no surface or no
// valid weights (the message carries weights_note(), e.g. "not bound yet").
GltfExportInput gltf_input_from_document(const Document& doc);

// Writes `path` (.glb, or .gltf + .bin). glTF skins linearly: for a document that skins with DQS or
// STBS the report gets a note that the file plays LBS; with additional weights, a note on their baking. Throws dfm::Error as above and as export_gltf.
GltfExportReport export_document_gltf(const Document& doc, const std::string& path,
                                      const GltfExportOptions& options = {});

}  // namespace dfm
