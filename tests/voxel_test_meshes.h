#pragma once
// Closed test surfaces built from unit voxels: the boundary of a union of cubes, each cube face split
// into s x s squares of two triangles, outward. Inside is known exactly (the voxel containing a point),
// so segmentations can be scored without trusting any winding-number code.
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <vector>

#include <Eigen/Core>

#include "core/mesh/mesh.h"

namespace dfm::test {

using Voxel = std::array<int, 3>;

struct VoxelShape {
  std::set<Voxel> voxels;
  bool contains(const Eigen::Vector3d& p) const {
    return voxels.count({static_cast<int>(std::floor(p(0))), static_cast<int>(std::floor(p(1))),
                         static_cast<int>(std::floor(p(2)))}) > 0;
  }
  void add_box(Voxel lo, Voxel hi) {  // voxels lo <= v < hi
    for (int x = lo[0]; x < hi[0]; ++x)
      for (int y = lo[1]; y < hi[1]; ++y)
        for (int z = lo[2]; z < hi[2]; ++z) voxels.insert({x, y, z});
  }
  void remove_box(Voxel lo, Voxel hi) {
    for (int x = lo[0]; x < hi[0]; ++x)
      for (int y = lo[1]; y < hi[1]; ++y)
        for (int z = lo[2]; z < hi[2]; ++z) voxels.erase({x, y, z});
  }
};

// The boundary faces; `face_tag` receives, per triangle, the voxel and the outward axis/sign (0..5:
// -x +x -y +y -z +z) it came from, so tests can pick patches to damage.
struct TaggedFace {
  Voxel voxel;
  int side;
};
inline TriMesh voxel_surface(const VoxelShape& shape, int s, std::vector<TaggedFace>* tags = nullptr) {
  std::map<std::array<int, 3>, int> index;  // lattice point (units of 1/s) -> vertex
  std::vector<Eigen::Vector3d> V;
  std::vector<std::array<int, 3>> F;
  auto vertex = [&](const std::array<int, 3>& q) {
    auto [it, fresh] = index.emplace(q, static_cast<int>(V.size()));
    if (fresh) V.push_back(Eigen::Vector3d(q[0], q[1], q[2]) / s);
    return it->second;
  };
  for (const Voxel& v : shape.voxels)
    for (int side = 0; side < 6; ++side) {
      const int axis = side / 2, dir = side % 2 ? 1 : -1;
      Voxel n = v;
      n[axis] += dir;
      if (shape.voxels.count(n)) continue;
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;  // (u, w, axis) is right-handed
      for (int i = 0; i < s; ++i)
        for (int j = 0; j < s; ++j) {
          std::array<int, 4> c;
          for (int k = 0; k < 4; ++k) {
            std::array<int, 3> q;
            q[axis] = (v[axis] + (dir > 0 ? 1 : 0)) * s;
            q[u] = v[u] * s + i + (k == 1 || k == 2);
            q[w] = v[w] * s + j + (k >= 2);
            c[k] = vertex(q);
          }
          // c0 (0,0) c1 (1,0) c2 (1,1) c3 (0,1) in (u, w): counter-clockwise about +axis.
          if (dir > 0) F.push_back({c[0], c[1], c[2]}), F.push_back({c[0], c[2], c[3]});
          else F.push_back({c[0], c[2], c[1]}), F.push_back({c[0], c[3], c[2]});
          if (tags) tags->push_back({v, side}), tags->push_back({v, side});
        }
    }
  TriMesh m;
  m.V.resize(V.size(), 3);
  for (size_t i = 0; i < V.size(); ++i) m.V.row(i) = V[i].transpose();
  m.F.resize(F.size(), 3);
  for (size_t i = 0; i < F.size(); ++i) m.F.row(i) << F[i][0], F[i][1], F[i][2];
  return m;
}

// The messy copy of a voxel surface: triangles whose tag matches `punch` are dropped (holes), those
// matching `flip` reversed, those matching `duplicate` added twice.
using FacePredicate = std::function<bool(const TaggedFace&)>;
inline TriMesh mess_up(const TriMesh& m, const std::vector<TaggedFace>& tags, const FacePredicate& punch,
                       const FacePredicate& flip, const FacePredicate& duplicate) {
  std::vector<Eigen::RowVector3i> F;
  for (int f = 0; f < m.F.rows(); ++f) {
    if (punch(tags[f])) continue;
    Eigen::RowVector3i t = m.F.row(f);
    if (flip(tags[f])) std::swap(t(1), t(2));
    F.push_back(t);
    if (duplicate(tags[f])) F.push_back(t);
  }
  TriMesh out;
  out.V = m.V;
  out.F.resize(F.size(), 3);
  for (size_t i = 0; i < F.size(); ++i) out.F.row(i) = F[i];
  return out;
}

}  // namespace dfm::test
