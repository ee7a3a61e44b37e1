// `deform sculpt` and `deform interpolate --method differential` end to end (the executable as a child
// process): the regions held in the written file, the uniform differential blend against the linear
// blend computed here, printed timings, and hostile index and state files refused by name (exit 1,
// nothing written).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/mesh/io.h"
#include "tests/cli_test_util.h"
#include "tests/sculpt_test_meshes.h"

using namespace dfm;
using namespace dfm::test;

namespace {

void write_indices(const std::string& path, const std::vector<int>& idx) {
  std::ofstream o(path);
  o << "# vertex indices\n";
  for (int i : idx) o << i << "\n";
}

}  // namespace

TEST_CASE("deform sculpt: fixed vertices kept, handle moved, timings printed; bad index files refused", "[cli][sculpt]") {
  ScratchDir s("cli_sculpt");
  const double h = 1.0 / 8;
  const TriMesh disk = ring_disk(h, 10);
  write_surface(s / "disk.obj", disk);
  const std::vector<int> fixed = ring_band(disk, 1.0, 1.25, h), handle = ring_band(disk, 0, 0.25, h);
  write_indices(s / "F.txt", fixed);
  write_indices(s / "H.txt", handle);
  for (const char* order : {"2", "3"}) {
    const RunResult r = run_deform(s, {"sculpt", s / "disk.obj", "--fixed", s / "F.txt", "--handle", s / "H.txt", "--move",
                                       "0.1", "-0.05", "0.2", "--order", order, "-o", s / "out.obj"});
    INFO(describe_run(r));
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Catch::Contains("factor") && Catch::Contains("solve"));
    const TriMesh out = read_surface(s / "out.obj");
    REQUIRE(out.V.rows() == disk.V.rows());
    for (int i : fixed) CHECK(out.V.row(i) == disk.V.row(i));
    for (int i : handle) CHECK((out.V.row(i) - disk.V.row(i) - Eigen::RowVector3d(0.1, -0.05, 0.2)).norm() < 1e-15);
    // The free ring between rises part of the way.
    CHECK(out.V.col(2).maxCoeff() == Approx(0.2));
  }
  // --rotate: the handle turns by 30 degrees about z through (0.1, 0, 0), then moves: each handle vertex
  // lands at R (p - c) + c + d exactly (the written file's digits).
  {
    const RunResult r = run_deform(s, {"sculpt", s / "disk.obj", "--fixed", s / "F.txt", "--handle", s / "H.txt", "--rotate", "0",
                                       "0", "2", "30", "--about", "0.1", "0", "0", "--move", "0", "0", "0.2", "-o", s / "out.obj"});
    INFO(describe_run(r));
    REQUIRE(r.exit_code == 0);
    const TriMesh out = read_surface(s / "out.obj");
    const double a = M_PI / 6;
    for (int i : handle) {
      const double x = disk.V(i, 0) - 0.1, y = disk.V(i, 1);
      const Eigen::RowVector3d want(0.1 + std::cos(a) * x - std::sin(a) * y, std::sin(a) * x + std::cos(a) * y, disk.V(i, 2) + 0.2);
      CHECK((out.V.row(i) - want).norm() < 1e-9);
    }
    for (int i : fixed) CHECK(out.V.row(i) == disk.V.row(i));
    const RunResult bad = run_deform(s, {"sculpt", s / "disk.obj", "--fixed", s / "F.txt", "--handle", s / "H.txt", "--rotate", "0",
                                         "0", "0", "30", "--move", "0", "0", "0", "-o", s / "out.obj"});
    CHECK(bad.exit_code == 2);
    CHECK_THAT(bad.err, Catch::Contains("nonzero axis"));
  }
  std::filesystem::remove(s / "out.obj");
  write_indices(s / "bad.txt", {0, 1, static_cast<int>(disk.V.rows())});
  std::ofstream(s / "junk.txt") << "3\nseven\n";
  std::vector<int> all;
  for (int i = 1; i < disk.V.rows(); ++i) all.push_back(i);
  write_indices(s / "all.txt", all);
  write_indices(s / "centre.txt", {0});
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--fixed", s / "bad.txt", "--handle", s / "H.txt"}, "bad.txt:4: vertex index " + std::to_string(disk.V.rows()) + " is out of range"},
      {{"--fixed", s / "F.txt", "--handle", s / "junk.txt"}, "junk.txt:2: expected one vertex index"},
      {{"--fixed", s / "all.txt", "--handle", s / "centre.txt"}, "free region is empty"},
      {{"--fixed", s / "F.txt", "--handle", s / "missing.txt"}, "missing.txt"},
      {{"--fixed", s / "F.txt", "--handle", s / "F.txt"}, "both fixed and in the handle"}};
  for (const auto& [flags, message] : cases) {
    std::vector<std::string> args{"sculpt", s / "disk.obj", "--move", "0", "0", "1", "-o", s / "out.obj"};
    args.insert(args.end(), flags.begin(), flags.end());
    const RunResult r = run_deform(s, args);
    INFO(describe_run(r));
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Catch::Contains(message));
    CHECK(!std::filesystem::exists(s / "out.obj"));
  }
  const RunResult usage = run_deform(s, {"sculpt", s / "disk.obj", "--fixed", s / "F.txt", "--handle", s / "H.txt", "--move",
                                         "0", "0", "1", "--order", "4", "-o", s / "out.obj"});
  CHECK(usage.exit_code == 2);
}

TEST_CASE("deform interpolate --method differential: uniform is linear, offsets read, bad state files refused", "[cli][sculpt]") {
  ScratchDir s("cli_differential");
  TriMesh k0 = ring_disk(1.0 / 8, 8), k1 = k0;
  for (int i = 0; i < k1.V.rows(); ++i) k1.V(i, 2) = 0.3 * std::exp(-k1.V.row(i).squaredNorm() / 0.1) + 0.2 * k1.V(i, 0);
  write_surface(s / "k0.obj", k0);
  write_surface(s / "k1.obj", k1);
  const RunResult r = run_deform(s, {"interpolate", "--keyframes", s / "k0.obj", s / "k1.obj", "--method", "differential",
                                     "--at", "0.3", "-o", s / "mid.obj"});
  INFO(describe_run(r));
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::Contains("factor") && Catch::Contains("solve"));
  const TriMesh mid = read_surface(s / "mid.obj");
  CHECK((mid.V - (0.7 * k0.V + 0.3 * k1.V)).cwiseAbs().maxCoeff() < 1e-9);
  // Offsets: the middle arrives early (0.6), so at T = 0.4 it is at state 1 while the rim is at 0.4.
  {
    std::ofstream o(s / "S.dmat");
    o << "1 " << k0.V.rows() << "\n";
    for (int i = 0; i < k0.V.rows(); ++i) o << (k0.V.row(i).norm() < 0.3 ? 0.6 : 0.0) << "\n";
  }
  const RunResult e = run_deform(s, {"interpolate", "--keyframes", s / "k0.obj", s / "k1.obj", "--method", "differential",
                                     "--states", s / "S.dmat", "--at", "0.4", "-o", s / "early.obj"});
  INFO(describe_run(e));
  REQUIRE(e.exit_code == 0);
  const TriMesh early = read_surface(s / "early.obj");
  // The centre's height above its neighbours' is the second key's (differential coordinates).
  CHECK(early.V(0, 2) - early.V(1, 2) == Approx(k1.V(0, 2) - k1.V(1, 2)).margin(0.02));
  {
    std::ofstream o(s / "short.dmat");
    o << "1 3\n0\n0\n0\n";
    std::ofstream p(s / "far.dmat");
    p << "1 " << k0.V.rows() << "\n";
    for (int i = 0; i < k0.V.rows(); ++i) p << (i == 5 ? 1.5 : 0.0) << "\n";
  }
  for (const auto& [file, message] : std::vector<std::pair<std::string, std::string>>{
           {"short.dmat", "short.dmat: transition-state offsets must be a"}, {"far.dmat", "far.dmat: transition state offset"}}) {
    const RunResult b = run_deform(s, {"interpolate", "--keyframes", s / "k0.obj", s / "k1.obj", "--method", "differential",
                                       "--states", s / file, "--at", "0.5", "-o", s / "bad.obj"});
    INFO(describe_run(b));
    CHECK(b.exit_code == 1);
    CHECK_THAT(b.err, Catch::Contains(message));
    CHECK(!std::filesystem::exists(s / "bad.obj"));
  }
}
