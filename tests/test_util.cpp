#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/util/huge_pages.h"

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

// Whether the mapping holding address a is advised for huge pages ("hg" in /proc/self/smaps).
static bool advised_huge(const void* a) {
  std::ifstream smaps("/proc/self/smaps");
  const auto x = reinterpret_cast<std::uintptr_t>(a);
  bool inside = false;
  for (std::string line; std::getline(smaps, line);) {
    std::uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> lo >> dash >> hi && dash == '-') {
      inside = lo <= x && x < hi;
      continue;
    }
    if (inside && line.rfind("VmFlags:", 0) == 0) return line.find(" hg") != std::string::npos;
  }
  return false;
}

TEST_CASE("advise_huge_pages advises exactly the whole 2 MB pages inside the range", "[util]") {
  if (!fs::exists("/sys/kernel/mm/transparent_hugepage/enabled")) {
    WARN("this kernel has no transparent huge pages: nothing to check");
    return;
  }
  constexpr std::size_t kHuge = std::size_t{2} << 20, kBytes = 5 * kHuge;
  void* map = mmap(nullptr, kBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  REQUIRE(map != MAP_FAILED);
  char* p = static_cast<char*>(map);
  // A range starting one 4 KB page in and ending one short of the end: its whole 2 MB pages only.
  dfm::advise_huge_pages(p + 4096, kBytes - 2 * 4096);
  const auto at = reinterpret_cast<std::uintptr_t>(p);
  char* first = p + ((at + 4096 + kHuge - 1) / kHuge * kHuge - at);
  char* end = p + ((at + kBytes - 4096) / kHuge * kHuge - at);
  REQUIRE(end - first >= static_cast<std::ptrdiff_t>(2 * kHuge));
  CHECK(!advised_huge(first - 1));
  CHECK(advised_huge(first));
  CHECK(advised_huge(end - 1));
  CHECK(!advised_huge(end));
  // The memory stays ordinary memory.
  for (std::size_t i = 0; i < kBytes; i += 4096) p[i] = static_cast<char>(i / 4096);
  bool same = true;
  for (std::size_t i = 0; i < kBytes; i += 4096) same = same && p[i] == static_cast<char>(i / 4096);
  CHECK(same);
  munmap(map, kBytes);
  // A range under two huge pages is left alone, even one starting on a 2 MB boundary.
  map = mmap(nullptr, kBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  REQUIRE(map != MAP_FAILED);
  p = static_cast<char*>(map);
  char* q = p + ((reinterpret_cast<std::uintptr_t>(p) + kHuge - 1) / kHuge * kHuge - reinterpret_cast<std::uintptr_t>(p));
  dfm::advise_huge_pages(q, 2 * kHuge - 1);  // holds the whole page [q, q + 2 MB)
  CHECK(!advised_huge(q));
  munmap(map, kBytes);
}
