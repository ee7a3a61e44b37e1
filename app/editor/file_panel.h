#pragma once
// An ImGui file browser (folders, files filtered by the extensions the editor opens) with a recent
// files list kept in $XDG_CONFIG_HOME/deform-editor/recent.txt (or ~/.config/...). It is shown for a
// command of the table (core/scene/command.h) whose first argument is the file: the chosen path
// completes the command line, which the editor runs as any menu item's.
#include <string>
#include <vector>

namespace dfm::editor {

// Most-recent-first list, without duplicates, at most `max` entries (pure: testable).
std::vector<std::string> push_recent(std::vector<std::string> list, const std::string& path, size_t max = 12);
std::string recent_files_path();
std::vector<std::string> load_recent();
void save_recent(const std::vector<std::string>& list);  // best effort: never throws

class FilePanel {
 public:
  enum class Mode { Open, Save };
  FilePanel();
  // Opens the panel for `command lead_args... FILE more_args...`; `title` e.g. "Open", "Save scene as";
  // default_name pre-fills the name field.
  void show(Mode mode, const std::string& title, const std::string& command, const std::string& default_name = "",
            const std::vector<std::string>& more_args = {}, const std::vector<std::string>& lead_args = {});
  // Draws it when open; returns true on the frame a path is chosen (then command_line()).
  bool draw();
  // The command with the chosen path as its first argument.
  std::vector<std::string> command_line() const;
  void add_recent(const std::string& path);
  const std::vector<std::string>& recent() const { return recent_; }

 private:
  void list_dir();
  bool open_ = false;
  Mode mode_ = Mode::Open;
  std::string title_, command_, chosen_;
  std::vector<std::string> more_args_, lead_args_;
  std::string dir_;
  char name_[512] = {0};
  std::vector<std::pair<std::string, bool>> entries_;  // name, is_dir
  std::vector<std::string> recent_;
  std::string error_;
};

}  // namespace dfm::editor
