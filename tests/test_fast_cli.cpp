// `deform pose --fast` end to end on hand.mesh with its 20 bones (Jacobson 2013, 7.3.1): with no free
// handle the output is exactly the plain LBS pose; with free bones the printed energy never increases
// and ends below the energy of the plain pose.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "core/mesh/io.h"
#include "tests/cli_test_util.h"
#include "tests/test_support.h"

using namespace dfm;
namespace fs = std::filesystem;

namespace {

std::vector<double> printed_energies(const std::string& out) {
  std::vector<double> e;
  const std::regex line("fast: iteration ([0-9]+) energy ([-+0-9.eE]+)");
  for (std::sregex_iterator it(out.begin(), out.end(), line), end; it != end; ++it) e.push_back(std::stod((*it)[2]));
  return e;
}

}  // namespace

TEST_CASE("deform pose --fast on the hand: no free handle is plain LBS; free bones lower the energy",
          "[fast][cli][data]") {
  DFM_DATA_OR_SKIP(mesh, "hand.mesh");
  DFM_DATA_OR_SKIP(tgf, "hand.tgf");
  DFM_DATA_OR_SKIP(pose, "hand-pose.dmat");
  const fs::path dir = fs::temp_directory_path() / ("dfm_test_fast_cli_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string exe = DFM_DEFORM_EXE, W = (dir / "W.dmat").string();
  auto run = [&](const std::vector<std::string>& args) {
    const test::RunResult r = test::run_program(exe, args, dir);
    INFO(r.command << "\n" << r.out << r.err);
    REQUIRE(r.exit_code == 0);
    return r.out;
  };
  run({"bind", mesh, "--skeleton", tgf, "-o", W});
  const std::vector<std::string> common{"pose", mesh, "--weights", W, "--skeleton", tgf, "--pose", pose, "--cpu"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = common;
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  run(with({"-o", (dir / "lbs.obj").string()}));
  const std::string fixed_out = run(with({"--fast", "--iterations", "3", "-o", (dir / "fixed.obj").string()}));
  const TriMesh lbs = read_surface((dir / "lbs.obj").string()), fixed = read_surface((dir / "fixed.obj").string());
  REQUIRE(lbs.V.rows() == fixed.V.rows());
  CHECK((lbs.V - fixed.V).cwiseAbs().maxCoeff() == 0.0);
  CHECK(printed_energies(fixed_out).size() == 3);

  const std::string free_out =
      run(with({"--fast", "--free", "5,6,7,bone 9", "--iterations", "15", "-o", (dir / "free.obj").string()}));
  const std::vector<double> e = printed_energies(free_out), e_fixed = printed_energies(fixed_out);
  REQUIRE(e.size() == 15);
  for (size_t i = 1; i < e.size(); ++i) CHECK(e[i] <= e[i - 1] * (1 + 1e-12));
  CHECK(e.back() < e_fixed.back());
  CHECK(free_out.find("precompute") != std::string::npos);
  CHECK(free_out.find("us per iteration") != std::string::npos);

  const test::RunResult bad = test::run_program(exe, with({"--fast", "--free", "no such bone", "-o", (dir / "x.obj").string()}), dir);
  CHECK(bad.exit_code != 0);
  CHECK(bad.err.find("no handle named 'no such bone'") != std::string::npos);
  fs::remove_all(dir);
}

namespace {

std::vector<double> printed_kinetic(const std::string& out) {
  std::vector<double> e;
  const std::regex line("dynamics: frame ([0-9]+) kinetic ([-+0-9.eE]+)");
  for (std::sregex_iterator it(out.begin(), out.end(), line), end; it != end; ++it) e.push_back(std::stod((*it)[2]));
  return e;
}

}  // namespace

TEST_CASE("deform pose --fast --dynamics on the arm: a frame per step, settling on the static solve (7.7)",
          "[fast][cli][dynamics][data]") {
  DFM_DATA_OR_SKIP(mesh, "arm.obj");
  const fs::path dir = fs::temp_directory_path() / ("dfm_test_fast_dyn_cli_" + std::to_string(::getpid()));
  fs::create_directories(dir / "seq");
  const std::string exe = DFM_DEFORM_EXE, W = (dir / "W.dmat").string(), P = (dir / "P.txt").string(),
                    PP = (dir / "PP.txt").string();
  {  // two handles at the shoulder, the elbow (solved entirely), the hand moved sideways
    std::ofstream(P) << "-0.7296 0.0117 -0.1328\n-0.7832 0.2166 -0.0075\n0.0814 0.1852 -0.0425\n0.7357 -0.1752 0.0902\n";
    std::ofstream(PP) << "0 0 0\n0 0 0\n0 0 0\n0 0 0.5\n";
  }
  auto run = [&](const std::vector<std::string>& args) {
    const test::RunResult r = test::run_program(exe, args, dir);
    INFO(r.command << "\n" << r.out << r.err);
    REQUIRE(r.exit_code == 0);
    return r.out;
  };
  run({"bind", mesh, "--points", P, "-o", W});
  const std::vector<std::string> common{"pose", mesh, "--weights", W, "--points", P, "--points-pose", PP,
                                        "--fast", "--free", "2", "--cpu"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = common;
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  run(with({"--iterations", "300", "-o", (dir / "static.obj").string()}));
  const std::string out = run(with({"--dynamics", "--frames", "24", "--dt", "0.25", "--iterations", "10", "--sequence",
                                    (dir / "seq" / "arm").string(), "-o", (dir / "last.obj").string()}));
  const std::vector<double> ke = printed_kinetic(out);
  REQUIRE(ke.size() == 24);
  for (int i = 0; i < 24; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "arm%04d.obj", i);
    CHECK(fs::exists(dir / "seq" / name));
  }
  CHECK(ke.back() < 1e-6 * ke.front());
  const TriMesh stat = read_surface((dir / "static.obj").string()), last = read_surface((dir / "last.obj").string()),
                first = read_surface((dir / "seq" / "arm0000.obj").string());
  const double diag = (stat.V.colwise().maxCoeff() - stat.V.colwise().minCoeff()).norm();
  CHECK((last.V - stat.V).rowwise().norm().maxCoeff() < 1e-3 * diag);
  CHECK((first.V - stat.V).rowwise().norm().maxCoeff() > 1e-2 * diag);  // the first frame lags
  // Bad input: the problem named, a usage error (exit 2, as every usage error of deform).
  for (const auto& [extra, message] :
       std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"--dynamics", "--frames", "3", "--sequence", "x"}, "--dynamics needs --dt H"},
           {{"--dynamics", "--frames", "3", "--dt", "-1", "--sequence", "x"}, "--dynamics needs --dt H"},
           {{"--dynamics", "--frames", "0", "--dt", "0.1", "--sequence", "x"}, "--frames N with N >= 1"},
           {{"--dynamics", "--frames", "3", "--dt", "0.1"}, "--dynamics needs --sequence PREFIX"},
           {{"--dynamics", "--frames", "3", "--dt", "0.1", "--damping", "-2", "--sequence", "x"}, "--damping must be >= 0"},
           {{"--sequence", "x", "-o", "y.obj"}, "go with --dynamics"}}) {
    const test::RunResult bad = test::run_program(exe, with(extra), dir);
    INFO(bad.command << "\n" << bad.err);
    CHECK(bad.exit_code == 2);
    CHECK(bad.err.find(message) != std::string::npos);
  }
  const test::RunResult no_fast =
      test::run_program(exe, {"pose", mesh, "--weights", W, "--points", P, "--dynamics", "--frames", "2", "--dt", "0.1",
                              "--sequence", "x"}, dir);
  CHECK(no_fast.exit_code == 2);
  CHECK(no_fast.err.find("--dynamics needs --fast") != std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("deform bind --additional and pose --fast --additional: the cigar's free extras fill the bend (7.3.3)",
          "[fast][cli][additional]") {
  const fs::path dir = fs::temp_directory_path() / ("dfm_test_fast_additional_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string exe = DFM_DEFORM_EXE, mesh = std::string(DFM_SOURCE_DIR) + "/docs/cigar.obj",
                    tgf = (dir / "ends.tgf").string(), Q = (dir / "turn.dmat").string(), W = (dir / "W.dmat").string(),
                    A = (dir / "A.dmat").string();
  {  // a pinned bone in each end of the cigar (x in [-2.5, 2.5]); the right one turned 90 degrees about z
    std::ofstream(tgf) << "1 -2.4 0 0\n2 -1.8 0 0\n3 1.8 0 0\n4 2.4 0 0\n#\n1 2\n3 4\n";
    const double s = std::sqrt(0.5);
    std::ofstream(Q) << "4 2\n0 0\n0 0\n0 " << s << "\n1 " << s << "\n";  // x, y, z, w columns; bone 2 turned
  }
  auto run = [&](const std::vector<std::string>& args) {
    const test::RunResult r = test::run_program(exe, args, dir);
    INFO(r.command << "\n" << r.out << r.err);
    REQUIRE(r.exit_code == 0);
    return r.out;
  };
  const std::string bound = run({"bind", mesh, "--skeleton", tgf, "-o", W, "--additional", "6", A});
  CHECK(bound.find("additional weights, 1226 x 6") != std::string::npos);
  const TriMesh cigar = read_surface(mesh);
  const std::vector<std::string> common{"pose", mesh, "--weights", W, "--skeleton", tgf, "--cpu", "--fast", "--iterations", "30"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = common;
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  // At rest the extras solve to zero: the bind's own rest shape.
  run(with({"--additional", A, "-o", (dir / "rest.obj").string()}));
  CHECK((read_surface((dir / "rest.obj").string()).V - cigar.V).cwiseAbs().maxCoeff() < 1e-9);
  // Turned: both ends are pinned bones, so without extras FAST has nothing to solve (LBS); with them the
  // energy falls from that pose's and the middle moves.
  const std::string lbs_out = run(with({"--pose", Q, "-o", (dir / "lbs.obj").string()}));
  const std::string extra_out = run(with({"--pose", Q, "--additional", A, "-o", (dir / "extra.obj").string()}));
  CHECK(extra_out.find("fast: 6 additional handles solved") != std::string::npos);
  const std::vector<double> e_lbs = printed_energies(lbs_out), e = printed_energies(extra_out);
  REQUIRE(e.size() == 30);
  for (size_t i = 1; i < e.size(); ++i) CHECK(e[i] <= e[i - 1] * (1 + 1e-12));
  INFO("energy: LBS " << e_lbs.back() << ", with 6 additional handles " << e.back());
  CHECK(e.back() < 0.5 * e_lbs.back());
  const TriMesh lbs = read_surface((dir / "lbs.obj").string()), extra = read_surface((dir / "extra.obj").string());
  CHECK((lbs.V - extra.V).rowwise().norm().maxCoeff() > 0.05);
  // Dynamics takes them too: frames written, settling.
  fs::create_directories(dir / "seq");
  const std::string dyn = run(with({"--pose", Q, "--additional", A, "--dynamics", "--frames", "3", "--dt", "0.5", "--sequence",
                                    (dir / "seq" / "c").string()}));
  CHECK(fs::exists(dir / "seq" / "c0002.obj"));
  // Bad input: named, nothing written.
  const test::RunResult no_fast =
      test::run_program(exe, {"pose", mesh, "--weights", W, "--skeleton", tgf, "--additional", A, "-o", "x.obj"}, dir);
  CHECK(no_fast.exit_code == 2);
  CHECK(no_fast.err.find("--additional needs --fast") != std::string::npos);
  const std::string bad = (dir / "bad.dmat").string();
  std::ofstream(bad) << "3 2\n0 0 0 0 0 0\n";
  const test::RunResult rows = test::run_program(exe, with({"--additional", bad, "-o", "x.obj"}), dir);
  CHECK(rows.exit_code == 1);
  CHECK(rows.err.find("bad.dmat") != std::string::npos);
  CHECK(rows.err.find("one finite row per mesh vertex (1226)") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "x.obj"));
  const test::RunResult k0 = test::run_program(exe, {"bind", mesh, "--skeleton", tgf, "-o", W, "--additional", "0", A}, dir);
  CHECK(k0.exit_code == 2);
  CHECK(k0.err.find("--additional K must be between 1 and 100") != std::string::npos);
  fs::remove_all(dir);
}
