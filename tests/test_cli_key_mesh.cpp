// `deform manifold --keyframes` of any connectivity (build_manifold_sequence): same-connectivity keys
// give exactly the prism build, --stats prints the build's stages, a bad keyframe (missing, open, NaN)
// exits 1 naming the file, and a sphere -> torus transition slices closed.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <Eigen/Geometry>

#include "core/anim/manifold.h"
#include "core/anim/manifold_io.h"
#include "core/mesh/io.h"
#include "tests/cli_test_util.h"
#include "tests/key_mesh_test_meshes.h"

using dfm::test::run_program;
using dfm::test::describe_run;
using dfm::test::RunResult;
namespace fs = std::filesystem;

namespace {

struct Scratch : dfm::test::ScratchDir {
  Scratch() : ScratchDir("test_cli_key_mesh") {}
};

RunResult deform(const Scratch& s, const std::vector<std::string>& args) { return dfm::test::run_deform(s, args); }

long count_field(const std::string& text, const std::string& key) {
  std::smatch m;
  if (std::regex_search(text, m, std::regex("\\b" + key + ": (-?[0-9]+)"))) return std::stol(m[1]);
  return -1;
}

dfm::TriMesh sphere() { return dfm::test::icosphere({0, 0, 0}, 1.0, 1); }
dfm::TriMesh torus() { return dfm::test::torus({0, 0, 0}, 1.0, 0.35, 16, 8); }

}  // namespace

TEST_CASE("deform manifold: same-connectivity keyframes are exactly the prism build, with stage stats", "[cli]") {
  Scratch s;
  dfm::TriMesh a = sphere(), b = sphere(), c = sphere();
  b.V.col(1).array() += 0.25;
  c.V *= 1.3;
  dfm::test::write_obj_raw(s / "a.obj", a);
  dfm::test::write_obj_raw(s / "b.obj", b);
  dfm::test::write_obj_raw(s / "c.obj", c);
  const RunResult r = deform(s, {"manifold", "--keyframes", s / "a.obj", s / "b.obj", s / "c.obj", "--times", "0", "1",
                                 "3", "--at", "0.5", "-o", s / "slice.obj", "--stats", "--save-manifold", s / "m.tet4",
                                 "--frames", "3", "--sequence", s / "seq"});
  INFO(describe_run(r));
  REQUIRE(r.exit_code == 0);
  CHECK(count_field(r.out, "prism slabs") == 2);
  CHECK(count_field(r.out, "transition slabs") == 0);
  CHECK(count_field(r.out, "steiner points") == 0);
  for (const char* k : {"conform seconds: ", "field seconds: ", "delaunay seconds: ", "extract seconds: ",
                        "relax seconds: ", "total seconds: "})
    CHECK(r.out.find(k) != std::string::npos);
  CHECK(r.out.find("closed: yes") != std::string::npos);
  // The saved manifold is the prism build of the three layers.
  const dfm::AnimationManifold want = dfm::build_manifold({a.V, b.V, c.V}, a.F, {0, 1, 3});
  const dfm::AnimationManifold got = dfm::read_manifold(s / "m.tet4");
  REQUIRE(got.num_vertices() == want.num_vertices());
  CHECK((got.V - want.V).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(got.T == want.T);
  CHECK(got.times == want.times);
  CHECK(got.slab_offsets == want.slab_offsets);
  CHECK(fs::exists(s / "seq0002.obj"));
  // Issue 38: the slice at 0.5 and every frame of the sequence are the keys' mesh (the vertices in
  // their order, each on its own straight path between the keys around its time, and their triangles).
  const dfm::TriMesh at = dfm::read_surface(s / "slice.obj");
  REQUIRE(at.num_vertices() == a.num_vertices());
  CHECK(at.F == a.F);
  CHECK((at.V - (0.5 * a.V + 0.5 * b.V)).cwiseAbs().maxCoeff() < 1e-12);
  for (int i = 0; i < 3; ++i) {  // frames at t = 0, 1.5, 3
    const dfm::TriMesh f = dfm::read_surface(s / ("seq000" + std::to_string(i) + ".obj"));
    REQUIRE(f.num_vertices() == a.num_vertices());
    CHECK(f.F == a.F);
    const Eigen::MatrixXd expect = i == 0 ? a.V : i == 1 ? Eigen::MatrixXd(0.75 * b.V + 0.25 * c.V) : c.V;
    CHECK((f.V - expect).cwiseAbs().maxCoeff() < 1e-12);
  }
  // The saved manifold keeps its prism layers, so slicing it again gives the same frame.
  const RunResult again = deform(s, {"manifold", "--manifold", s / "m.tet4", "--at", "0.5", "-o", s / "again.obj"});
  INFO(describe_run(again));
  REQUIRE(again.exit_code == 0);
  const dfm::TriMesh at2 = dfm::read_surface(s / "again.obj");
  CHECK(at2.V == at.V);
  CHECK(at2.F == at.F);
}

TEST_CASE("deform manifold: a bad keyframe exits 1 naming the file", "[cli][hostile]") {
  Scratch s;
  dfm::test::write_obj_raw(s / "sphere.obj", sphere());
  dfm::test::write_obj_raw(s / "open.obj", dfm::test::open_copy(torus()));
  dfm::TriMesh nan = torus();
  nan.V(2, 0) = std::nan("");
  dfm::test::write_obj_raw(s / "nan.obj", nan);
  dfm::TriMesh bad = torus();
  bad.F(4, 1) = 9999;
  dfm::test::write_obj_raw(s / "badindex.obj", bad);
  for (const std::string f : {"missing.obj", "open.obj", "nan.obj", "badindex.obj"}) {
    const RunResult r = deform(s, {"manifold", "--keyframes", s / "sphere.obj", s / f, "--at", "0.5", "--stats"});
    INFO(describe_run(r));
    CHECK_FALSE(r.signaled);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("deform manifold: error: ") == 0);
    CHECK(r.err.find(f) != std::string::npos);
  }
}

TEST_CASE("deform manifold: sphere -> torus is a transition whose slice is closed", "[cli][transition]") {
  Scratch s;
  dfm::test::write_obj_raw(s / "sphere.obj", sphere());
  dfm::test::write_obj_raw(s / "torus.obj", torus());
  const RunResult r = deform(s, {"manifold", "--keyframes", s / "sphere.obj", s / "torus.obj", "--at", "0.5", "-o",
                                 s / "mid.obj", "--stats", "--save-manifold", s / "m.tet4"});
  INFO(describe_run(r));
  REQUIRE(r.exit_code == 0);
  CHECK(count_field(r.out, "transition slabs") == 1);
  CHECK(count_field(r.out, "prism slabs") == 0);
  CHECK(r.out.find("closed: yes") != std::string::npos);
  CHECK(dfm::read_manifold(s / "m.tet4").num_tets() > 0);
}

TEST_CASE("deform manifold --inbetween arap: a turning body stays rigid between same-connectivity keyframes; "
          "deform interpolate --symmetric", "[cli]") {
  Scratch s;
  dfm::TriMesh a = dfm::test::icosphere({0, 0, 0}, 1.0, 1);
  a.V.col(0) *= 3.0;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(2 * M_PI / 3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  dfm::TriMesh b = a;
  b.V = a.V * R.transpose();
  dfm::test::write_obj_raw(s / "a.obj", a);
  dfm::test::write_obj_raw(s / "b.obj", b);
  // Three in-betweens: t = 0.5 is a layer, the body turned by 60 degrees about its centre.
  RunResult r = deform(s, {"manifold", "--keyframes", s / "a.obj", s / "b.obj", "--inbetween", "arap", "--inbetweens", "3",
                           "--at", "0.5", "-o", s / "mid.obj", "--stats"});
  INFO(describe_run(r));
  REQUIRE(r.exit_code == 0);
  CHECK(count_field(r.out, "prism slabs") == 4);
  const dfm::TriMesh mid = dfm::read_surface(s / "mid.obj");
  const Eigen::Matrix3d R60 = Eigen::AngleAxisd(M_PI / 3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  // The slice is welded afresh: compare the point sets (each slice vertex near the turned body's vertex).
  const Eigen::MatrixXd expect = a.V * R60.transpose();
  const Eigen::RowVector3d shift = mid.V.colwise().mean() - expect.colwise().mean();
  const Eigen::MatrixXd placed = expect.rowwise() + shift;
  double worst = 0;
  for (int i = 0; i < mid.V.rows(); ++i)
    worst = std::max(worst, std::sqrt((placed.rowwise() - mid.V.row(i)).rowwise().squaredNorm().minCoeff()));
  CHECK(worst < 1e-5);
  // The linear blend of the same keys pulls the body in.
  r = deform(s, {"manifold", "--keyframes", s / "a.obj", s / "b.obj", "--at", "0.5", "-o", s / "lin.obj"});
  REQUIRE(r.exit_code == 0);
  const dfm::TriMesh lin = dfm::read_surface(s / "lin.obj");
  CHECK(lin.V.rowwise().norm().maxCoeff() < 0.8 * mid.V.rowwise().norm().maxCoeff());
  // Usage: handles needs pose keys; a bad method word.
  r = deform(s, {"manifold", "--keyframes", s / "a.obj", s / "b.obj", "--inbetween", "handles", "--at", "0.5", "-o",
                 s / "x.obj"});
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("pose keys") != std::string::npos);
  r = deform(s, {"manifold", "--keyframes", s / "a.obj", s / "b.obj", "--inbetween", "spline", "--at", "0.5", "-o",
                 s / "x.obj"});
  CHECK(r.exit_code == 2);
  // deform interpolate --symmetric: the same rigid turn at exactly t = 0.5.
  r = deform(s, {"interpolate", "--keyframes", s / "a.obj", s / "b.obj", "--symmetric", "--at", "0.5", "-o", s / "sym.obj"});
  INFO(describe_run(r));
  REQUIRE(r.exit_code == 0);
  const dfm::TriMesh sym = dfm::read_surface(s / "sym.obj");
  const Eigen::RowVector3d sym_shift = sym.V.colwise().mean() - expect.colwise().mean();
  CHECK(((sym.V.rowwise() - sym_shift) - expect).cwiseAbs().maxCoeff() < 1e-5);
  r = deform(s, {"interpolate", "--keyframes", s / "a.obj", s / "b.obj", "--method", "linear", "--symmetric", "--at",
                 "0.5", "-o", s / "x.obj"});
  CHECK(r.exit_code == 2);
}

TEST_CASE("deform manifold --pairs: a moved key travels, its picked pair followed; hostile pairs exit 1 naming "
          "the file, line and problem", "[cli][transition][hostile]") {
  Scratch s;
  dfm::test::write_obj_raw(s / "a.obj", sphere());
  dfm::test::write_obj_raw(s / "b.obj", dfm::test::icosphere({3, 0, 0}, 0.6, 2));
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(s / name) << text;
    return s / name;
  };
  const std::string good = write("good.txt", "# tip to tip\n1 0 0   3.6 0 0\n\n0 1 0 3 0.6 0\n");
  RunResult r = deform(s, {"manifold", "--keyframes", s / "a.obj", s / "b.obj", "--pairs", good, "--at", "0.5", "-o",
                           s / "mid.obj", "--stats"});
  INFO(describe_run(r));
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("closed: yes") != std::string::npos);
  const dfm::TriMesh mid = dfm::read_surface(s / "mid.obj");
  const Eigen::RowVector3d c = 0.5 * (mid.V.colwise().minCoeff() + mid.V.colwise().maxCoeff());
  CHECK(std::abs(c.x() - 1.5) < 0.1);  // halfway along the travel
  // Three keys: 'pair 1' sends the lines after it to keys 1 and 2 (b -> c, c turned a quarter).
  dfm::TriMesh ring = dfm::test::torus({0, 0, 0}, 0.5, 0.2, 24, 10);
  ring.V = (ring.V * Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix().transpose()).eval();
  ring.V.col(0).array() += 6;
  dfm::test::write_obj_raw(s / "c.obj", ring);
  const std::string three = write("three.txt", "1 0 0 3.6 0 0\npair 1\n3.6 0 0 6.7 0 0\n");
  r = deform(s, {"manifold", "--keyframes", s / "a.obj", s / "b.obj", s / "c.obj", "--pairs", three, "--at", "1.5",
                 "--stats"});
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("closed: yes") != std::string::npos);
  dfm::test::write_obj_raw(s / "a2.obj", dfm::test::icosphere({2, 0, 0}, 1.0, 1));  // a's triangles: the prism build
  r = deform(s, {"manifold", "--keyframes", s / "a.obj", s / "a2.obj", "--pairs", good, "--at", "0.5", "--stats"});
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("good.txt:2:") != std::string::npos);
  CHECK(r.err.find("transitions only") != std::string::npos);
  struct Bad {
    std::string text, where, problem;
  };
  const std::vector<Bad> bad = {{"1 0 0 3.6 0 0\n0 1 0 nan 0.6 0\n", ":2:", "not a finite number"},
                                {"1 0 0 3.6 0 0\n\n0 1 0 3 0.6\n", ":3:", "expected 6 numbers"},
                                {"1 0 0 3.6 0 0\n0 1.5 0 3 0.6 0\n", ":2:", "from its key"},
                                {"pair 1\n1 0 0 3.6 0 0\n", ":1:", "pair K"}};
  for (size_t i = 0; i < bad.size(); ++i) {
    const std::string f = write("bad" + std::to_string(i) + ".txt", bad[i].text);
    r = deform(s, {"manifold", "--keyframes", s / "a.obj", s / "b.obj", "--pairs", f, "--at", "0.5", "--stats"});
    INFO(describe_run(r));
    CHECK_FALSE(r.signaled);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("bad" + std::to_string(i) + ".txt" + bad[i].where) != std::string::npos);
    CHECK(r.err.find(bad[i].problem) != std::string::npos);
  }
}
