// The document's bind as a worker job: the same core call as `deform bind` and scripts
// (bind_surface / bind_tet_mesh with bind_options(doc), so the painted shape-preservation mask is
// part of it), run on copies of the inputs. The UI thread stores the result with apply_bind_result.
#include "app/editor/bind_worker.h"
#include "core/scene/bind_document.h"
#include "core/util/error.h"

namespace dfm::editor {

namespace {
// The bind module's stage names, as the progress bar shows them.
std::string stage_label(const std::string& stage, bool tet_input) {
  if (stage == "meshing") return tet_input ? "checking the tet mesh" : "tetrahedralizing (TetGen)";
  if (stage == "assembly") return "assembling the energy";
  if (stage == "factorization") return "factorizing";
  if (stage == "solve") return "solving weights";
  if (stage == "mapping") return "mapping to the surface";
  if (stage == "endpoints") return "endpoint weights (joints)";
  if (stage == "additional") return "additional weights";
  return stage;
}
}  // namespace

BindJob make_document_bind_job(const Document& doc) {
  if (doc.surface().num_vertices() == 0) throw Error("nothing to bind: open a mesh first");
  if (doc.num_handles() == 0) throw Error("nothing to bind: add handles (points, bones or a cage) first");
  // Snapshot: the worker must not read the document while the UI edits it.
  struct Input {
    TriMesh surface;
    TetMesh tets;
    Rig rig;
    BindOptions options;
  };
  auto in = std::make_shared<Input>(Input{doc.has_tets() ? TriMesh{} : doc.surface(), doc.tets(), doc.rig(), bind_options(doc)});
  return [in](const std::function<void(const std::string&, double)>& progress,
              const std::atomic<bool>& cancel) -> BindOutcome {
    const bool tet_input = in->tets.num_tets() > 0;
    BindOptions o = in->options;
    o.cancel = &cancel;
    o.progress = [&](const std::string& stage, double f) { progress(stage_label(stage, tet_input), f); };
    BindOutcome out;
    out.result = std::make_shared<BindResult>(tet_input ? bind_tet_mesh(in->tets, in->rig, o)
                                                        : bind_surface(in->surface, in->rig, o));
    out.ok = true;
    return out;
  };
}

}  // namespace dfm::editor
