#pragma once
// Runs tests/gltf/validate.js (the Khronos glTF Validator under Node.js) from C++ tests.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <unistd.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "tests/test_support.h"

namespace dfm::test {

inline std::string gltf_validator_dir() { return DFM_GLTF_VALIDATOR_DIR; }

inline std::filesystem::path gltf_temp_dir(const std::string& name) {
  auto d = std::filesystem::temp_directory_path() / ("dfm_gltf_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

inline std::string run_capture(const std::string& cmd, int* status) {
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) {
    *status = -1;
    return out;
  }
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  const int rc = pclose(p);
  *status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  return out;
}

// Installs the pinned gltf-validator (npm ci) when missing. False = skip (outside CI only); in CI a
// missing Node/npm or a failed install FAILS the test with the reason.
inline bool gltf_validator_ready() {
  const std::string dir = gltf_validator_dir();
  if (std::filesystem::exists(dir + "/node_modules/gltf-validator/package.json")) return true;
  int rc = 0;
  std::string log = run_capture("command -v node && command -v npm 2>&1", &rc);
  std::string why;
  if (rc != 0) {
    why = "node and npm are needed to run the Khronos glTF Validator but were not found on PATH";
  } else {
    const std::string install = std::filesystem::exists(dir + "/package-lock.json") ? "npm ci" : "npm install";
    log = run_capture("cd '" + dir + "' && " + install + " --no-audit --no-fund 2>&1", &rc);
    if (rc == 0 && std::filesystem::exists(dir + "/node_modules/gltf-validator/package.json")) return true;
    why = "could not install the gltf-validator npm package in " + dir + " (" + install + " exit " +
          std::to_string(rc) + "):\n" + log;
  }
  if (running_in_ci()) FAIL("glTF validator unavailable in CI: " << why);
  WARN("SKIPPED: glTF validator unavailable: " << why);
  return false;
}

// The validator's JSON summary for one file (see tests/gltf/validate.js).
inline nlohmann::json run_gltf_validator(const std::string& file) {
  int rc = 0;
  const std::string out = run_capture("node '" + gltf_validator_dir() + "/validate.js' '" + file + "' 2>&1", &rc);
  INFO("validate.js output: " << out);
  REQUIRE(rc != 2);
  nlohmann::json j;
  REQUIRE_NOTHROW(j = nlohmann::json::parse(out));
  return j;
}

// Zero errors and zero warnings, with the messages shown on failure.
inline void check_gltf_valid(const std::string& file) {
  const nlohmann::json r = run_gltf_validator(file);
  INFO(file << ": " << r.dump(1));
  CHECK(r.value("errors", -1) == 0);
  CHECK(r.value("warnings", -1) == 0);
}

}  // namespace dfm::test
