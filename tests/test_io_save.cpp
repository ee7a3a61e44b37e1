// Saving never destroys the previous file on failure. Each failing save runs in a forked child so the
// failure can be real without touching the test process:
//   full disk:         setrlimit(RLIMIT_FSIZE) with SIGXFSZ ignored, so write(2) fails with EFBIG
//                      (the same path through the stream as ENOSPC);
//   permission denied: the child drops root to uid/gid 65534 (or, when not root, the folder is made
//                      read-only), so creating the temp file beside the target fails with EACCES;
//   not a folder:      the target's parent is a regular file (ENOTDIR), which denies root as well.
// After each: the previous file is intact byte for byte, no temp file is left, the error names the file.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include <grp.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include "core/mesh/io.h"
#include "core/scene/scene_file.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "tests/fuzz/fuzz_scene_fixture.h"
#include "tests/file_bytes.h"

using namespace dfm;
namespace fs = std::filesystem;
using Catch::Contains;

namespace {

using dfm::test::slurp;
using dfm::test::spill;

struct TempDir {
  fs::path dir;
  explicit TempDir(const std::string& tag) {
    dir = fs::temp_directory_path() / ("dfm_test_io_save_" + tag + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    fs::permissions(dir, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                             fs::perms::others_read | fs::perms::others_exec);
  }
  ~TempDir() {
    std::error_code ec;
    fs::permissions(dir, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(dir, ec);
  }
  // Every entry in the folder (temp files start with '.', so they show here too).
  std::vector<std::string> entries() const {
    std::vector<std::string> v;
    for (const auto& e : fs::directory_iterator(dir)) v.push_back(e.path().filename().string());
    std::sort(v.begin(), v.end());
    return v;
  }
};

enum class Failure { FullDisk, PermissionDenied };

struct ChildResult {
  bool threw_error = false;  // the save threw dfm::Error (the expected outcome)
  std::string message;       // its what()
  std::string other;         // anything else that happened instead
};

// Runs `save` in a forked child under `failure`; the child reports through a pipe.
ChildResult save_in_child(Failure failure, const fs::path& dir, const std::function<void()>& save) {
  int fd[2];
  REQUIRE(::pipe(fd) == 0);
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    ::close(fd[0]);
    auto report = [&](char kind, const std::string& text) {
      const std::string msg = kind + text;
      ssize_t n = ::write(fd[1], msg.data(), msg.size());
      (void)n;
      ::_exit(0);
    };
    if (failure == Failure::FullDisk) {
      ::signal(SIGXFSZ, SIG_IGN);  // EFBIG instead of a signal
      struct rlimit lim = {4096, 4096};
      if (::setrlimit(RLIMIT_FSIZE, &lim) != 0) report('?', "setrlimit failed");
    } else if (::geteuid() == 0) {
      // Root ignores permission bits: become nobody, who cannot write into a root-owned 0755 folder.
      if (::setgroups(0, nullptr) != 0 || ::setgid(65534) != 0 || ::setuid(65534) != 0)
        report('?', "cannot drop root privileges");
    }
    try {
      save();
      report('?', "the save succeeded");
    } catch (const Error& e) {
      report('E', e.what());
    } catch (const std::exception& e) {
      report('?', std::string("non-dfm exception: ") + e.what());
    }
    report('?', "unknown exception");
  }
  ::close(fd[1]);
  std::string out;
  char buf[4096];
  for (ssize_t n; (n = ::read(fd[0], buf, sizeof buf)) > 0;) out.append(buf, static_cast<size_t>(n));
  ::close(fd[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ChildResult r;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    r.other = "child died: status " + std::to_string(status);
  } else if (!out.empty() && out[0] == 'E') {
    r.threw_error = true;
    r.message = out.substr(1);
  } else {
    r.other = out.empty() ? "no report" : out.substr(1);
  }
  return r;
}

// For PermissionDenied when not root: make the folder read-only around the child.
struct ReadOnlyUnlessRoot {
  fs::path dir;
  bool active = false;
  ReadOnlyUnlessRoot(Failure f, const fs::path& d) : dir(d) {
    if (f == Failure::PermissionDenied && ::geteuid() != 0) {
      fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
      active = true;
    }
  }
  ~ReadOnlyUnlessRoot() {
    if (active) fs::permissions(dir, fs::perms::owner_all);
  }
};

// A mesh whose OBJ text is far above the 4096-byte limit.
TriMesh big_mesh() {
  TriMesh m;
  const int n = 3000;
  m.V.resize(n, 3);
  m.F.resize(n - 2, 3);
  for (int i = 0; i < n; ++i) m.V.row(i) << i * 0.001, std::sin(i * 0.1), std::cos(i * 0.1);
  for (int i = 0; i < n - 2; ++i) m.F.row(i) << i, i + 1, i + 2;
  return m;
}

const char* failure_name(Failure f) { return f == Failure::FullDisk ? "full disk" : "permission denied"; }

}  // namespace

TEST_CASE("write_file_atomic keeps the previous file on a full disk or a refused folder", "[io][save]") {
  for (Failure f : {Failure::FullDisk, Failure::PermissionDenied}) {
    // Large writes fail in the middle of writing; a 5000-byte write fails only at the final flush.
    for (size_t bytes : {size_t(1) << 20, size_t(5000)}) {
      INFO(failure_name(f) << ", " << bytes << " bytes");
      TempDir t("atomic");
      const fs::path target = t.dir / "doc.txt";
      const std::string old = "the previous version\n";
      spill(target, old);
      ChildResult r;
      {
        ReadOnlyUnlessRoot ro(f, t.dir);
        r = save_in_child(f, t.dir, [&] {
          write_file_atomic(target.string(), [&](std::ostream& o) { o << std::string(bytes, 'x'); });
        });
      }
      INFO(r.other);
      REQUIRE(r.threw_error);
      CHECK_THAT(r.message, Contains(target.string()));
      CHECK_THAT(r.message, Contains(f == Failure::FullDisk ? "write failed" : "Permission denied"));
      CHECK(slurp(target) == old);
      CHECK(t.entries() == std::vector<std::string>{"doc.txt"});
    }
  }
  // The same writes succeed without the failure, so the checks above test the failure and nothing else.
  TempDir t("atomic_ok");
  write_file_atomic((t.dir / "doc.txt").string(), [](std::ostream& o) { o << std::string(1 << 20, 'x'); });
  CHECK(fs::file_size(t.dir / "doc.txt") == (1u << 20));
  CHECK(t.entries() == std::vector<std::string>{"doc.txt"});
}

TEST_CASE("a save under a parent that is a file, or on /proc, names the file and leaves it alone", "[io][save]") {
  TempDir t("notdir");
  spill(t.dir / "plain", "a regular file");
  const std::string bad = (t.dir / "plain" / "out.obj").string();
  try {
    write_surface(bad, big_mesh());
    FAIL("expected an error");
  } catch (const Error& e) {
    CHECK_THAT(e.what(), Contains(bad));
    CHECK_THAT(e.what(), Contains("cannot create temporary file"));
  }
  CHECK(slurp(t.dir / "plain") == "a regular file");
  // /proc refuses new files even to root: the existing /proc/self/comm keeps its content.
  if (fs::exists("/proc/self/comm")) {
    const std::string before = slurp("/proc/self/comm");
    CHECK_THROWS_WITH(write_file_atomic("/proc/self/comm", [](std::ostream& o) { o << "overwritten"; }),
                      Contains("/proc/self/comm"));
    CHECK(slurp("/proc/self/comm") == before);
  }
}

TEST_CASE("OBJ, binary PLY and dmat writers keep the previous file on failure", "[io][save]") {
  const TriMesh m = big_mesh();
  for (Failure f : {Failure::FullDisk, Failure::PermissionDenied}) {
    for (const char* name : {"mesh.obj", "mesh.ply", "w.dmat"}) {
      INFO(failure_name(f) << ", " << name);
      TempDir t("writers");
      const fs::path target = t.dir / name;
      const std::string ext = target.extension().string();
      // The previous file is a valid small one, written by the same writer.
      TriMesh small;
      small.V = m.V.topRows(3);
      small.F = m.F.topRows(1);
      if (ext == ".dmat") write_dmat(target.string(), small.V, true);
      else write_surface(target.string(), small, true);
      const std::string old = slurp(target);
      ChildResult r;
      {
        ReadOnlyUnlessRoot ro(f, t.dir);
        r = save_in_child(f, t.dir, [&] {
          if (ext == ".dmat") write_dmat(target.string(), m.V, true);
          else write_surface(target.string(), m, true);
        });
      }
      INFO(r.other);
      REQUIRE(r.threw_error);
      CHECK_THAT(r.message, Contains(target.string()));
      CHECK(slurp(target) == old);
      CHECK(t.entries() == std::vector<std::string>{name});
      // And the previous file still reads as before.
      if (ext == ".dmat") CHECK(read_dmat(target.string()) == small.V);
      else CHECK(read_surface(target.string()).F == small.F);
    }
  }
}

TEST_CASE("a failed scene save leaves the previous scene (JSON and sidecar) loadable", "[io][save][scene]") {
  const SceneData old_scene = fuzz::fixed_scene();
  // The new scene: a big surface (its sidecar alone is over the limit) or many keys (the sidecar fits
  // under the limit, the JSON does not: the sidecar must not replace the old one on its own).
  SceneData big_sidecar = old_scene, big_json = old_scene;
  big_sidecar.surface = big_mesh();
  big_sidecar.weights.resize(0, 0);
  big_sidecar.mask.resize(0);
  big_sidecar.tets = TetMesh();
  big_sidecar.surface_to_tet.resize(0);
  big_sidecar.rig.regions.clear();
  big_sidecar.pose = rest_pose_params(big_sidecar.rig);
  big_sidecar.keys.clear();
  big_sidecar.selection.handles = {0};
  for (int i = 0; i < 200; ++i) big_json.keys.push_back({2.0 + i, big_json.pose});
  for (Failure f : {Failure::FullDisk, Failure::PermissionDenied}) {
    for (const SceneData* next : {&big_sidecar, &big_json}) {
      INFO(failure_name(f) << (next == &big_json ? ", big JSON" : ", big sidecar"));
      TempDir t("scene");
      const fs::path json = t.dir / "s.scene.json", bin = t.dir / "s.scene.bin";
      write_scene(json.string(), old_scene);
      const std::string old_json = slurp(json), old_bin = slurp(bin);
      if (f == Failure::FullDisk && next == &big_json) {
        // The case this guards: the new sidecar fits under the limit, the new JSON does not.
        TempDir probe("scene_probe");
        write_scene((probe.dir / "s.scene.json").string(), *next);
        REQUIRE(fs::file_size(probe.dir / "s.scene.bin") < 4096);
        REQUIRE(fs::file_size(probe.dir / "s.scene.json") > 4096);
      }
      ChildResult r;
      {
        ReadOnlyUnlessRoot ro(f, t.dir);
        r = save_in_child(f, t.dir, [&] { write_scene(json.string(), *next); });
      }
      INFO(r.other);
      REQUIRE(r.threw_error);
      CHECK((r.message.find(json.string()) != std::string::npos || r.message.find(bin.string()) != std::string::npos));
      CHECK(slurp(json) == old_json);
      CHECK(slurp(bin) == old_bin);
      CHECK(t.entries() == std::vector<std::string>{"s.scene.bin", "s.scene.json"});
      const SceneData back = read_scene(json.string());
      CHECK(back.surface.V == old_scene.surface.V);
      CHECK(back.keys.size() == old_scene.keys.size());
    }
  }
}
