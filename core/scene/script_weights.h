#pragma once
// The script's weights-* commands (SCRIPT.md), inside script.cpp only: their arguments checked at
// parse time and run as the Document's weights_* commands.
#include <functional>
#include <string>

#include "core/scene/script.h"

namespace dfm::script_detail {

// Throws dfm::Error naming the bad argument of a weights-* line (called by parse_script).
void check_weight_command(const ScriptLine& line);
// Runs a weights-* line; false when the line is another command. print: one line per report.
bool run_weight_command(Document& doc, const ScriptLine& line, const std::function<void(const std::string&)>& print);

}  // namespace dfm::script_detail
