#include "core/scene/command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/scene/command_parts.h"
#include "core/util/error.h"

namespace dfm {

namespace command_detail {

Command& add(std::vector<Command>& table, const std::string& name, const std::string& usage, int min_args,
             int max_args, std::vector<ArgSpec> args, RunFn run) {
  Command c;
  c.name = name;
  c.usage = usage;
  c.min_args = min_args;
  c.max_args = max_args;
  c.args = std::move(args);
  c.run = std::move(run);
  table.push_back(std::move(c));
  return table.back();
}

ArgSpec number_arg() { return {ArgKind::Number, {}}; }
ArgSpec handle_arg() { return {ArgKind::Handle, {}}; }
ArgSpec word_arg() { return {ArgKind::Word, {}}; }
ArgSpec file_arg() { return {ArgKind::File, {}}; }
ArgSpec arg_checked_by_line(ArgKind kind) { return {kind, [](const std::string&, const std::string&) {}}; }

bool parse_number(const std::string& w, double& out) {
  const char* b = w.c_str();
  char* e = nullptr;
  out = std::strtod(b, &e);
  return e != b && *e == '\0' && std::isfinite(out);
}

double num(const CommandWords& w, int i) {
  double x = 0;
  parse_number(w[i], x);  // checked by check_command
  return x;
}

int handle_at(const Document& doc, const CommandWords& w, int i) { return find_handle(doc.rig(), w[i]); }

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string not_a_number(const std::string& w, const std::string& usage) {
  return "'" + w + "' is not a finite number; usage: " + usage;
}

std::string needs_surface(const Document& doc) { return doc.surface().num_vertices() > 0 ? "" : "no surface (open a mesh)"; }
std::string needs_weights(const Document& doc) { return doc.has_weights() ? "" : doc.weights_note() + " (bind first)"; }
std::string needs_a_frame(const Document& doc) {
  return doc.has_weights() || doc.has_mesh_keys() ? "" : doc.weights_note() + " (bind first)";
}
std::string needs_two_keys(const Document& doc) {
  if (const std::string why = needs_a_frame(doc); !why.empty()) return why;
  return doc.keys().size() >= 2 ? "" : "needs at least two keys";
}

}  // namespace command_detail

using namespace command_detail;

const std::vector<Command>& commands() {
  static const std::vector<Command> table = [] {
    std::vector<Command> t;
    add_rig_commands(t);
    add_weight_commands(t);
    add_pose_commands(t);
    add_key_commands(t);
    add_sculpt_commands(t);
    add_space_time_commands(t);
    add_file_commands(t);
    return t;
  }();
  return table;
}

const Command* find_command(const std::string& name) {
  for (const Command& c : commands())
    if (c.name == name) return &c;
  return nullptr;
}

namespace {

// The kind's own check of a word, when the argument declares no check of its own.
void check_kind(ArgKind kind, const std::string& w, const std::string& usage) {
  double x = 0;
  if (kind == ArgKind::Number && !parse_number(w, x)) throw Error(not_a_number(w, usage));
  // A handle: a number must be a handle number; a name waits for the run (it needs the rig by then).
  if (kind == ArgKind::Handle && parse_number(w, x) && (x != std::floor(x) || x < 0))
    throw Error("'" + w + "' is not a handle number or name; usage: " + usage);
}

}  // namespace

const Command& check_command(const CommandWords& words) {
  const Command* c = find_command(words.at(0));
  if (!c) throw Error("unknown command '" + words[0] + "' (see SCRIPT.md)");
  const int nargs = static_cast<int>(words.size()) - 1;
  if (nargs < c->min_args || nargs > c->max_args)
    throw Error("'" + c->name + "' takes " +
                (c->min_args == c->max_args ? std::to_string(c->min_args)
                                            : std::to_string(c->min_args) + ".." + std::to_string(c->max_args)) +
                " argument(s), got " + std::to_string(nargs) + "; usage: " + c->usage);
  for (int i = 1; i <= nargs && !c->args.empty(); ++i) {
    const ArgSpec& a = c->args[std::min<size_t>(i - 1, c->args.size() - 1)];
    if (a.check) a.check(words[i], c->usage);
    else check_kind(a.kind, words[i], c->usage);
  }
  if (c->check) c->check(words, c->usage);
  return *c;
}

bool run_checked(const Command& c, Document& doc, const CommandWords& words, const ScriptHost& host) {
  CommandContext ctx{doc, host, host.print, false};
  if (!ctx.print)
    ctx.print = [](const std::string& s) {
      std::printf("%s\n", s.c_str());
      std::fflush(stdout);
    };
  c.run(ctx, words);
  return ctx.quit;
}

CommandArg::CommandArg(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);  // reads back as the same double
  word = buf;
}

CommandArg::CommandArg(int x) : word(std::to_string(x)) {}

CommandWords command_words(const std::string& name, std::initializer_list<CommandArg> args) {
  CommandWords w{name};
  for (const CommandArg& a : args) w.push_back(a.word);
  return w;
}

CommandWords command_words(const std::string& name, const std::vector<int>& handles) {
  CommandWords w{name};
  for (int h : handles) w.push_back(CommandArg(h).word);
  return w;
}

void run_command(Document& doc, const CommandWords& words, const ScriptHost& host) {
  try {
    run_checked(check_command(words), doc, words, host);
  } catch (const Error& e) {
    throw Error(words.at(0) + ": " + e.what());
  }
}

std::string command_unavailable(const std::string& name, const Document& doc) {
  const Command* c = find_command(name);
  if (!c) return "unknown command '" + name + "'";
  return c->poll ? c->poll(doc) : "";
}

}  // namespace dfm
