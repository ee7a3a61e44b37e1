#pragma once
// Whole-file byte helpers for tests that compare files exactly.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace dfm::test {

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void spill(const std::filesystem::path& p, const std::string& s) {
  std::ofstream(p, std::ios::binary) << s;
}

}  // namespace dfm::test
