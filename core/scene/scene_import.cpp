#include "core/scene/scene_import.h"

#include <map>
#include <mutex>

#include "core/util/atomic_file.h"

namespace dfm {

namespace {
std::map<std::string, SceneImporter>& table() {
  static std::map<std::string, SceneImporter> t;
  return t;
}
std::map<std::string, MotionImporter>& motion_table() {
  static std::map<std::string, MotionImporter> t;
  return t;
}
std::mutex& table_mutex() {
  static std::mutex m;
  return m;
}
}  // namespace

void register_scene_importer(const std::string& extension, SceneImporter importer) {
  std::lock_guard<std::mutex> lock(table_mutex());
  table()[extension] = std::move(importer);
}

const SceneImporter* scene_importer_for(const std::string& path) {
  std::lock_guard<std::mutex> lock(table_mutex());
  const auto it = table().find(file_extension(path));
  return it == table().end() ? nullptr : &it->second;
}

void register_motion_importer(const std::string& extension, MotionImporter importer) {
  std::lock_guard<std::mutex> lock(table_mutex());
  motion_table()[extension] = std::move(importer);
}

const MotionImporter* motion_importer_for(const std::string& path) {
  std::lock_guard<std::mutex> lock(table_mutex());
  const auto it = motion_table().find(file_extension(path));
  return it == motion_table().end() ? nullptr : &it->second;
}

}  // namespace dfm
