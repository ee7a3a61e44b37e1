// `deform shape-space` end to end: --at synthesizes the affine combination (written here) and each
// base exactly at its own coordinates; --analyze prints the coordinates a shape was made with and a
// zero residual; bad files exit 1 naming the file, usage problems exit 2.
#include <unistd.h>

#include <filesystem>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/mesh/io.h"
#include "tests/cli_test_util.h"
#include "tests/volume_test_meshes.h"

using dfm::test::run_program;
using dfm::test::describe_run;
using dfm::test::RunResult;
namespace fs = std::filesystem;

namespace {

struct Scratch : dfm::test::ScratchDir {
  Scratch() : ScratchDir("test_shape_space_cli") {}
};

RunResult deform(const Scratch& s, const std::vector<std::string>& args) { return dfm::test::run_deform(s, args); }

// Three wobbly icospheres (one connectivity) written as OBJ (17 digits: they read back exactly).
std::vector<std::string> write_bases(const Scratch& s, std::vector<dfm::TriMesh>& meshes) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  std::vector<std::string> files;
  for (int k = 0; k < 3; ++k) {
    dfm::TriMesh m = dfm::test::icosphere(Eigen::Vector3d::Zero(), 1.0, 1);
    for (int i = 0; i < m.V.rows(); ++i)
      for (int c = 0; c < 3; ++c) m.V(i, c) += u(rng);
    files.push_back(s / ("k" + std::to_string(k) + ".obj"));
    dfm::write_surface(files.back(), m);
    meshes.push_back(dfm::read_surface(files.back()));
  }
  return files;
}

std::vector<double> coordinates(const std::string& out) {
  std::smatch m;
  std::vector<double> x;
  if (!std::regex_search(out, m, std::regex("coordinates:([^\n]*)"))) return x;
  std::istringstream in(m[1].str());
  for (double v; in >> v;) x.push_back(v);
  return x;
}

}  // namespace

TEST_CASE("deform shape-space: synthesis, exact bases, analysis round trip", "[cli][shape_space]") {
  Scratch s;
  std::vector<dfm::TriMesh> B;
  const std::vector<std::string> k = write_bases(s, B);
  const std::string out = s / "out.obj";

  // The affine combination 0.2 B0 + 0.5 B1 + 0.3 B2 (Eq. 5.36), computed here.
  RunResult r = deform(s, {"shape-space", "--bases", k[0], k[1], k[2], "--at", "0.2", "0.5", "0.3", "-o", out});
  REQUIRE(r.exit_code == 0);
  const Eigen::MatrixXd want = 0.2 * B[0].V + 0.5 * B[1].V + 0.3 * B[2].V;
  const dfm::TriMesh got = dfm::read_surface(out);
  REQUIRE(got.V.rows() == want.rows());
  REQUIRE(got.F.rows() == B[0].F.rows());
  CHECK(got.F == B[0].F);
  CHECK((got.V - want).cwiseAbs().maxCoeff() < 1e-12);

  for (int i = 0; i < 3; ++i)
    for (const char* method : {"linear", "arap"}) {
      std::vector<std::string> args = {"shape-space", "--bases", k[0], k[1], k[2], "--method", method, "--at"};
      for (int j = 0; j < 3; ++j) args.push_back(i == j ? "1" : "0");
      args.insert(args.end(), {"-o", out});
      r = deform(s, args);
      INFO(describe_run(r));
      REQUIRE(r.exit_code == 0);
      const Eigen::MatrixXd V = dfm::read_surface(out).V;
      REQUIRE(V.rows() == B[i].V.rows());
      CHECK(V == B[i].V);
    }

  // Analysis of a synthesized shape (with extrapolating weights) returns its coordinates.
  r = deform(s, {"shape-space", "--bases", k[0], k[1], k[2], "--at", "-0.25", "0.5", "0.75", "-o", out});
  REQUIRE(r.exit_code == 0);
  r = deform(s, {"shape-space", "--bases", k[0], k[1], k[2], "--analyze", out});
  INFO(describe_run(r));
  REQUIRE(r.exit_code == 0);
  const std::vector<double> x = coordinates(r.out);
  REQUIRE(x.size() == 3);
  CHECK(std::abs(x[0] + 0.25) < 1e-9);
  CHECK(std::abs(x[1] - 0.5) < 1e-9);
  CHECK(std::abs(x[2] - 0.75) < 1e-9);
  std::smatch m;
  REQUIRE(std::regex_search(r.out, m, std::regex("residual: rms ([^,]+), max ([^ ]+)")));
  CHECK(std::stod(m[1]) < 1e-9);
  CHECK(std::stod(m[2]) < 1e-9);
}

TEST_CASE("deform shape-space: bad files exit 1 naming the file, usage problems exit 2", "[cli][shape_space]") {
  Scratch s;
  std::vector<dfm::TriMesh> B;
  const std::vector<std::string> k = write_bases(s, B);
  const std::string out = s / "out.obj", other = s / "other.obj", missing = s / "missing.obj";
  dfm::write_surface(other, dfm::test::icosphere(Eigen::Vector3d::Zero(), 1.0, 2));

  RunResult r = deform(s, {"shape-space", "--bases", k[0], missing, "--at", "0.5", "0.5", "-o", out});
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("missing.obj") != std::string::npos);
  r = deform(s, {"shape-space", "--bases", k[0], k[1], other, "--at", "0.2", "0.3", "0.5", "-o", out});
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("other.obj") != std::string::npos);
  r = deform(s, {"shape-space", "--bases", k[0], k[1], "--analyze", other});
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("other.obj") != std::string::npos);
  CHECK(!fs::exists(out));

  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"shape-space", "--bases", k[0], "--at", "1", "-o", out},                           // one base
           {"shape-space", "--bases", k[0], k[1], "--at", "0.5", "-o", out},                   // count
           {"shape-space", "--bases", k[0], k[1], "--at", "0.5", "0.6", "-o", out},            // sum
           {"shape-space", "--bases", k[0], k[1], "--at", "0.5", "nan", "-o", out},            // not finite
           {"shape-space", "--bases", k[0], k[1], k[2], "--at", "1", "1", "-1", "-o", out},    // S_1 = 0
           {"shape-space", "--bases", k[0], k[1], "--at", "0.5", "0.5"},                       // no -o
           {"shape-space", "--bases", k[0], k[1]},                                             // neither
           {"shape-space", "--bases", k[0], k[1], "--analyze", k[0], "--method", "arap"},
           {"shape-space", "--bases", k[0], k[1], "--at", "0.5", "0.5", "-o", out, "--method", "cubic"}}) {
    r = deform(s, args);
    INFO(describe_run(r));
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("usage: deform shape-space") != std::string::npos);
  }
  CHECK(!fs::exists(out));
}
