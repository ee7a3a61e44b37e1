#include "core/rig/rig.h"

#include <functional>

#include "core/util/error.h"

namespace dfm {

int num_point_handles(const Rig& rig) { return static_cast<int>(rig.points.size()); }

int num_cage_vertices(const Rig& rig) {
  int n = 0;
  for (const Cage& c : rig.cages) n += c.mesh.num_vertices();
  return n;
}

int num_handles(const Rig& rig) {
  return num_point_handles(rig) + rig.skeleton.num_bones() + num_cage_vertices(rig) +
         static_cast<int>(rig.regions.size());
}

HandleRef handle_ref(const Rig& rig, int h) {
  if (h < 0 || h >= num_handles(rig)) throw Error("handle index " + std::to_string(h) + " out of range");
  if (h < num_point_handles(rig)) return {HandleKind::Point, h};
  h -= num_point_handles(rig);
  if (h < rig.skeleton.num_bones()) return {HandleKind::Bone, h};
  h -= rig.skeleton.num_bones();
  for (int c = 0; c < static_cast<int>(rig.cages.size()); ++c) {
    int n = rig.cages[c].mesh.num_vertices();
    if (h < n) return {HandleKind::CageVertex, h, c};
    h -= n;
  }
  return {HandleKind::Region, h};
}

int handle_index(const Rig& rig, const HandleRef& r) {
  switch (r.kind) {
    case HandleKind::Point: return r.index;
    case HandleKind::Bone: return num_point_handles(rig) + r.index;
    case HandleKind::CageVertex: {
      int base = num_point_handles(rig) + rig.skeleton.num_bones();
      for (int c = 0; c < r.cage; ++c) base += rig.cages[c].mesh.num_vertices();
      return base + r.index;
    }
    case HandleKind::Region:
      return num_point_handles(rig) + rig.skeleton.num_bones() + num_cage_vertices(rig) + r.index;
  }
  return -1;
}

const char* handle_kind_name(HandleKind k) {
  switch (k) {
    case HandleKind::Point: return "point";
    case HandleKind::Bone: return "bone";
    case HandleKind::CageVertex: return "cage vertex";
    case HandleKind::Region: return "region";
  }
  return "?";
}

std::string handle_name(const Rig& rig, int h) {
  HandleRef r = handle_ref(rig, h);
  std::string given;
  switch (r.kind) {
    case HandleKind::Point: given = rig.points[r.index].name; break;
    case HandleKind::Bone: given = rig.skeleton.bones[r.index].name; break;
    case HandleKind::CageVertex:
      given = (rig.cages[r.cage].name.empty() ? "cage " + std::to_string(r.cage) : rig.cages[r.cage].name) +
              " vertex " + std::to_string(r.index);
      break;
    case HandleKind::Region: given = rig.regions[r.index].name; break;
  }
  if (!given.empty()) return given;
  return std::string(handle_kind_name(r.kind)) + " " + std::to_string(r.index);
}

void compute_bone_parents(Skeleton& s) {
  for (Bone& b : s.bones) {
    b.parent = -1;
    for (int k = 0; k < s.num_bones(); ++k)
      if (s.bones[k].b == b.a && &s.bones[k] != &b) {
        b.parent = k;
        break;
      }
  }
  bones_topological_order(s);  // throws on cycles
}

std::vector<int> bones_topological_order(const Skeleton& s) {
  const int n = s.num_bones();
  std::vector<int> order, state(n, 0);  // 0 new, 1 visiting, 2 done
  std::function<void(int)> visit = [&](int i) {
    if (state[i] == 2) return;
    if (state[i] == 1) throw Error("skeleton has a cycle of bones through bone " + std::to_string(i));
    state[i] = 1;
    int p = s.bones[i].parent;
    if (p >= 0 && p < n) visit(p);
    state[i] = 2;
    order.push_back(i);
  };
  for (int i = 0; i < n; ++i) visit(i);
  return order;
}

}  // namespace dfm
