#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace fs = std::filesystem;

static std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST_CASE("atomic write replaces the file only on success", "[util]") {
  fs::path dir = fs::temp_directory_path() / "dfm_test_util";
  fs::create_directories(dir);
  fs::path f = dir / "a.txt";
  dfm::write_file_atomic(f.string(), [](std::ostream& o) { o << "first"; });
  REQUIRE(slurp(f) == "first");
  // A writer that fails half-way leaves the previous content and no temp files.
  REQUIRE_THROWS_AS(dfm::write_file_atomic(f.string(), [](std::ostream& o) {
                      o << "partial";
                      throw dfm::Error("boom");
                    }),
                    dfm::Error);
  REQUIRE(slurp(f) == "first");
  int files = 0;
  for (auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
  REQUIRE(files == 1);
  fs::remove_all(dir);
}

TEST_CASE("atomic write into a missing folder names the file", "[util]") {
  try {
    dfm::write_file_atomic("/nonexistent-folder-xyz/out.obj", [](std::ostream& o) { o << "x"; });
    FAIL("expected an error");
  } catch (const dfm::Error& e) {
    REQUIRE(std::string(e.what()).find("/nonexistent-folder-xyz/out.obj") != std::string::npos);
  }
}

TEST_CASE("file_extension and require_readable_file", "[util]") {
  REQUIRE(dfm::file_extension("a/b.OBJ") == "obj");
  REQUIRE(dfm::file_extension("noext") == "");
  REQUIRE_THROWS_WITH(dfm::require_readable_file("/no/such/file.obj"), Catch::Contains("no such file"));
  REQUIRE_THROWS_WITH(dfm::require_readable_file(fs::temp_directory_path().string()),
                      Catch::Contains("directory"));
}

TEST_CASE("require_readable_file refuses a pipe instead of blocking on it", "[util]") {
  fs::path dir = fs::temp_directory_path() / ("dfm_test_util_fifo_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path fifo = dir / "pipe.obj";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  REQUIRE_THROWS_WITH(dfm::require_readable_file(fifo.string()), Catch::Contains("pipe.obj") && Catch::Contains("pipe"));
  fs::remove_all(dir);
}

TEST_CASE("write_files_atomic replaces no file unless every write succeeded", "[util]") {
  fs::path dir = fs::temp_directory_path() / ("dfm_test_util_multi_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string a = (dir / "a.bin").string(), b = (dir / "b.json").string();
  dfm::write_files_atomic({{a, [](std::ostream& o) { o << "A1"; }, true}, {b, [](std::ostream& o) { o << "B1"; }}});
  REQUIRE(slurp(a) == "A1");
  REQUIRE(slurp(b) == "B1");
  // The second writer fails after the first one's temp was complete: the first must not be renamed.
  REQUIRE_THROWS_WITH(dfm::write_files_atomic({{a, [](std::ostream& o) { o << "A2"; }, true},
                                               {b, [](std::ostream& o) {
                                                  o << "B2";
                                                  throw dfm::Error("b.json: boom");
                                                }}}),
                      Catch::Contains("boom"));
  REQUIRE(slurp(a) == "A1");
  REQUIRE(slurp(b) == "B1");
  std::vector<std::string> names;  // no temp file (".a.bin.tmpN") is left behind
  for (auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  REQUIRE(names == std::vector<std::string>{"a.bin", "b.json"});
  dfm::write_files_atomic({{a, [](std::ostream& o) { o << "A3"; }, true}, {b, [](std::ostream& o) { o << "B3"; }}});
  REQUIRE(slurp(a) == "A3");
  REQUIRE(slurp(b) == "B3");
  fs::remove_all(dir);
}
