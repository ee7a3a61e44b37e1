// The document's bind as a worker job: volume (TetGen or the given tet mesh), then BBW weights,
// mapped back to the surface vertices. Progress stages are reported to the UI.
#include <chrono>

#include "app/editor/bind_worker.h"
#include "core/bind/bbw.h"
#include "core/bind/bind_volume.h"
#include "core/util/error.h"

namespace dfm::editor {

BindJob make_document_bind_job(const Document& doc) {
  if (doc.surface().num_vertices() == 0) throw Error("nothing to bind: open a mesh first");
  if (doc.num_handles() == 0) throw Error("nothing to bind: add handles (points, bones or a cage) first");
  // Snapshot: the worker must not read the document while the UI edits it.
  struct Input {
    TriMesh surface;
    TetMesh tets;
    Rig rig;
    BindSettings settings;
  };
  auto in = std::make_shared<Input>(Input{doc.surface(), doc.tets(), doc.rig(), doc.bind_settings()});
  return [in](const std::function<void(const std::string&, double)>& progress,
              const std::atomic<bool>& cancel) -> BindOutcome {
    const auto t0 = std::chrono::steady_clock::now();
    BindOutcome out;
    progress(in->tets.num_tets() > 0 ? "checking tet mesh" : "tetrahedralizing (TetGen)", 0.02);
    BindVolume vol = in->tets.num_tets() > 0 ? bind_volume_from_tets(in->tets, in->rig)
                                             : build_bind_volume(in->surface, in->rig, in->settings.volume);
    if (cancel) throw Error("cancelled");
    BbwOptions opts;
    opts.cancel = &cancel;
    opts.progress = [&](const std::string& stage, double f) { progress(stage, 0.15 + 0.8 * f); };
    BbwStats stats;
    progress("solving weights", 0.15);
    const Eigen::MatrixXd Wt = bbw_weights(vol.tets.V, vol.tets.T, vol.b, vol.bc, opts, &stats);
    progress("mapping to the surface", 0.97);
    Eigen::MatrixXd W = vol.to_user * Wt;
    // Rows sum to one on the surface too (the map interpolates).
    for (int i = 0; i < W.rows(); ++i) {
      const double s = W.row(i).sum();
      if (s > 0) W.row(i) /= s;
    }
    out.ok = true;
    out.weights = std::move(W);
    out.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    out.stats.tet_vertices = vol.tets.num_vertices();
    out.stats.tets = vol.tets.num_tets();
    out.stats.notes = vol.notes;
    progress("done", 1.0);
    return out;
  };
}

}  // namespace dfm::editor
