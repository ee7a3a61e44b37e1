#pragma once
// Building a Rig from files: TGF skeletons (bones, point handles = joints on no bone, pseudo-edges,
// cage edges), point lists and cage meshes.
#include <string>
#include <vector>

#include "core/mesh/io.h"
#include "core/rig/rig.h"

namespace dfm {

// Bones from TGF bone edges; joints touched by no bone become point handles (appended to rig.points
// after any already there); pseudo-edges between such joints become rig.pseudo_edges.
void add_tgf_to_rig(Rig& rig, const TgfData& tgf, const std::string& source_name);
TgfData rig_to_tgf(const Rig& rig);
// Point handles from a points file (one 'x y z' a line), appended to rig.points as "point 1", ...
// Throws dfm::Error naming the file when it holds no point.
void add_points_file_to_rig(Rig& rig, const std::string& path);

}  // namespace dfm
