// The table's space-time edit commands (SCRIPT.md; issue 35): edit-region, edit-drag, edit-clear.
#include <algorithm>

#include "core/anim/manifold_sequence.h"
#include "core/scene/command_parts.h"
#include "core/scene/key_surfaces.h"
#include "core/util/error.h"

namespace dfm::command_detail {
namespace {

// The keys' manifold with the first `count` edits replayed: what edit `count` is made on.
AnimationManifold manifold_before(const Document& doc, size_t count) {
  if (doc.keys().size() < 2) throw Error("a space-time edit needs an animation: key at least two poses");
  AnimationManifold m = build_manifold_sequence(key_surfaces(doc));
  const std::vector<SpaceTimeEdit>& all = doc.space_time_edits();
  apply_space_time_edits(m, std::vector<SpaceTimeEdit>(all.begin(), all.begin() + std::min(count, all.size())));
  return m;
}

bool moves(const SpaceTimeEdit& e) {
  return e.move != Eigen::Vector3d::Zero() || e.rotation.coeffs() != Eigen::Quaterniond::Identity().coeffs() ||
         e.retime != 0;
}

// Starts an edit: the region and window, no move yet (a still edit changes nothing).
void edit_region(CommandContext& x, const CommandWords& w) {
  SpaceTimeEdit e;
  e.region.center = {num(w, 1), num(w, 2), num(w, 3)};
  e.region.radius = num(w, 4);
  e.region.t0 = num(w, 5);
  e.region.t1 = num(w, 6);
  e.handle.point = e.region.center;
  e.handle.time = std::clamp(x.doc.time(), e.region.t0, e.region.t1);
  check_space_time_edit(e);
  const AnimationManifold m = manifold_before(x.doc, x.doc.space_time_edits().size());
  if (e.region.t1 <= m.times.front() || e.region.t0 >= m.times.back())
    throw Error("the window [" + w[5] + ", " + w[6] + "] is outside the animation [" + std::to_string(m.times.front()) +
                ", " + std::to_string(m.times.back()) + "]");
  bool any = false;
  for (int v = 0; v < m.num_vertices() && !any; ++v)
    any = (m.V.row(v).head<3>().transpose() - e.region.center).norm() <= e.region.radius && m.V(v, 3) >= e.region.t0 &&
          m.V(v, 3) <= e.region.t1;
  if (!any) throw Error("the region holds no vertex of the animation (centre, radius or window)");
  x.doc.add_space_time_edit(e);
}

// Drags the handle at (HX HY HZ) at the current time by (DX DY DZ): the current edit's first move, or
// more of the same handle's move, or (another handle) a new edit over the same region.
void edit_drag(CommandContext& x, const CommandWords& w) {
  const std::vector<SpaceTimeEdit>& edits = x.doc.space_time_edits();
  if (edits.empty()) throw Error("no space-time edit: start one with edit-region");
  const Eigen::Vector3d h(num(w, 1), num(w, 2), num(w, 3)), d(num(w, 4), num(w, 5), num(w, 6));
  const double dt = w.size() > 7 ? num(w, 7) : 0.0;  // retime (optional)
  SpaceTimeEdit e = edits.back();
  int index = static_cast<int>(edits.size()) - 1;
  if (!moves(e)) {
    e.handle = {h, x.doc.time()};
    e.move = d;
    e.retime = dt;
  } else if (e.handle.point == h && e.handle.time == x.doc.time()) {
    e.move += d;
    e.retime += dt;
  } else {
    e.handle = {h, x.doc.time()};
    e.move = d;
    e.retime = dt;
    e.rotation = Eigen::Quaterniond::Identity();
    ++index;
  }
  check_space_time_edit(e);
  {
    // A clear error, nothing changed: the region, and a retime that would fold the manifold in time.
    AnimationManifold m = manifold_before(x.doc, index);
    select_edit_region(m, e.region, e.handle);
    if (e.retime != 0) apply_space_time_edit(m, e);  // solves once more: only retimes can be refused
  }
  if (index == static_cast<int>(edits.size()))
    x.doc.add_space_time_edit(e);
  else
    x.doc.set_space_time_edit(index, e);
}

}  // namespace

void add_space_time_commands(std::vector<Command>& t) {
  Command* c = &add(t, "edit-region", "edit-region CX CY CZ RADIUS T0 T1", 6, 6, {number_arg()}, edit_region);
  c->poll = needs_two_keys;
  c = &add(t, "edit-drag", "edit-drag HX HY HZ DX DY DZ [DT]", 6, 7, {number_arg()}, edit_drag);
  c->poll = needs_two_keys;
  add(t, "edit-clear", "edit-clear", 0, 0, {}, [](CommandContext& x, const CommandWords&) { x.doc.clear_space_time_edits(); });
}

}  // namespace dfm::command_detail
