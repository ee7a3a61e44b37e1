#pragma once
// Shared test helpers: locating ../shared/data. When CI=true a missing file fails the test;
// elsewhere the test is skipped with a visible message.
#include <cstdlib>
#include <filesystem>
#include <string>

#include <catch2/catch.hpp>

#include "core/util/error.h"

namespace dfm::test {

inline std::string data_dir() {
  const char* env = std::getenv("DFM_DATA_DIR");
  return env ? env : DFM_DATA_DIR;
}

inline bool running_in_ci() {
  const char* ci = std::getenv("CI");
  return ci && std::string(ci) == "true";
}

// Full path of a shared data file, or "" when absent outside CI (the caller then returns).
inline std::string data_file(const std::string& name) {
  std::string p = data_dir() + "/" + name;
  if (std::filesystem::exists(p)) return p;
  if (running_in_ci()) FAIL("shared data file missing in CI: " << p);
  WARN("SKIPPED: shared data file not found: " << p);
  return "";
}

// What a call threw, told apart by type: "cancelled" (dfm::Cancelled), "error" (any other dfm::Error)
// or "nothing".
template <class F>
std::string thrown_kind(F&& f) {
  try {
    f();
  } catch (const Cancelled&) {
    return "cancelled";
  } catch (const Error&) {
    return "error";
  }
  return "nothing";
}

}  // namespace dfm::test

#define DFM_DATA_OR_SKIP(var, name)            \
  const std::string var = dfm::test::data_file(name); \
  if (var.empty()) return
