// The script's transfer-weights (issue 34): a bound scene's weights, or a mesh and its weights file,
// carried onto the document's surface (core/bind/weight_transfer.h) as one undo step.
#include <catch2/catch.hpp>

#include <filesystem>

#include <unistd.h>

#include "core/mesh/io.h"
#include "core/scene/script.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;

namespace {

void run(Document& d, const std::string& text) { run_script(d, parse_script(text, "tw.txt"), "tw.txt"); }

// A sphere with two point handles and weights that blend across x.
void make_two_points(Document& d, int level) {
  d.set_surface(test::icosphere(Eigen::Vector3d::Zero(), 1.0, level), "sphere");
  d.add_point(Eigen::Vector3d(-0.5, 0, 0));
  d.add_point(Eigen::Vector3d(0.5, 0, 0));
  const Eigen::MatrixXd& V = d.surface().V;
  Eigen::MatrixXd W(V.rows(), 2);
  for (int i = 0; i < V.rows(); ++i) W.row(i) << 0.5 - 0.5 * V(i, 0), 0.5 + 0.5 * V(i, 0);
  d.set_weights(W, BindStats{});
}

}  // namespace

TEST_CASE("transfer-weights: a bound scene's weights onto the document, one undo step; a mesh needs its weights file") {
  const std::string dir = std::filesystem::temp_directory_path() / ("dfm_tw_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  Document a;
  make_two_points(a, 2);
  a.save_scene(dir + "/a.scene.json");
  write_surface(dir + "/a.obj", a.surface());
  write_dmat(dir + "/a.dmat", a.weights());

  Document b;  // a finer sphere, the same rig
  make_two_points(b, 3);
  const Eigen::MatrixXd before = b.weights();
  const int steps = b.undo_depth();
  run(b, "transfer-weights " + dir + "/a.scene.json\n");
  CHECK(b.undo_depth() == steps + 1);
  CHECK(b.weights().minCoeff() >= 0);
  CHECK((b.weights().rowwise().sum().array() - 1).abs().maxCoeff() < 1e-12);
  CHECK((b.weights() - before).cwiseAbs().maxCoeff() < 0.02);  // linear in x: the finer sphere's own, nearly
  const Eigen::MatrixXd from_scene = b.weights();
  b.undo();
  CHECK(b.weights() == before);
  run(b, "transfer-weights " + dir + "/a.obj " + dir + "/a.dmat\n");
  CHECK((b.weights() - from_scene).cwiseAbs().maxCoeff() < 1e-12);  // the same source, the same result

  CHECK_THROWS_WITH(run(b, "transfer-weights " + dir + "/a.obj\n"), Catch::Contains("tw.txt:1") && Catch::Contains("W.dmat"));
  Document c;  // a rig of another size
  c.set_surface(a.surface(), "sphere");
  c.add_point(Eigen::Vector3d(0, 0, 0));
  CHECK_THROWS_WITH(run(c, "transfer-weights " + dir + "/a.scene.json\n"), Catch::Contains("correspond by number"));
  std::filesystem::remove_all(dir);
}
