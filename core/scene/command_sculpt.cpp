// The table's Sculpt tool and local transition commands (issue 37, SCRIPT.md): the editor's Sculpt
// tool runs these lines, so a script repeats what it did.

#include "core/scene/command_parts.h"
#include "core/scene/local_transition.h"
#include "core/util/error.h"

namespace dfm::command_detail {
namespace {

Eigen::Vector3d point_at(const CommandWords& w, int i) { return {num(w, i), num(w, i + 1), num(w, i + 2)}; }

// sculpt-region X Y Z RADIUS [erase]
void sculpt_region(CommandContext& x, const CommandWords& w) {
  if (w.size() > 5 && w[5] != "erase") throw Error("the last word is 'erase' or nothing, got " + w[5]);
  x.doc.sculpt_region(point_at(w, 1), num(w, 4), w.size() > 5);
  x.print(w[0] + ": " + std::to_string(x.doc.sculpt()->region_count()) + " free vertices");
}

void sculpt_handle(CommandContext& x, const CommandWords& w) {
  const int n = x.doc.sculpt_handle(point_at(w, 1), num(w, 4));
  x.print(w[0] + ": " + std::to_string(n) + " handle vertices");
}

void sculpt_order(CommandContext& x, const CommandWords& w) {
  if (w[1] != "2" && w[1] != "3") throw Error("the order is 2 (C1) or 3 (C2), got '" + w[1] + "'");
  x.doc.sculpt_order(w[1] == "2" ? 2 : 3);
}

// transition-state T VALUE X Y Z RADIUS [FALLOFF]: one dab of the local transition brush.
void transition_state(CommandContext& x, const CommandWords& w) {
  const int k = transition_interval(x.doc, num(w, 1));
  const TransitionDab dab = transition_dab(x.doc, k, num(w, 2), point_at(w, 3), num(w, 6), w.size() > 7 ? num(w, 7) : 0.0);
  x.doc.paint_transition(k, dab.vertices, dab.values);
}

void clear_transition(CommandContext& x, const CommandWords& w) {
  x.doc.clear_transition(transition_interval(x.doc, w.size() > 1 ? num(w, 1) : x.doc.time()));
}

std::string needs_session(const Document& doc) { return doc.sculpt() ? "" : "nothing sculpted (paint a region first)"; }

}  // namespace

void add_sculpt_commands(std::vector<Command>& t) {
  Command* c = &add(t, "sculpt-region", "sculpt-region X Y Z RADIUS [erase]", 4, 5,
                    {number_arg(), number_arg(), number_arg(), number_arg(), word_arg()}, sculpt_region);
  c->poll = needs_surface;
  c->undoable = false;  // tool state, like the selection; sculpt-key is the edit
  c = &add(t, "sculpt-handle", "sculpt-handle X Y Z RADIUS", 4, 4, {number_arg()}, sculpt_handle);
  c->poll = needs_session, c->undoable = false;
  c = &add(t, "sculpt-order", "sculpt-order 2|3", 1, 1, {word_arg()}, sculpt_order);
  c->poll = needs_surface, c->undoable = false;
  c = &add(t, "sculpt-move", "sculpt-move DX DY DZ", 3, 3, {number_arg()},
           [](CommandContext& x, const CommandWords& w) { x.doc.sculpt_move(point_at(w, 1)); });
  c->poll = needs_session, c->undoable = false;
  add(t, "sculpt-key", "sculpt-key [TIME]", 0, 1, {number_arg()}, [](CommandContext& x, const CommandWords& w) {
    x.doc.sculpt_key(w.size() > 1 ? num(w, 1) : x.doc.time());
  }).poll = needs_session;
  c = &add(t, "sculpt-clear", "sculpt-clear", 0, 0, {}, [](CommandContext& x, const CommandWords&) { x.doc.sculpt_clear(); });
  c->undoable = false;
  add(t, "transition-state", "transition-state T VALUE X Y Z RADIUS [FALLOFF]", 6, 7, {number_arg()}, transition_state).poll =
      needs_two_keys;
  add(t, "clear-transition", "clear-transition [TIME]", 0, 1, {number_arg()}, clear_transition).poll = needs_two_keys;
}

}  // namespace dfm::command_detail
