// The script's `shape-space-key` (what the editor's Shape space panel does): bases are the document's
// keys, the synthesized shape is keyed with Document::key_mesh (one undo step). Checked against the
// affine combination of the key meshes written here (Alexa 2002, Eq. 5.36) and, at e_i, the key itself.
#include <catch2/catch.hpp>

#include "core/scene/command.h"
#include "core/scene/script.h"
#include "core/scene/shape_space_keys.h"
#include "core/util/error.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;

namespace {

// A document whose surface is an icosphere, with three mesh keys of its triangles (ellipsoids: their
// blends stay closed and free of self-intersections) at t = 0, 1, 2.
void three_mesh_keys(Document& doc, std::vector<TriMesh>& keys) {
  const TriMesh s = test::icosphere(Eigen::Vector3d::Zero(), 1.0, 1);
  doc.set_surface(s, "sphere");
  keys.assign(3, s);
  keys[1].V.col(0) *= 1.6;
  keys[2].V.col(1) *= 0.7;
  keys[2].V.col(2) = keys[2].V.col(2).array() * 1.3 + 0.4;
  for (int i = 0; i < 3; ++i) doc.key_mesh(keys[i], "k" + std::to_string(i) + ".obj", i);
}

void run(Document& doc, const std::string& text) { run_script(doc, parse_script(text, "s.txt"), "s.txt"); }

}  // namespace

TEST_CASE("shape-space-key keys the synthesized shape: the affine combination, each key exactly at e_i", "[script][shape_space]") {
  Document doc;
  std::vector<TriMesh> k;
  three_mesh_keys(doc, k);
  run(doc, "shape-space-key linear 0 1 2 0.2 0.5 0.3 3\n");
  REQUIRE(doc.keys().size() == 4);
  const SceneKey& made = doc.keys()[3];
  CHECK(made.time == 3.0);
  REQUIRE(made.mesh.F.rows() == k[0].F.rows());
  CHECK(made.mesh.F == k[0].F);
  REQUIRE(made.mesh.V.rows() == k[0].V.rows());
  CHECK((made.mesh.V - (0.2 * k[0].V + 0.5 * k[1].V + 0.3 * k[2].V)).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(made.mesh_path == "shape space linear 0.2 0.5 0.3");
  doc.undo();
  CHECK(doc.keys().size() == 3);

  // The bases in another order, ARAP, at the current time; e_i gives that key bit for bit.
  doc.set_time(4);
  run(doc, "shape-space-key arap 2 0 1 0 0 1\n");
  REQUIRE(doc.key_at(4) == 3);
  CHECK(doc.keys()[3].mesh.V == k[1].V);
  run(doc, "shape-space-key arap 2 0 1 0.5 0.25 0.25 5\n");
  const Eigen::MatrixXd& V = doc.keys()[doc.key_at(5)].mesh.V;
  CHECK(V.allFinite());
  CHECK((V - k[0].V).norm() > 0.1);
}

TEST_CASE("shape-space-key errors: parse problems and bad keys name the line and the cause", "[script][shape_space]") {
  CHECK_THROWS_WITH(parse_script("shape-space-key cubic 0 1 0.5 0.5\n", "s.txt"), Catch::Contains("linear or arap"));
  CHECK_THROWS_WITH(parse_script("shape-space-key linear 0 1 0.5 x\n", "s.txt"), Catch::Contains("'x' is not a finite number"));
  CHECK_THROWS_WITH(parse_script("shape-space-key linear 0 1 0.5\n", "s.txt"), Catch::Contains("takes 5.."));
  Document doc;
  std::vector<TriMesh> k;
  three_mesh_keys(doc, k);
  CHECK_THROWS_WITH(run(doc, "shape-space-key linear 0 7 0.5 0.5\n"), Catch::Contains("s.txt:1:") && Catch::Contains("no key at time 7"));
  CHECK_THROWS_WITH(run(doc, "shape-space-key linear 0 0 0.5 0.5\n"), Catch::Contains("listed twice"));
  CHECK_THROWS_WITH(run(doc, "shape-space-key linear 0 1 0.5 0.6\n"), Catch::Contains("sum to 1.1"));
  CHECK(doc.keys().size() == 3);
  // A mesh key of another connectivity is named.
  doc.key_mesh(test::icosphere(Eigen::Vector3d::Zero(), 1.0, 2), "fine.obj", 6);
  CHECK_THROWS_WITH(run(doc, "shape-space-key linear 0 6 0.5 0.5\n"), Catch::Contains("fine.obj"));
}

TEST_CASE("shape-space-key keys the host's ready shape (the editor's cursor) as is, else synthesizes", "[script][shape_space]") {
  Document doc;
  std::vector<TriMesh> k;
  three_mesh_keys(doc, k);
  std::vector<double> seen_times;
  Eigen::VectorXd seen_x;
  Eigen::MatrixXd ready = k[0].V.array() + 7.0;  // no blend of the keys: only the host's shape
  ScriptHost host;
  host.synthesized_shape = [&](const std::vector<double>& times, ShapeMorph morph, const Eigen::VectorXd& x) {
    seen_times = times;
    seen_x = x;
    return morph == ShapeMorph::Arap ? ready : Eigen::MatrixXd();
  };
  // The UI passes the coordinates to the last bit (CommandArg): the host sees them exactly.
  const double w1 = 1.0 / 3.0;
  run_command(doc, command_words("shape-space-key", {"arap", 0.0, 1.0, 2.0, 0.25, w1, 1.0 - 0.25 - w1, 3.0}), host);
  REQUIRE(doc.key_at(3) >= 0);
  CHECK(doc.keys()[doc.key_at(3)].mesh.V == ready);
  CHECK(seen_times == std::vector<double>{0, 1, 2});
  REQUIRE(seen_x.size() == 3);
  CHECK(seen_x(1) == w1);

  // No ready shape (linear here; or one of the wrong size): the command synthesizes it.
  run_script(doc, parse_script("shape-space-key linear 0 1 2 0.2 0.5 0.3 4\n", "s.txt"), "s.txt", host);
  const Eigen::MatrixXd& V = doc.keys()[doc.key_at(4)].mesh.V;
  CHECK((V - (0.2 * k[0].V + 0.5 * k[1].V + 0.3 * k[2].V)).cwiseAbs().maxCoeff() < 1e-12);
  ready.resize(5, 3);
  run_command(doc, command_words("shape-space-key", {"arap", 0.0, 1.0, 2.0, 0.0, 1.0, 0.0, 5.0}), host);
  CHECK(doc.keys()[doc.key_at(5)].mesh.V == k[1].V);
}
