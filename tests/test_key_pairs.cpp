// Picked pairs in the document (issue 30): the key-pair command checks each point against its key and
// is one undo step, the scene file keeps the pairs, and the editor's Pair tool makes the same command
// from two clicks.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "app/editor/pair_tool.h"
#include "core/scene/key_pairs.h"
#include "core/scene/scene_file.h"
#include "core/scene/script.h"
#include "core/util/error.h"
#include "tests/transition_test_meshes.h"

using namespace dfm;

namespace {

// A sphere keyed at 0 and a torus at 1 (different connectivity: a transition).
void key_sphere_to_torus(Document& d) {
  d.key_mesh(dfm::test::icosphere(Eigen::Vector3d::Zero(), 0.45, 2), "sphere.obj", 0);
  d.key_mesh(dfm::test::torus(Eigen::Vector3d::Zero(), 0.32, 0.12, 24, 12), "torus.obj", 1);
}

void run(Document& d, const std::string& text) { run_script(d, parse_script(text, "s.txt"), "s.txt"); }

}  // namespace

TEST_CASE("key-pair: each point on its key, one undo step; far points and one connectivity refused") {
  Document d;
  key_sphere_to_torus(d);
  // (0.45, 0, 0) is a vertex of the sphere, (0.44, 0, 0) the torus's outer equator.
  run(d, "key-pair 0.45 0 0 0.44 0 0 0\n");
  REQUIRE(d.keys()[0].pairs_to_next.rows() == 1);
  CHECK(d.keys()[0].pairs_to_next.row(0).isApprox((Eigen::Matrix<double, 1, 6>() << 0.45, 0, 0, 0.44, 0, 0).finished()));
  run(d, "set-time 0.5\nkey-pair 0 0.45 0 0 0.44 0\n");  // the interval holding the current time
  CHECK(d.keys()[0].pairs_to_next.rows() == 2);
  d.undo();
  CHECK(d.keys()[0].pairs_to_next.rows() == 1);
  // 0.2 off the sphere (its diagonal is 1.56: 2% is 0.031).
  CHECK_THROWS_WITH(run(d, "key-pair 0.65 0 0 0.44 0 0\n"),
                    Catch::Contains("s.txt:1") && Catch::Contains("picked pair 2") && Catch::Contains("first point"));
  CHECK_THROWS_WITH(run(d, "key-pair 0.45 0 0 0.44 0 nan\n"), Catch::Contains("s.txt:1"));
  CHECK(d.keys()[0].pairs_to_next.rows() == 1);
  run(d, "clear-pairs 0\n");
  CHECK(d.keys()[0].pairs_to_next.rows() == 0);

  Document same;
  same.key_mesh(dfm::test::icosphere(Eigen::Vector3d::Zero(), 0.45, 2), "a.obj", 0);
  same.key_mesh(dfm::test::icosphere(Eigen::Vector3d(0.1, 0, 0), 0.45, 2), "b.obj", 1);
  CHECK_THROWS_WITH(run(same, "key-pair 0.45 0 0 0.55 0 0 0\n"), Catch::Contains("one connectivity"));
  Document one;
  one.key_mesh(dfm::test::icosphere(Eigen::Vector3d::Zero(), 0.45, 2), "a.obj", 0);
  CHECK_THROWS_WITH(run(one, "key-pair 0.45 0 0 0.45 0 0\n"), Catch::Contains("two keys"));
}

TEST_CASE("key pairs: the scene file keeps them; a pair on the last key is refused by name") {
  Document d;
  key_sphere_to_torus(d);
  run(d, "key-pair 0.45 0 0 0.44 0 0 0\nkey-pair 0 0.45 0 0 0.44 0 0\n");
  const std::string path = (std::filesystem::temp_directory_path() / ("dfm_pairs_" + std::to_string(::getpid()) + ".scene.json")).string();
  write_scene(path, d.data());
  const SceneData back = read_scene(path);
  REQUIRE(back.keys.size() == 2);
  CHECK(back.keys[0].pairs_to_next == d.keys()[0].pairs_to_next);  // bit for bit
  CHECK(back.keys[1].pairs_to_next.rows() == 0);
  // Hand-edited: pairs on the last key.
  nlohmann::json j;
  {
    std::ifstream in(path);
    in >> j;
  }
  j["keys"][1]["pairs"] = nlohmann::json::array({nlohmann::json::array({0, 0, 0, 1, 1, 1})});
  {
    std::ofstream out(path);
    out << j.dump();
  }
  CHECK_THROWS_WITH(read_scene(path), Catch::Contains(path) && Catch::Contains("keys[1].pairs"));
  std::filesystem::remove(path);
  std::filesystem::remove(scene_sidecar_path(path));
}

TEST_CASE("Pair tool: a click on a key, the next key, a click there: the key-pair command") {
  Document d;
  key_sphere_to_torus(d);
  editor::PairTool tool;
  d.set_time(0.5);  // not on a key: nothing starts
  CHECK(tool.click(d, Eigen::Vector3d(0.45, 0, 0)).command.empty());
  CHECK(!tool.first());
  d.set_time(0);
  CHECK(tool.click(d, std::nullopt).status.find("surface") != std::string::npos);  // missed the surface
  const editor::PairTool::Step a = tool.click(d, Eigen::Vector3d(0.45, 0, 0));
  CHECK(a.command.empty());
  REQUIRE(a.go_to);
  CHECK(*a.go_to == 1.0);
  d.set_time(*a.go_to);
  const editor::PairTool::Step b = tool.click(d, Eigen::Vector3d(0.44, 0, 0));
  REQUIRE(b.command.size() == 8);
  CHECK(b.command[0] == "key-pair");
  CHECK(!tool.first());
  run_script(d, {{1, b.command}}, "pair tool");
  REQUIRE(d.keys()[0].pairs_to_next.rows() == 1);
  CHECK(d.keys()[0].pairs_to_next(0, 0) == 0.45);  // %.17g words: the click's coordinates exactly
  CHECK(d.keys()[0].pairs_to_next(0, 3) == 0.44);
}
