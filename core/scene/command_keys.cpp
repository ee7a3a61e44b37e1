// The table's key and time commands (SCRIPT.md).
#include "core/anim/inbetween_method.h"
#include "core/scene/command_parts.h"
#include "core/scene/key_pairs.h"
#include "core/scene/shape_space_keys.h"
#include "core/util/error.h"

namespace dfm::command_detail {
namespace {

double time_or_now(const Document& doc, const CommandWords& w, size_t i) { return w.size() > i ? num(w, i) : doc.time(); }

// Key times, then as many weights, then an optional time to key at (Alexa 2002, ch. 5).
void shape_space_key(CommandContext& x, const CommandWords& w) {
  const int m = static_cast<int>(w.size()) - 2, n = m / 2;
  std::vector<double> times;
  Eigen::VectorXd weights(n);
  for (int i = 0; i < n; ++i) times.push_back(num(w, 2 + i)), weights(i) = num(w, 2 + n + i);
  const ShapeMorph morph = parse_shape_morph(w[1]);
  ShapeSpace space = key_shape_space(x.doc, times, morph);
  const Eigen::MatrixXd ready = x.host.synthesized_shape ? x.host.synthesized_shape(times, morph, weights) : Eigen::MatrixXd();
  key_synthesized_shape(x.doc, space, weights, m % 2 ? num(w, static_cast<int>(w.size()) - 1) : x.doc.time(), ready);
}

void delete_key(CommandContext& x, const CommandWords& w) {
  const double t = time_or_now(x.doc, w, 1);
  const int k = x.doc.key_at(t);
  if (k < 0) throw Error("no key at time " + (w.size() > 1 ? w[1] : std::to_string(t)));
  x.doc.delete_key(k);
}

void set_inbetween(CommandContext& x, const CommandWords& w) {
  const int k = x.doc.key_at(num(w, 1));
  if (k < 0) throw Error("no key at time " + w[1]);
  x.doc.set_key_inbetween(k, parse_inbetween_method(w[2]));
}

// A pair from the key whose interval holds TIME (default: the current time) to the next key.
void key_pair(CommandContext& x, const CommandWords& w) {
  Eigen::Matrix<double, 1, 6> p;
  for (int c = 0; c < 6; ++c) p[c] = num(w, 1 + c);
  add_key_pair(x.doc, pair_interval(x.doc, time_or_now(x.doc, w, 7)), p);
}

void clear_pairs(CommandContext& x, const CommandWords& w) {
  x.doc.set_key_pairs(pair_interval(x.doc, time_or_now(x.doc, w, 1)), Eigen::MatrixXd(0, 6));
}

ArgSpec morph_arg() {
  return {ArgKind::Word, [](const std::string& m, const std::string& usage) {
            if (m != "linear" && m != "arap") throw Error("the morph must be linear or arap, got '" + m + "'; usage: " + usage);
          }};
}

ArgSpec inbetween_arg() {
  return {ArgKind::Word, [](const std::string& m, const std::string&) { parse_inbetween_method(m); }};
}

}  // namespace

void add_key_commands(std::vector<Command>& t) {
  add(t, "set-key", "set-key [TIME]", 0, 1, {number_arg()},
      [](CommandContext& x, const CommandWords& w) { x.doc.set_key(time_or_now(x.doc, w, 1)); });
  Command* c = &add(t, "key-mesh", "key-mesh FILE [TIME]", 1, 2, {file_arg(), number_arg()},
                    [](CommandContext& x, const CommandWords& w) { x.doc.key_mesh_file(w[1], time_or_now(x.doc, w, 2)); });
  c->remember_file = true;
  add(t, "shape-space-key", "shape-space-key linear|arap T0 T1 ... W0 W1 ... [TIME]", 5, 2001, {morph_arg(), number_arg()},
      shape_space_key);
  add(t, "delete-key", "delete-key [TIME]", 0, 1, {number_arg()}, delete_key);
  add(t, "set-inbetween", "set-inbetween TIME handles|arap|linear", 2, 2, {number_arg(), inbetween_arg()}, set_inbetween);
  add(t, "key-pair", "key-pair X0 Y0 Z0 X1 Y1 Z1 [TIME]", 6, 7, {number_arg()}, key_pair);
  add(t, "clear-pairs", "clear-pairs [TIME]", 0, 1, {number_arg()}, clear_pairs);
  c = &add(t, "set-time", "set-time T", 1, 1, {number_arg()},
           [](CommandContext& x, const CommandWords& w) { x.doc.set_time(num(w, 1)); });
  c->undoable = false;  // scrubbing is view state
}

}  // namespace dfm::command_detail
