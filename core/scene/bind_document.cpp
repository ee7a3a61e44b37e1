#include "core/scene/bind_document.h"

#include "core/util/error.h"

namespace dfm {

BindOptions bind_options(const Document& doc) {
  BindOptions o;
  o.volume = doc.bind_settings().volume;
  o.bbw.monotone = doc.bind_settings().monotone;
  o.additional_weights = doc.bind_settings().additional_weights;
  const Eigen::VectorXd& mask = doc.mask();
  if (mask.size() != doc.surface().num_vertices() || mask.size() == 0 || mask.maxCoeff() <= 0) return o;
  // The bind maps a per-user-vertex mask onto its volume (tet_mask_from_user_vertices). A tet input's
  // user vertices are its tet vertices: the painted boundary values go to theirs, interior ones stay 0.
  if (doc.has_tets()) {
    o.vertex_mask = Eigen::VectorXd::Zero(doc.tets().num_vertices());
    for (int i = 0; i < doc.surface().num_vertices(); ++i)
      o.vertex_mask[doc.data().surface_to_tet[i]] = kPaintedMaskRho * mask[i];
  } else {
    o.vertex_mask = kPaintedMaskRho * mask;
  }
  return o;
}

void apply_bind_result(Document& doc, const BindResult& r) {
  Eigen::MatrixXd W, E, A;
  if (doc.has_tets()) {
    const Eigen::VectorXi& map = doc.data().surface_to_tet;
    if (r.weights.rows() != doc.tets().num_vertices())
      throw Error("bind result has " + std::to_string(r.weights.rows()) + " rows but the tet mesh has " +
                  std::to_string(doc.tets().num_vertices()) + " vertices (the scene changed during the bind)");
    W.resize(map.size(), r.weights.cols());
    for (int i = 0; i < map.size(); ++i) W.row(i) = r.weights.row(map[i]);
    if (r.endpoint_weights.rows() == r.weights.rows()) {
      E.resize(map.size(), r.endpoint_weights.cols());
      for (int i = 0; i < map.size(); ++i) E.row(i) = r.endpoint_weights.row(map[i]);
    }
    if (r.additional_weights.rows() == r.weights.rows()) {
      A.resize(map.size(), r.additional_weights.cols());
      for (int i = 0; i < map.size(); ++i) A.row(i) = r.additional_weights.row(map[i]);
    }
  } else {
    W = r.weights;
    E = r.endpoint_weights;
    A = r.additional_weights;
  }
  BindStats st;
  st.seconds = r.report.total_seconds;
  st.tet_vertices = r.report.tet_vertices;
  st.tets = r.report.tets;
  st.notes = r.report.notes;
  if (A.cols() > 0)
    st.notes.push_back(std::to_string(A.cols()) + " additional weights (FAST's free handles, " +
                       std::to_string(static_cast<int>(1000 * r.report.additional_seconds)) + " ms)");
  doc.set_weights(W, st, E, A);  // checks #V x #handles against the current document
}

void run_bind_blocking(Document& doc, const BindOptions& extra) {
  if (doc.surface().num_vertices() == 0) throw Error("bind: no surface (open a mesh first)");
  if (doc.num_handles() == 0) throw Error("bind: the rig has no handles");
  BindOptions o = extra;
  const BindOptions from_doc = bind_options(doc);
  o.volume = from_doc.volume;
  o.additional_weights = from_doc.additional_weights;
  if (o.bbw.shape_mask.size() == 0 && o.vertex_mask.size() == 0) o.vertex_mask = from_doc.vertex_mask;
  const BindResult r = doc.has_tets() ? bind_tet_mesh(doc.tets(), doc.rig(), o) : bind_surface(doc.surface(), doc.rig(), o);
  apply_bind_result(doc, r);
}

}  // namespace dfm
