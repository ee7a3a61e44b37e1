// The table's selection, posing and undo commands (SCRIPT.md).
#include <cmath>
#include <limits>

#include "core/pose/fast_rig.h"
#include "core/scene/command_parts.h"
#include "core/skin/skin.h"
#include "core/util/error.h"

namespace dfm::command_detail {
namespace {

std::vector<int> selected_or_fail(const Document& doc) {
  if (doc.selection().handles.empty()) throw Error("no handle selected (use: select HANDLE)");
  return doc.selection().handles;
}

std::string needs_selection(const Document& doc) { return doc.selection().handles.empty() ? "no handle selected" : ""; }

void select(CommandContext& x, const CommandWords& w) {
  Selection s;
  for (size_t i = 1; i < w.size(); ++i) s.handles.push_back(handle_at(x.doc, w, static_cast<int>(i)));
  x.doc.set_selection(s);
}

void translate(CommandContext& x, const CommandWords& w) {
  const Eigen::Vector3d d(num(w, 1), num(w, 2), num(w, 3));
  for (int h : selected_or_fail(x.doc)) {
    const DragReport r = x.doc.translate_handle(h, d);
    if (r.kind != DragKind::Moved) x.print("translate: " + r.message);
  }
}

void rotate(CommandContext& x, const CommandWords& w) {
  const Eigen::Vector3d axis(num(w, 2), num(w, 3), num(w, 4));
  if (axis.norm() < 1e-12) throw Error("rotation axis is zero");
  const Eigen::Quaterniond q(Eigen::AngleAxisd(num(w, 1) * M_PI / 180.0, axis.normalized()));
  for (int h : selected_or_fail(x.doc)) x.doc.rotate_handle(h, q);
}

// The bone a BONE_HANDLE word names (a handle number or name that is a bone).
int bone_at(const Document& doc, const CommandWords& w, int i) {
  const HandleRef r = handle_ref(doc.rig(), handle_at(doc, w, i));
  if (r.kind != HandleKind::Bone) throw Error("handle '" + w[i] + "' is a " + handle_kind_name(r.kind) + ", not a bone");
  return r.index;
}

void twist(CommandContext& x, const CommandWords& w) {
  const int b = bone_at(x.doc, w, 1);
  BoneTwistStretch ts = twist_stretch_of(x.doc.pose_params(), b);
  ts.twist = num(w, 2) * M_PI / 180.0;
  if (w.size() > 3) ts.twist_start = num(w, 3) * M_PI / 180.0;
  x.doc.set_bone_twist_stretch(b, ts);
}

void stretch(CommandContext& x, const CommandWords& w) {
  const int b = bone_at(x.doc, w, 1);
  BoneTwistStretch ts = twist_stretch_of(x.doc.pose_params(), b);
  ts.stretch = num(w, 2);
  if (w.size() > 3) ts.twist_start = num(w, 3) * M_PI / 180.0;
  x.doc.set_bone_twist_stretch(b, ts);
}

// endpoint-filter BONE [X1 Y1 X2 Y2 ...]: the curve the bone's endpoint weights pass through (none: off).
void endpoint_filter(CommandContext& x, const CommandWords& w) {
  if (w.size() % 2 != 0) throw Error("the filter's points come in X Y pairs");
  EndpointFilter f;
  for (size_t i = 2; i + 1 < w.size(); i += 2) f.emplace_back(num(w, static_cast<int>(i)), num(w, static_cast<int>(i + 1)));
  x.doc.set_endpoint_filter(bone_at(x.doc, w, 1), f);
}

void ik_chain(CommandContext& x, const CommandWords& w) {
  PosingSettings p = x.doc.posing();
  p.fast = true;
  p.states = ik_chain_states(x.doc.rig(), x.doc.handle_states(), handle_at(x.doc, w, 1));
  x.doc.set_posing(p);
}

void fast(CommandContext& x, const CommandWords& w) {
  if (w[1] != "on" && w[1] != "off") throw Error("fast: expected on or off, got '" + w[1] + "'");
  PosingSettings p = x.doc.posing();
  p.fast = w[1] == "on";
  if (w.size() > 2) {
    double n = 0;
    if (!parse_number(w[2], n) || n != std::floor(n)) throw Error("'" + w[2] + "' is not an iteration count");
    p.iterations = static_cast<int>(n);
  }
  x.doc.set_posing(p);
}

// dynamics on|off [DT [DAMPING [DENSITY]]]
void dynamics(CommandContext& x, const CommandWords& w) {
  if (w[1] != "on" && w[1] != "off") throw Error("dynamics: expected on or off, got '" + w[1] + "'");
  PosingSettings p = x.doc.posing();
  p.dynamics = w[1] == "on";
  p.fast = p.fast || p.dynamics;  // translate and rotate step it only with FAST on (as the panel's switch)
  if (w.size() > 2) p.dt = num(w, 2);
  if (w.size() > 3) p.damping = num(w, 3);
  if (w.size() > 4) p.density = num(w, 4);
  x.doc.set_posing(p);
}

}  // namespace

void add_pose_commands(std::vector<Command>& t) {
  Command* c = &add(t, "select", "select HANDLE [HANDLE ...]", 1, 1000, {handle_arg()}, select);
  c->undoable = false;  // selection is view state
  add(t, "translate", "translate DX DY DZ", 3, 3, {number_arg()}, translate).poll = needs_selection;
  add(t, "rotate", "rotate DEGREES AX AY AZ", 4, 4, {number_arg()}, rotate).poll = needs_selection;
  add(t, "drag", "drag HANDLE DX DY DZ", 4, 4, {handle_arg(), number_arg()}, [](CommandContext& x, const CommandWords& w) {
    x.print("drag: " + x.doc.drag_handle(handle_at(x.doc, w, 1), Eigen::Vector3d(num(w, 2), num(w, 3), num(w, 4))).message);
  }).poll = needs_weights;
  add(t, "handle-state", "handle-state HANDLE pinned|position|free", 2, 2, {handle_arg(), word_arg()},
      [](CommandContext& x, const CommandWords& w) {
        x.doc.set_handle_state(handle_at(x.doc, w, 1), parse_constraint_state(w[2]));
      });
  add(t, "twist", "twist BONE_HANDLE DEGREES [AT_START_DEGREES]", 2, 3, {handle_arg(), number_arg()}, twist);
  add(t, "stretch", "stretch BONE_HANDLE FACTOR [AT_START_DEGREES]", 2, 3, {handle_arg(), number_arg()}, stretch);
  add(t, "endpoint-filter", "endpoint-filter BONE_HANDLE [X1 Y1 X2 Y2 ...]", 1, 41, {handle_arg(), number_arg()},
      endpoint_filter);
  add(t, "fast", "fast on|off [ITERATIONS]", 1, 2, {word_arg()}, fast);
  add(t, "dynamics", "dynamics on|off [DT [DAMPING [DENSITY]]]", 1, 4, {word_arg(), number_arg()}, dynamics);
  add(t, "settle", "settle [STEPS]", 0, 1, {number_arg()}, [](CommandContext& x, const CommandWords& w) {
    int steps = -1;
    if (w.size() > 1) {
      if (num(w, 1) < 0 || num(w, 1) != std::floor(num(w, 1))) throw Error("settle: '" + w[1] + "' is not a step count");
      steps = static_cast<int>(num(w, 1));
    }
    const int n = x.doc.settle_dynamics(steps);
    x.print("settle: " + std::to_string(n) + " steps" + (x.doc.dynamics_live() ? " (still moving)" : " (settled)"));
  });
  add(t, "simulate", "simulate FPS [FROM TO]", 1, 3, {number_arg()}, [](CommandContext& x, const CommandWords& w) {
    if (w.size() == 3) throw Error("simulate: give both FROM and TO, or neither");
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const int n = x.doc.simulate(num(w, 1), w.size() > 2 ? num(w, 2) : nan, w.size() > 3 ? num(w, 3) : nan);
    x.print("simulate: keyed " + std::to_string(n) + " frames");
  }).poll = needs_weights;
  add(t, "ik-chain", "ik-chain BONE_HANDLE", 1, 1, {handle_arg()}, ik_chain);
  add(t, "set-method", "set-method lbs|dqs|stbs|stbs-dqs", 1, 1, {word_arg()},
      [](CommandContext& x, const CommandWords& w) { x.doc.set_method(parse_skin_method(w[1])); });
  add(t, "reset-pose", "reset-pose", 0, 0, {}, [](CommandContext& x, const CommandWords&) { x.doc.reset_pose(); });
  c = &add(t, "undo", "undo", 0, 0, {}, [](CommandContext& x, const CommandWords&) { x.doc.undo(); });
  c->undoable = false;
  c->poll = [](const Document& d) { return d.can_undo() ? "" : "nothing to undo"; };
  c = &add(t, "redo", "redo", 0, 0, {}, [](CommandContext& x, const CommandWords&) { x.doc.redo(); });
  c->undoable = false;
  c->poll = [](const Document& d) { return d.can_redo() ? "" : "nothing to redo"; };
}

}  // namespace dfm::command_detail
