// The table's space-time edit commands (SCRIPT.md; issue 35): edit-region, edit-brush, edit-drag,
// edit-refine, edit-clear.
#include <algorithm>

#include "core/anim/manifold_laplacian.h"
#include "core/anim/manifold_refine.h"
#include "core/scene/command_parts.h"
#include "core/scene/key_surfaces.h"
#include "core/util/error.h"

namespace dfm::command_detail {
namespace {

bool moves(const SpaceTimeEdit& e) {
  return e.move != Eigen::Vector3d::Zero() || e.rotation.coeffs() != Eigen::Quaterniond::Identity().coeffs() ||
         e.retime != 0;
}

// edit-region's optional words after T0 T1, the edit's setup (cmd_edit_manifold's --weights,
// --time-scale, --volume): weights=W, time-scale=S, volume; each at most once.
void read_setup(const CommandWords& w, SpaceTimeEdit& e) {
  bool weights = false, scale = false, volume = false;
  for (size_t i = 7; i < w.size(); ++i) {
    const std::string& o = w[i];
    if (o.rfind("weights=", 0) == 0) {
      if (weights) throw Error("weights= given twice");
      weights = true;
      try {
        e.weights = parse_laplacian_weights(o.substr(8));
      } catch (const Error& err) {
        throw Error(std::string("weights=: ") + err.what());
      }
    } else if (o.rfind("time-scale=", 0) == 0) {
      if (scale) throw Error("time-scale= given twice");
      scale = true;
      if (!parse_number(o.substr(11), e.time_scale) || !(e.time_scale > 0))
        throw Error("time-scale= must be a number > 0, got '" + o.substr(11) + "'");
    } else if (o == "volume") {
      if (volume) throw Error("volume given twice");
      volume = e.preserve_volume = true;
    } else {
      throw Error("unknown word '" + o + "' (weights=W, time-scale=S, volume)");
    }
  }
}

// Whether a vertex of m lies within the region's radius of p at a time inside its window.
bool ball_holds_vertex(const AnimationManifold& m, const Eigen::Vector3d& p, const EditRegionSpec& r) {
  for (int v = 0; v < m.num_vertices(); ++v)
    if ((m.V.row(v).head<3>().transpose() - p).norm() <= r.radius && m.V(v, 3) >= r.t0 && m.V(v, 3) <= r.t1) return true;
  return false;
}

// Starts an edit: the region and window and its setup, no move yet (a still edit changes nothing).
void edit_region(CommandContext& x, const CommandWords& w) {
  SpaceTimeEdit e;
  e.region.center = {num(w, 1), num(w, 2), num(w, 3)};
  e.region.radius = num(w, 4);
  e.region.t0 = num(w, 5);
  e.region.t1 = num(w, 6);
  e.handle.point = e.region.center;
  e.handle.time = std::clamp(x.doc.time(), e.region.t0, e.region.t1);
  read_setup(w, e);
  check_space_time_edit(e);
  const AnimationManifold m = manifold_before_edit(x.doc, x.doc.space_time_edits().size());
  if (e.region.t1 <= m.times.front() || e.region.t0 >= m.times.back())
    throw Error("the window [" + w[5] + ", " + w[6] + "] is outside the animation [" + std::to_string(m.times.front()) +
                ", " + std::to_string(m.times.back()) + "]");
  if (!ball_holds_vertex(m, e.region.center, e.region))
    throw Error("the region holds no vertex of the animation (centre, radius or window)");
  x.doc.add_space_time_edit(e);
}

// Brushes more of the current edit's region: a ball of its radius at (X Y Z), before its first drag.
void edit_brush(CommandContext& x, const CommandWords& w) {
  const std::vector<SpaceTimeEdit>& edits = x.doc.space_time_edits();
  if (edits.empty()) throw Error("no space-time edit: start one with edit-region");
  SpaceTimeEdit e = edits.back();
  if (moves(e)) throw Error("the current space-time edit has been dragged: start a new region (edit-region) to brush");
  const Eigen::Vector3d p(num(w, 1), num(w, 2), num(w, 3));
  e.region.dabs.push_back(p);
  check_space_time_edit(e);
  const AnimationManifold m = manifold_before_edit(x.doc, edits.size() - 1);
  if (!ball_holds_vertex(m, p, e.region))
    throw Error("the dab holds no vertex of the animation inside the edit's window");
  x.doc.set_space_time_edit(static_cast<int>(edits.size()) - 1, e);
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
  e.refine = false;  // a drag is made on the unrefined mesh; edit-refine again after it
  check_space_time_edit(e);
  {
    // A clear error, nothing changed: the region, and a retime that would fold the manifold in time.
    AnimationManifold m = manifold_before_edit(x.doc, index);
    select_edit_region(m, e.region, e.handle);
    if (e.retime != 0) apply_space_time_edit(m, e);  // solves once more: only retimes can be refused
  }
  if (index == static_cast<int>(edits.size()))
    x.doc.add_space_time_edit(e);
  else
    x.doc.set_space_time_edit(index, e);
}

// Refines what the last edit stretched (Southern 4.5.1; core/anim/manifold_refine.h): the edit is made
// again on a finer layer mesh, by the replay. A manifold it cannot refine is a clear error here (the
// unrefined edit already applies, so its region and handle are good on the refined mesh too).
void edit_refine(CommandContext& x, const CommandWords&) {
  const std::vector<SpaceTimeEdit>& edits = x.doc.space_time_edits();
  if (edits.empty() || !moves(edits.back())) throw Error("no space-time edit to refine: drag one first (edit-drag)");
  SpaceTimeEdit e = edits.back();
  if (e.refine) throw Error("the last space-time edit is refined already");
  e.refine = true;
  check_refinable(manifold_before_edit(x.doc, edits.size() - 1));
  x.doc.set_space_time_edit(static_cast<int>(edits.size()) - 1, e);
}

}  // namespace

void add_space_time_commands(std::vector<Command>& t) {
  const ArgSpec n = number_arg();
  Command* c = &add(t, "edit-region", "edit-region CX CY CZ RADIUS T0 T1 [weights=W] [time-scale=S] [volume]", 6, 9,
                    {n, n, n, n, n, n, arg_checked_by_line(ArgKind::Word)}, edit_region);
  c->check = [](const CommandWords& w, const std::string& usage) {
    SpaceTimeEdit e;
    try {
      read_setup(w, e);
    } catch (const Error& err) {
      throw Error(std::string(err.what()) + "; usage: " + usage);
    }
  };
  c->poll = needs_two_keys;
  c = &add(t, "edit-brush", "edit-brush X Y Z", 3, 3, {number_arg()}, edit_brush);
  c->poll = needs_two_keys;
  c = &add(t, "edit-drag", "edit-drag HX HY HZ DX DY DZ [DT]", 6, 7, {number_arg()}, edit_drag);
  c->poll = needs_two_keys;
  c = &add(t, "edit-refine", "edit-refine", 0, 0, {}, edit_refine);
  c->poll = needs_two_keys;
  add(t, "edit-clear", "edit-clear", 0, 0, {}, [](CommandContext& x, const CommandWords&) { x.doc.clear_space_time_edits(); });
}

}  // namespace dfm::command_detail
