#pragma once
// The Sculpt tool's session (issue 37; Jacobson 2013 ch. 3, core/sculpt/variational_deform.h): a free
// region painted on a base surface (the rest of it is fixed), a handle inside the region, and the
// handle's translation; the free vertices between take the biharmonic (order 2, C1) or triharmonic
// (order 3, C2) displacement. Tool state held by the Document, like the selection: not saved and not
// undoable; keying the result (Document::sculpt_key) is the undoable edit.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/mesh/mesh.h"

namespace dfm {

struct SculptSession {
  // What is sculpted: the mesh key at the document's time when the session started (its index then),
  // else the rest surface (-1). A region or handle change after a move keeps the result as the new base
  // (strokes accumulate, as in a sculpting program), so base is the shape the current move starts from.
  int source_key = -1;
  TriMesh base;                  // positions and triangles (no normals)
  std::vector<char> region;      // per vertex: 1 = free (painted); the rest of the surface is fixed
  std::vector<int> handle;       // the handle's vertices, all inside the region, in index order
  int order = 2;                 // 2: smooth (C1), 3: very smooth (C2)
  Eigen::Vector3d move = Eigen::Vector3d::Zero();  // the handle's translation since the base
  Eigen::MatrixXd result;        // base deformed by move (base.V until a move)
  std::uint64_t revision = 0;    // bumped on every change (the view re-uploads the result)
  int region_count() const;
};

}  // namespace dfm
