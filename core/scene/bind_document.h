#pragma once
// Binding a Document: the bind module's options from the document's settings, and storing a result.
// The editor runs dfm::bind_surface / bind_tet_mesh on its worker thread with copies of the surface,
// tets and rig, then calls apply_bind_result on the UI thread (one undo step). A document edited
// while the bind ran refuses the result (sizes no longer match) with a dfm::Error.
#include "core/bind/bind.h"
#include "core/scene/document.h"

namespace dfm {

// rho of a fully painted vertex (mask 1): painted tets ~1000x stiffer than the biharmonic term, so
// they move nearly rigidly (bbw.h scales rho to be unitless; 1 would barely show).
constexpr double kPaintedMaskRho = 1e3;

// Volume options from the document, and the painted mask (scaled by kPaintedMaskRho) as vertex_mask,
// which the bind maps onto its volume: per surface vertex for a surface input, per tet vertex for a
// tet-mesh input (boundary vertices painted, interior ones 0).
BindOptions bind_options(const Document& doc);
// Weights on the surface vertices (rows picked through surface_to_tet for a tet input) + stats.
void apply_bind_result(Document& doc, const BindResult& result);
// Both, in the calling thread (scripts, tests, the CLI).
void run_bind_blocking(Document& doc, const BindOptions& extra = {});

}  // namespace dfm
