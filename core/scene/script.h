#pragma once
// The editor's script language (see core/scene/SCRIPT.md): one command per line, words separated by
// spaces, '#' starts a comment. Every command calls the same Document member the UI uses.
#include <functional>
#include <string>
#include <vector>

#include "core/scene/document.h"

namespace dfm {

struct ScriptLine {
  int line = 0;                    // 1-based line in the script file
  std::vector<std::string> words;  // words[0] = command
};

// Parses and checks every line (command known, argument count and numbers valid) before anything runs.
// Throws dfm::Error "script.txt:LINE: problem".
std::vector<ScriptLine> parse_script(const std::string& text, const std::string& script_name);
std::vector<ScriptLine> read_script(const std::string& path);

// What the host (editor) provides. Each callback may be empty; a command that needs a missing one
// fails with a dfm::Error naming the line.
struct ScriptHost {
  // screenshot f.png: render the current view to a PNG.
  std::function<void(const std::string& png_path)> screenshot;
  // bind: compute weights for doc (the editor runs its worker and waits). Empty -> run_bind_blocking()
  // (core/scene/bind_document.h).
  std::function<void(Document& doc)> bind;
  // export-gltf OUT.glb [4|8]: write the document as glTF with that many influences per vertex
  // (the editor calls export_document_gltf; core/scene cannot depend on core/export).
  std::function<void(const std::string& path, int influences)> export_gltf;
  // The lines a command reports (weights-report, the other weights-* summaries). Empty: stdout.
  std::function<void(const std::string& line)> print;
  // Called after each command (the editor redraws; tests may record).
  std::function<void(const ScriptLine&)> after_command;
};

struct ScriptResult {
  bool quit = false;  // the script said `quit`
  int commands_run = 0;
};

// Runs the commands in order. Errors are rethrown as "script.txt:LINE: <command>: problem".
ScriptResult run_script(Document& doc, const std::vector<ScriptLine>& lines, const std::string& script_name,
                        const ScriptHost& host = {});

// The deformed surface of the current frame: the animation manifold's slice at doc.time() when the
// document has keys (>= 2), else the current pose skinned with doc.method(). Needs weights.
TriMesh posed_surface(const Document& doc);

}  // namespace dfm
