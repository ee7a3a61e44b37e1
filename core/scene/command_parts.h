#pragma once
// Inside the command table only (command*.cpp): the helpers each area's commands are declared with,
// and the functions that add each area's commands to the table.
#include <string>
#include <vector>

#include "core/scene/command.h"

namespace dfm::command_detail {

using RunFn = std::function<void(CommandContext&, const CommandWords&)>;

// Appends a command and returns it, for the fields that differ from the defaults.
Command& add(std::vector<Command>& table, const std::string& name, const std::string& usage, int min_args,
             int max_args, std::vector<ArgSpec> args, RunFn run);

ArgSpec number_arg();
ArgSpec handle_arg();
ArgSpec word_arg();
ArgSpec file_arg();
// An argument whose checks are the line's (Command::check), which names the problem its own way.
ArgSpec arg_checked_by_line(ArgKind kind);

bool parse_number(const std::string& w, double& out);  // finite numbers only
double num(const CommandWords& w, int i);             // words[i], checked by check_command
int handle_at(const Document& doc, const CommandWords& w, int i);  // number or name (find_handle)
bool ends_with(const std::string& s, const std::string& suffix);
std::string not_a_number(const std::string& w, const std::string& usage);

// Availability (Command::poll).
std::string needs_surface(const Document& doc);
std::string needs_weights(const Document& doc);
std::string needs_a_frame(const Document& doc);  // weights or a mesh key: something to save posed
std::string needs_two_keys(const Document& doc);

void add_rig_commands(std::vector<Command>& table);      // command_rig.cpp: surface, rig, bind, mask
void add_pose_commands(std::vector<Command>& table);     // command_pose.cpp: selection, posing, undo
void add_key_commands(std::vector<Command>& table);      // command_keys.cpp: keys and time
void add_weight_commands(std::vector<Command>& table);   // command_weights.cpp: weights-*
void add_sculpt_commands(std::vector<Command>& table);   // command_sculpt.cpp: sculpt-*, transition-state
void add_space_time_commands(std::vector<Command>& table);  // command_space_time.cpp: edit-region, ...
void add_file_commands(std::vector<Command>& table);     // command_files.cpp: saving, host commands, quit

}  // namespace dfm::command_detail
