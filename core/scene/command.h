#pragma once
// One command table (SCRIPT.md): every editor command declared once, with its name, typed arguments,
// undo flag, when it is available and what it does to the document. The script runner, the editor's
// menus, buttons and file panel all look commands up here and run them the same way, so a script
// line and a UI action are the same call (as Blender's operators are for menus and Python).
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include "core/anim/shape_space.h"
#include "core/scene/document.h"

namespace dfm {

// A command line as words: words[0] is the command, the rest its arguments.
using CommandWords = std::vector<std::string>;

// A line of a script: its words and where it was.
struct ScriptLine {
  int line = 0;        // 1-based line in the script file
  CommandWords words;  // words[0] = command
};

// What the host (the editor) provides. Each callback may be empty; a command that needs a missing one
// fails with a dfm::Error saying so.
struct ScriptHost {
  // screenshot f.png: render the current view to a PNG.
  std::function<void(const std::string& png_path)> screenshot;
  // bind: compute weights for doc (the editor runs its worker). Empty -> run_bind_blocking()
  // (core/scene/bind_document.h).
  std::function<void(Document& doc)> bind;
  // export-gltf OUT.glb [4|8]: write the document as glTF with that many influences per vertex
  // (the editor calls export_document_gltf; core/scene cannot depend on core/export).
  std::function<void(const std::string& path, int influences)> export_gltf;
  // The lines a command reports (weights-report, the other weights-* summaries). Empty: stdout.
  std::function<void(const std::string& line)> print;
  // open and replace-surface call it once the document holds the new file: the editor syncs its view
  // to it and frames it (one place for "open, then show it", whoever opened).
  enum class Opened { Scene, NewMesh, Surface };
  std::function<void(Opened what)> opened;
  // shape-space-key: the shape already synthesized for these bases, morph and coordinates (the
  // editor's Shape space cursor, an ARAP shape its worker made), keyed as is; empty: none, the
  // command synthesizes it.
  std::function<Eigen::MatrixXd(const std::vector<double>& times, ShapeMorph morph, const Eigen::VectorXd& x)>
      synthesized_shape;
  // Called after each script line (the editor redraws; tests may record).
  std::function<void(const ScriptLine&)> after_command;
};

// The kind of word an argument is, checked before anything runs. Handle: a number (a handle number:
// an integer >= 0) or a name, resolved by core/rig's find_handle when the command runs.
enum class ArgKind { Number, Handle, Word, File };

struct ArgSpec {
  ArgKind kind = ArgKind::Word;
  // Further checks of the word before anything runs (a fixed set of words, an extension); throws
  // dfm::Error with the whole message. Empty: the kind's check only.
  std::function<void(const std::string& word, const std::string& usage)> check;
};

struct CommandContext {
  Document& doc;
  const ScriptHost& host;
  std::function<void(const std::string&)> print;  // never empty
  bool quit = false;                              // set by `quit`
};

struct Command {
  std::string name;
  std::string usage;  // "rotate DEGREES AX AY AZ"
  int min_args = 0, max_args = 0;
  std::vector<ArgSpec> args;  // one per argument; the last one repeats
  bool undoable = true;       // one undo step (false: view state, files, undo itself)
  // Why the command cannot run on doc now ("" = it can): menus and buttons grey it out. The command
  // itself still checks and throws its documented message.
  std::function<std::string(const Document&)> poll;
  // Whole-line checks after each argument's own (add-bone's threes); throws dfm::Error.
  std::function<void(const CommandWords&, const std::string& usage)> check;
  std::function<void(CommandContext&, const CommandWords&)> run;
  bool remember_file = false;  // the first argument is a file the user opened or saved (recent files)
};

// Every command, in SCRIPT.md's order.
const std::vector<Command>& commands();
// nullptr when no command has that name.
const Command* find_command(const std::string& name);

// Checks a line (command known, argument count, each argument's kind and checks, the line's checks)
// and returns its command; throws dfm::Error "problem" (the script runner adds file and line).
const Command& check_command(const CommandWords& words);

// Runs a checked line on doc; errors are dfm::Error "problem" (the runner adds line and command).
// Returns true when the line was `quit`.
bool run_checked(const Command& c, Document& doc, const CommandWords& words, const ScriptHost& host);

// An argument as a UI passes it: numbers (exactly, to the last bit), handle numbers, words, files.
struct CommandArg {
  std::string word;
  CommandArg(double x);
  CommandArg(int x);
  CommandArg(const std::string& w) : word(w) {}
  CommandArg(const char* w) : word(w) {}
};
CommandWords command_words(const std::string& name, std::initializer_list<CommandArg> args = {});
// The same with a list of handle numbers (select, delete-handles).
CommandWords command_words(const std::string& name, const std::vector<int>& handles);

// What a menu item or button does: checks the line and runs it, as a script line runs. Throws
// dfm::Error "name: problem".
void run_command(Document& doc, const CommandWords& words, const ScriptHost& host = {});

// Whether a command is available on doc ("" = yes; else why not, for a tooltip).
std::string command_unavailable(const std::string& name, const Document& doc);

}  // namespace dfm
