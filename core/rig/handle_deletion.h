#pragma once
// Deleting handles from a rig and from pose parameters sized for it: rig surgery in one place, for the
// document's delete command. A cage vertex deletes its whole cage (a cage's vertices go together);
// a deleted point takes its pseudo-edges along, and joints no remaining bone uses are dropped.
#include <set>
#include <utility>
#include <vector>

#include "core/rig/pose_params.h"
#include "core/rig/rig.h"

namespace dfm {

// What a deletion removes, worked out on the rig before it.
struct HandleDeletion {
  std::set<int> points, bones, cages, regions;     // indices within their kinds
  std::vector<std::pair<int, int>> cage_vertices;  // [begin, end) of each deleted cage's vertices, concatenated
  std::vector<int> new_handle;                     // old handle index -> new one, -1 for a deleted handle
  bool empty() const { return points.empty() && bones.empty() && cages.empty() && regions.empty(); }
};

// Throws dfm::Error naming a handle out of range.
HandleDeletion plan_handle_deletion(const Rig& rig, const std::vector<int>& handles);

// Removes the planned handles from the rig the plan was made on: points (pseudo-edges renumbered),
// bones (unused joints dropped, joints renumbered, parents recomputed), cages, regions.
void delete_handles(Rig& rig, const HandleDeletion& d);

// Removes their entries from pose parameters (every per-handle vector; entries a short vector lacks
// are skipped) and renumbers the solved transforms, dropping the deleted handles'.
void delete_handles(PoseParams& p, const HandleDeletion& d);

}  // namespace dfm
