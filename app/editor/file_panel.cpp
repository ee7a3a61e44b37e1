#include "app/editor/file_panel.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <imgui.h>

namespace fs = std::filesystem;

namespace dfm::editor {

std::vector<std::string> push_recent(std::vector<std::string> list, const std::string& path, size_t max) {
  list.erase(std::remove(list.begin(), list.end(), path), list.end());
  list.insert(list.begin(), path);
  if (list.size() > max) list.resize(max);
  return list;
}

std::string recent_files_path() {
  const char* xdg = std::getenv("XDG_CONFIG_HOME");
  const char* home = std::getenv("HOME");
  std::string base = xdg && *xdg ? xdg : (home && *home ? std::string(home) + "/.config" : ".");
  return base + "/deform-editor/recent.txt";
}

std::vector<std::string> load_recent() {
  std::vector<std::string> out;
  std::ifstream in(recent_files_path());
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) out.push_back(line);
  return out;
}

void save_recent(const std::vector<std::string>& list) {
  try {
    const fs::path p = recent_files_path();
    fs::create_directories(p.parent_path());
    std::ofstream out(p);
    for (const auto& s : list) out << s << "\n";
  } catch (...) {
    // A read-only home must not stop the editor; the list is a convenience.
  }
}

namespace {
bool openable(const std::string& name) {
  static const char* exts[] = {".obj", ".off", ".ply", ".stl", ".mesh", ".node", ".ele", ".tgf", ".json"};
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
  for (const char* e : exts) {
    const std::string ext = e;
    if (lower.size() >= ext.size() && lower.compare(lower.size() - ext.size(), ext.size(), ext) == 0) return true;
  }
  return false;
}
}  // namespace

FilePanel::FilePanel() : recent_(load_recent()) {
  std::error_code ec;
  dir_ = fs::current_path(ec).string();
}

void FilePanel::show(Mode mode, const std::string& title, const std::string& command, const std::string& default_name,
                     const std::vector<std::string>& more_args, const std::vector<std::string>& lead_args) {
  open_ = true;
  lead_args_ = lead_args;
  mode_ = mode;
  title_ = title;
  command_ = command;
  more_args_ = more_args;
  std::snprintf(name_, sizeof name_, "%s", default_name.c_str());
  error_.clear();
  list_dir();
}

std::vector<std::string> FilePanel::command_line() const {
  std::vector<std::string> words{command_};
  words.insert(words.end(), lead_args_.begin(), lead_args_.end());
  words.push_back(chosen_);
  words.insert(words.end(), more_args_.begin(), more_args_.end());
  return words;
}

void FilePanel::add_recent(const std::string& path) {
  std::error_code ec;
  const std::string abs = fs::absolute(path, ec).lexically_normal().string();
  recent_ = push_recent(recent_, ec ? path : abs);
  save_recent(recent_);
}

void FilePanel::list_dir() {
  entries_.clear();
  std::error_code ec;
  for (fs::directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.empty() || name[0] == '.') continue;
    const bool is_dir = it->is_directory(ec);
    if (is_dir || mode_ == Mode::Save || openable(name)) entries_.emplace_back(name, is_dir);
  }
  if (ec) error_ = "cannot list " + dir_ + ": " + ec.message();
  std::sort(entries_.begin(), entries_.end(), [](const auto& a, const auto& b) {
    return a.second != b.second ? a.second > b.second : a.first < b.first;
  });
}

bool FilePanel::draw() {
  if (!open_) return false;
  bool chosen = false;
  ImGui::SetNextWindowSize(ImVec2(560, 460), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowPos(ImGui::GetMainViewport()->GetCenter(), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (ImGui::Begin(title_.c_str(), &open_, ImGuiWindowFlags_NoCollapse)) {
    ImGui::TextDisabled("%s", dir_.c_str());
    if (ImGui::Button("Up")) {
      dir_ = fs::path(dir_).parent_path().string();
      list_dir();
    }
    ImGui::SameLine();
    if (ImGui::Button("Refresh")) list_dir();
    const float list_h = ImGui::GetContentRegionAvail().y - 110;
    ImGui::BeginChild("files", ImVec2(0, std::max(80.f, list_h)), true);
    for (const auto& [name, is_dir] : entries_) {
      const std::string label = (is_dir ? "[dir] " : "      ") + name;
      if (ImGui::Selectable(label.c_str(), false, ImGuiSelectableFlags_AllowDoubleClick)) {
        if (is_dir) {
          dir_ = (fs::path(dir_) / name).string();
          list_dir();
          break;
        }
        std::snprintf(name_, sizeof name_, "%s", name.c_str());
        if (ImGui::IsMouseDoubleClicked(0)) {
          chosen_ = (fs::path(dir_) / name).string();
          chosen = true;
        }
      }
    }
    ImGui::EndChild();
    ImGui::SetNextItemWidth(-90);
    const bool enter = ImGui::InputText("##name", name_, sizeof name_, ImGuiInputTextFlags_EnterReturnsTrue);
    ImGui::SameLine();
    if ((ImGui::Button(mode_ == Mode::Open ? "Open" : "Save", ImVec2(80, 0)) || enter) && name_[0]) {
      const fs::path p(name_);
      chosen_ = p.is_absolute() ? p.string() : (fs::path(dir_) / p).string();
      chosen = true;
    }
    if (mode_ == Mode::Open && !recent_.empty()) {
      ImGui::SetNextItemWidth(-1);
      if (ImGui::BeginCombo("##recent", "Recent files...")) {
        for (const auto& r : recent_)
          if (ImGui::Selectable(r.c_str())) {
            chosen_ = r;
            chosen = true;
          }
        ImGui::EndCombo();
      }
    }
    if (!error_.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", error_.c_str());
  }
  ImGui::End();
  if (chosen) open_ = false;
  return chosen;
}

}  // namespace dfm::editor
