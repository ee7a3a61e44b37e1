#pragma once
// The editor's script language (see core/scene/SCRIPT.md): one command per line, words separated by
// spaces, '#' starts a comment. Each line is a command of the table (core/scene/command.h), the same
// call the editor's menus and buttons make; the host's callbacks (ScriptHost) are declared there.
#include <functional>
#include <string>
#include <vector>

#include "core/scene/command.h"
#include "core/scene/document.h"

namespace dfm {

// Parses and checks every line (command known, argument count and numbers valid) before anything runs.
// Throws dfm::Error "script.txt:LINE: problem".
std::vector<ScriptLine> parse_script(const std::string& text, const std::string& script_name);
std::vector<ScriptLine> read_script(const std::string& path);

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
