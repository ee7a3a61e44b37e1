// `deform pose --fast` end to end on hand.mesh with its 20 bones (Jacobson 2013, 7.3.1): with no free
// handle the output is exactly the plain LBS pose; with free bones the printed energy never increases
// and ends below the energy of the plain pose.
#include <filesystem>
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
