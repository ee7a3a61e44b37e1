#pragma once
// This program's rig carried through a glTF file (issue 32's round trip): the export writes it as JSON
// text in the "rig" node's extras ("deform_rig"), which other programs keep as a custom property and
// ignore, and the import rebuilds the same handles from it: point handles, bones with their tails and
// names, cages, regions and pseudo-edges, in handle order (rig.h), one per skin joint.
#include <string>

#include "core/rig/rig.h"

namespace dfm {

// The rig as JSON text (inline arrays).
std::string rig_extras_json(const Rig& rig);

// The rig from that text. Throws dfm::Error naming `what` when the text is not such a rig: not JSON,
// a field missing or of the wrong kind, a coordinate not finite, an index out of range (joints, cage
// vertices, regions' surface vertices below num_surface_vertices, pseudo-edges' points).
Rig rig_from_extras_json(const std::string& text, int num_surface_vertices, const std::string& what);

}  // namespace dfm
