#include "core/rig/handle_deletion.h"

#include <string>

#include "core/util/error.h"

namespace dfm {

namespace {

template <class T>
void erase_at(std::vector<T>& v, int i) {
  if (i >= 0 && i < static_cast<int>(v.size())) v.erase(v.begin() + i);
}

// Removes bone indices (descending) and then every joint no remaining bone uses.
void delete_bones(Skeleton& sk, const std::set<int>& bones) {
  for (auto it = bones.rbegin(); it != bones.rend(); ++it) sk.bones.erase(sk.bones.begin() + *it);
  std::vector<int> remap(sk.num_joints(), -1);
  for (const Bone& b : sk.bones) remap[b.a] = remap[b.b] = 0;
  int k = 0;
  for (int& r : remap)
    if (r == 0) r = k++;
  Eigen::MatrixXd J(k, 3);
  for (int j = 0; j < static_cast<int>(remap.size()); ++j)
    if (remap[j] >= 0) J.row(remap[j]) = sk.joints.row(j);
  sk.joints = J;
  for (Bone& b : sk.bones) {
    b.a = remap[b.a];
    b.b = remap[b.b];
  }
  compute_bone_parents(sk);
}

// Drops the pseudo-edges of point i and renumbers the points after it.
void delete_point_edges(std::vector<std::pair<int, int>>& edges, int i) {
  std::vector<std::pair<int, int>> kept;
  for (auto [a, b] : edges) {
    if (a == i || b == i) continue;
    kept.push_back({a > i ? a - 1 : a, b > i ? b - 1 : b});
  }
  edges = kept;
}

}  // namespace

HandleDeletion plan_handle_deletion(const Rig& rig, const std::vector<int>& handles) {
  const int n = num_handles(rig);
  for (int h : handles)
    if (h < 0 || h >= n) throw Error("no handle " + std::to_string(h));
  HandleDeletion d;
  for (int h : handles) {
    const HandleRef r = handle_ref(rig, h);
    switch (r.kind) {
      case HandleKind::Point: d.points.insert(r.index); break;
      case HandleKind::Bone: d.bones.insert(r.index); break;
      case HandleKind::CageVertex: d.cages.insert(r.cage); break;
      case HandleKind::Region: d.regions.insert(r.index); break;
    }
  }
  int base = 0;
  for (int c = 0; c < static_cast<int>(rig.cages.size()); ++c) {
    const int nv = rig.cages[c].mesh.num_vertices();
    if (d.cages.count(c)) d.cage_vertices.push_back({base, base + nv});
    base += nv;
  }
  d.new_handle.assign(n, -1);
  for (int h = 0, kept = 0; h < n; ++h) {
    const HandleRef r = handle_ref(rig, h);
    const bool gone = (r.kind == HandleKind::Point && d.points.count(r.index)) ||
                      (r.kind == HandleKind::Bone && d.bones.count(r.index)) ||
                      (r.kind == HandleKind::CageVertex && d.cages.count(r.cage)) ||
                      (r.kind == HandleKind::Region && d.regions.count(r.index));
    if (!gone) d.new_handle[h] = kept++;
  }
  return d;
}

void delete_handles(Rig& rig, const HandleDeletion& d) {
  for (auto it = d.cages.rbegin(); it != d.cages.rend(); ++it) rig.cages.erase(rig.cages.begin() + *it);
  for (auto it = d.regions.rbegin(); it != d.regions.rend(); ++it) rig.regions.erase(rig.regions.begin() + *it);
  for (auto it = d.points.rbegin(); it != d.points.rend(); ++it) {
    rig.points.erase(rig.points.begin() + *it);
    delete_point_edges(rig.pseudo_edges, *it);
  }
  if (!d.bones.empty()) delete_bones(rig.skeleton, d.bones);
}

void delete_handles(PoseParams& p, const HandleDeletion& d) {
  for (auto it = d.cage_vertices.rbegin(); it != d.cage_vertices.rend(); ++it)
    if (static_cast<int>(p.cage_translation.size()) >= it->second)
      p.cage_translation.erase(p.cage_translation.begin() + it->first, p.cage_translation.begin() + it->second);
  for (auto it = d.regions.rbegin(); it != d.regions.rend(); ++it) erase_at(p.region_transform, *it);
  for (auto it = d.points.rbegin(); it != d.points.rend(); ++it) {
    erase_at(p.point_translation, *it);
    erase_at(p.point_rotation, *it);
  }
  for (auto it = d.bones.rbegin(); it != d.bones.rend(); ++it) {
    erase_at(p.bone_rotation, *it);
    erase_at(p.bone_translation, *it);
    erase_at(p.bone_twist_stretch, *it);
  }
  std::map<int, Eigen::Affine3d> solved;
  for (const auto& [h, T] : p.solved)
    if (h >= 0 && h < static_cast<int>(d.new_handle.size()) && d.new_handle[h] >= 0) solved.emplace(d.new_handle[h], T);
  p.solved = std::move(solved);
}

}  // namespace dfm
