#include "core/export/export_document.h"

#include <filesystem>

#include "core/rig/forward_kinematics.h"
#include "core/scene/key_surfaces.h"
#include "core/util/error.h"

namespace dfm {

namespace {

bool twisted_or_stretched(const PoseParams& p) {
  for (const BoneTwistStretch& ts : p.bone_twist_stretch)
    if (!is_rest_twist_stretch(ts)) return true;
  return false;
}

// Whether what the document shows differs from LBS of its poses: another method, or a twisted or
// stretched bone in the current pose or a pose key.
bool skins_more_than_lbs(const Document& doc) {
  if (doc.method() != SkinMethod::LBS || twisted_or_stretched(doc.pose_params())) return true;
  for (const SceneKey& k : doc.keys())
    if (!k.is_mesh() && twisted_or_stretched(k.params)) return true;
  return false;
}

// ... or additional handles (baked: export_document.h).
bool shows_more_than_lbs(const Document& doc) { return skins_more_than_lbs(doc) || doc.num_additional() > 0; }

}  // namespace

GltfExportInput gltf_input_from_document(const Document& doc) {
  if (doc.surface().num_vertices() == 0) throw Error("glTF export: the document has no surface");
  if (!doc.has_weights())
    throw Error("glTF export: the document has no weights (" +
                (doc.weights_note().empty() ? std::string("not bound") : doc.weights_note()) + "); bind first");
  GltfExportInput in;
  const std::string from = !doc.path().empty() ? doc.path() : doc.surface_path();
  std::filesystem::path stem = std::filesystem::path(from).stem();
  if (stem.extension() == ".scene") stem = stem.stem();  // x.scene.json -> x
  in.name = stem.empty() ? "mesh" : stem.string();
  in.surface = doc.surface();
  in.rig = doc.rig();
  in.weights = doc.weights();
  in.current = doc.pose();
  const std::vector<double> times = doc.key_times();
  const std::vector<Pose> poses = doc.key_poses();
  for (size_t k = 0; k < times.size(); ++k)
    if (!doc.keys()[k].is_mesh()) in.keys.push_back({times[k], poses[k]});  // glTF skins one mesh
  if (shows_more_than_lbs(doc)) {  // the residual targets then carry the method, twist and stretch
    const SkinBinding binding = pose_binding(doc);
    for (const SceneKey& k : doc.keys())
      if (!k.is_mesh()) in.exact.push_back(skin_params(doc, binding, k.params));
    in.exact.push_back(skin_params(doc, binding, doc.pose_params()));
  }
  return in;
}

GltfExportReport export_document_gltf(const Document& doc, const std::string& path, const GltfExportOptions& options) {
  GltfExportReport r = export_gltf(path, gltf_input_from_document(doc), options);
  int mesh_keys = 0;
  for (const SceneKey& k : doc.keys()) mesh_keys += k.is_mesh();
  if (mesh_keys > 0)
    r.notes.push_back(std::to_string(mesh_keys) + " mesh key(s) left out: a glTF skin animates one mesh, so only the "
                      "pose keys are exported");
  if (doc.num_additional() > 0)
    r.notes.push_back(std::to_string(doc.num_additional()) + " additional weights baked (glTF joint weights sum to 1): " +
                      (r.residual_targets > 0 ? "the residual morph targets carry them at the keys and the current pose, "
                                                "blending linearly in between"
                                              : "the file plays the bind's weights alone (residual morph targets would "
                                                "carry them)"));
  if (skins_more_than_lbs(doc))
    r.notes.push_back(std::string("the document skins with ") + skin_method_name(doc.method()) +
                      (is_stbs(doc.method()) ? " (twist and stretch)" : "") +
                      "; glTF skinning is linear (LBS): " +
                      (r.residual_targets > 0 ? "the residual morph targets make its keys and current pose the document's "
                                                "surface; between keys the correction blends linearly"
                                              : "the file plays LBS with these weights (residual morph targets would "
                                                "carry the difference)"));
  return r;
}

}  // namespace dfm
