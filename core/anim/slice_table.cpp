#include "core/anim/slice_table.h"

#include <algorithm>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace dfm {

namespace {

// Derivation: on the reference tetrahedron (positive volume) put f = +1 on above vertices and -1 on
// below ones. The level set f = 0 crosses exactly the edges joining an above and a below vertex, at
// their midpoints. 3 crossings -> one triangle; 4 -> a planar quad, whose cyclic order walks
// a1-b1, a1-b2, a2-b2, a2-b1 (consecutive crossings share a vertex). Each polygon is then wound so its
// normal has a positive dot product with grad f, and a quad is split along its first diagonal.
std::array<SliceCase, 16> derive() {
  const Eigen::Vector3d ref[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  auto edge_of = [](int a, int b) {
    for (int e = 0; e < 6; ++e)
      if ((kSliceEdges[e][0] == a && kSliceEdges[e][1] == b) || (kSliceEdges[e][0] == b && kSliceEdges[e][1] == a))
        return e;
    return -1;
  };
  std::array<SliceCase, 16> table{};
  for (int mask = 0; mask < 16; ++mask) {
    std::vector<int> above, below;
    double f[4];
    for (int i = 0; i < 4; ++i) {
      const bool up = (mask >> i) & 1;
      (up ? above : below).push_back(i);
      f[i] = up ? 1.0 : -1.0;
    }
    std::vector<int> poly;  // edge indices in cyclic order
    if (above.size() == 1)
      for (int b : below) poly.push_back(edge_of(above[0], b));
    else if (below.size() == 1)
      for (int a : above) poly.push_back(edge_of(a, below[0]));
    else if (above.size() == 2)
      poly = {edge_of(above[0], below[0]), edge_of(above[0], below[1]), edge_of(above[1], below[1]),
              edge_of(above[1], below[0])};
    if (poly.empty()) continue;
    // grad f of the linear interpolant on the reference tetrahedron (its edges from vertex 0 are the axes).
    const Eigen::Vector3d grad(f[1] - f[0], f[2] - f[0], f[3] - f[0]);
    auto point = [&](int e) { return 0.5 * (ref[kSliceEdges[e][0]] + ref[kSliceEdges[e][1]]); };
    const Eigen::Vector3d n = (point(poly[1]) - point(poly[0])).cross(point(poly[2]) - point(poly[0]));
    if (n.dot(grad) < 0) std::reverse(poly.begin(), poly.end());
    SliceCase& c = table[mask];
    c.triangles[0] = {poly[0], poly[1], poly[2]};
    c.num_triangles = 1;
    if (poly.size() == 4) {
      c.triangles[1] = {poly[0], poly[2], poly[3]};
      c.num_triangles = 2;
    }
  }
  return table;
}

}  // namespace

const std::array<SliceCase, 16>& slice_table() {
  static const std::array<SliceCase, 16> table = derive();
  return table;
}

}  // namespace dfm
