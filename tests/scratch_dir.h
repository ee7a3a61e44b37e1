#pragma once
// A scratch folder per test, <temp>/dfm_<name>_<pid>: fresh on construction, removed with its contents
// at scope exit.
#include <unistd.h>

#include <filesystem>
#include <string>

namespace dfm::test {

struct ScratchDir {
  std::filesystem::path dir;
  explicit ScratchDir(const std::string& name)
      : dir(std::filesystem::temp_directory_path() / ("dfm_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  std::string operator/(const std::string& f) const { return (dir / f).string(); }
};

}  // namespace dfm::test
