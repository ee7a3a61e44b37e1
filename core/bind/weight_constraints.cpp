#include "core/bind/weight_constraints.h"

#include <algorithm>
#include <string>

#include "core/bind/handle_geometry.h"
#include "core/mesh/mesh_info.h"
#include "core/util/error.h"

namespace dfm {

std::vector<bool> WeightConstraints::mask(int num_vertices) const {
  std::vector<bool> m(num_vertices, false);
  for (int i = 0; i < b.size(); ++i)
    if (b(i) >= 0 && b(i) < num_vertices) m[b(i)] = true;
  return m;
}

WeightConstraints surface_weight_constraints(const Eigen::MatrixXd& V, const Rig& rig, double rel_tol) {
  const int nv = static_cast<int>(V.rows()), nh = num_handles(rig);
  const CageSoup cages = stack_cages(rig);
  Eigen::MatrixXd all(nv + cages.V.rows(), 3);
  all << V, cages.V;
  const double tol = rel_tol * bounding_box(all).diagonal().norm();
  BoundaryRows rows;
  if (tol > 0) {
    PointWelder grid(tol);  // a lookup over the surface vertices
    for (int i = 0; i < nv; ++i) grid.insert(V.row(i).transpose());
    // Point handles and cage vertices (bone samples are covered by the segment test below).
    for (const HandleSample& s : sample_handles(rig, 0)) {
      if (handle_ref(rig, s.handle).kind == HandleKind::Bone) continue;
      const int v = grid.find(s.x);
      if (v >= 0) rows.add(v, s.w);
    }
  }
  const Skeleton& sk = rig.skeleton;
  for (int i = 0; i < sk.num_bones(); ++i) {
    const Bone& bone = sk.bones[i];
    if (bone.a < 0 || bone.b < 0 || bone.a >= sk.num_joints() || bone.b >= sk.num_joints()) continue;
    const int h = handle_index(rig, {HandleKind::Bone, i});
    const Eigen::Vector3d a = sk.joints.row(bone.a).transpose(), d = sk.joints.row(bone.b).transpose() - a;
    const double l2 = d.squaredNorm();
    for (int v = 0; v < nv; ++v) {
      const Eigen::Vector3d p = V.row(v).transpose();
      const double t = l2 > 0 ? std::clamp((p - a).dot(d) / l2, 0.0, 1.0) : 0.0;
      if ((a + t * d - p).norm() <= tol) rows.add(v, {{h, 1.0}});
    }
  }
  for (int r = 0; r < static_cast<int>(rig.regions.size()); ++r) {
    const int h = handle_index(rig, {HandleKind::Region, r});
    for (int u : rig.regions[r].vertices) {
      if (u < 0 || u >= nv)
        throw Error("region \"" + handle_name(rig, h) + "\": vertex " + std::to_string(u) + " out of range");
      rows.add(u, {{h, 1.0}});
    }
  }
  add_cage_surface_rows(V, cages, tol, rows);
  WeightConstraints c;
  rows.finish(nh, c.b, c.bc);
  return c;
}

}  // namespace dfm
