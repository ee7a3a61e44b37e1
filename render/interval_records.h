#pragma once
// What one interval's slice topology (core/anim/interval_slice.h) uploads to the GPU: an
// IntervalVertex record per slice vertex (both endpoints of its manifold edge, their 3D slice normals,
// mu = A + B (t - t_lo) with A and B computed in double) and the triangles as uint32 indices. No GL,
// so a worker thread prepares it while another interval plays (app/editor/interval_prefetch.h).
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/anim/interval_slice.h"
#include "core/anim/manifold.h"
#include "render/vertex_format.h"

namespace dfm::gl {

struct IntervalRecords {
  std::vector<IntervalVertex> vertices;
  std::vector<std::uint32_t> indices;  // 3 per triangle
};

// vertex_normals4: the manifold's unit 4D vertex normals (manifold_vertex_normals). Throws dfm::Error
// on normals of the wrong size, an edge vertex or triangle index out of range, or an edge that does
// not go forward in time.
IntervalRecords interval_records(const IntervalSlice& interval, const AnimationManifold& m,
                                 const Eigen::MatrixXd& vertex_normals4);

}  // namespace dfm::gl
