// The weight tools as Document commands (one undo step each, exact undo/redo, the bind's constrained
// rows kept, refused without weights) and as script commands (the same results, bit for bit).
#include <catch2/catch.hpp>

#include "core/scene/document.h"
#include "core/scene/script.h"
#include "core/util/error.h"
#include "tests/weight_tools_test_meshes.h"

using namespace dfm;
using namespace dfm::test;

namespace {

// The strip with its five point handles and a region (handle 5) on two vertices at the right end,
// weights as a bind would leave them: 1 at each handle's vertices.
void make_strip_document(Document& d, double asymmetry = 0.5) {
  const TriMesh m = mirror_strip();
  d.set_surface(m, "strip");
  const Rig r = strip_rig();
  for (const PointHandle& p : r.points) d.add_point(p.position, p.name);
  d.add_region("tip");
  d.paint_region(0, {strip_vertex(20, 0), strip_vertex(20, 1)}, false);
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(m.num_vertices(), 6);
  W.leftCols(5) = strip_weights(m, r, asymmetry);
  for (int v : {strip_vertex(20, 0), strip_vertex(20, 1)}) W.row(v) = Eigen::RowVectorXd::Unit(6, 5);
  d.set_weights(W, {});
}

// Runs `edit`, then checks it made one undo step called `name` that undo and redo replay exactly.
void check_one_step(Document& d, const std::string& name, const std::function<void()>& edit) {
  const Eigen::MatrixXd before = d.weights();
  const int depth = d.undo_depth();
  edit();
  const Eigen::MatrixXd after = d.weights();
  REQUIRE(d.undo_depth() == depth + 1);
  CHECK(d.undo_name() == name);
  CHECK(after != before);
  d.undo();
  CHECK(d.weights() == before);
  d.redo();
  CHECK(d.weights() == after);
  // The handles' own rows (points and the region) are the bind's: never changed.
  for (int h = 0; h < 5; ++h) CHECK(after.row(strip_handle_vertex(h)) == before.row(strip_handle_vertex(h)));
  for (int v : {strip_vertex(20, 0), strip_vertex(20, 1)}) CHECK(after.row(v) == Eigen::RowVectorXd::Unit(6, 5));
  CHECK((after.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-12);
  CHECK(after.minCoeff() >= 0);
}

}  // namespace

TEST_CASE("weight tools are undoable document commands that keep the handles' rows") {
  Document d;
  make_strip_document(d);
  check_one_step(d, "limit weights to 2", [&] {
    const LimitReport r = d.weights_limit({2, 1.0});
    CHECK(r.rows_limited > 50);
  });
  for (int i = 0; i < d.weights().rows(); ++i) CHECK((d.weights().row(i).array() != 0).count() <= 2);
  const Eigen::MatrixXd limited = d.weights();
  check_one_step(d, "smooth weights", [&] { d.weights_smooth({3, 0.5, false}, {1}); });
  CHECK(d.weights().col(1) == limited.col(1));  // locked
  check_one_step(d, "mirror weights", [&] {
    MirrorOptions o;
    o.mode = MirrorMode::Flip;
    const MirrorReport r = d.weights_mirror(o);
    CHECK(r.handle_mirror == std::vector<int>{4, 3, 2, 1, 0, 5});
    CHECK(r.unmatched_handles == std::vector<int>{5});  // the region at the right end has no mirror
  });
  // Halve a column off the handles: normalize with two others locked brings the rows back to 1.
  Eigen::MatrixXd W = d.weights();
  W.col(0) *= 0.5;
  W(strip_handle_vertex(0), 0) = 1;
  d.set_weights(W, {});
  check_one_step(d, "normalize weights", [&] {
    const NormalizeReport r = d.weights_normalize({2, 3});
    CHECK(r.rows_scaled > 0);
  });
  CHECK(d.weights().col(2) == W.col(2));
  CHECK(d.weights().col(3) == W.col(3));
  // A tool that changes nothing makes no step.
  const int depth = d.undo_depth();
  d.weights_limit({6, 1.0});
  CHECK(d.undo_depth() == depth);
}

TEST_CASE("the weight tools need weights and check their arguments") {
  Document d;
  d.set_surface(mirror_strip(), "strip");
  d.add_point({0, 0.3, 0});
  CHECK_THROWS_WITH(d.weights_limit({4, 1.0}), Catch::Contains("needs weights") && Catch::Contains("bind"));
  CHECK_THROWS_WITH(d.weights_normalize({}), Catch::Contains("needs weights"));
  CHECK_THROWS_WITH(d.weights_smooth({}, {}), Catch::Contains("needs weights"));
  CHECK_THROWS_WITH(d.weights_mirror({}), Catch::Contains("needs weights"));
  CHECK(d.weights_report().empty());
  d.clear();
  make_strip_document(d);
  const int depth = d.undo_depth();
  const Eigen::MatrixXd W = d.weights();
  CHECK_THROWS(d.weights_limit({0, 1.0}));
  CHECK_THROWS(d.weights_normalize({6}));
  CHECK_THROWS(d.weights_smooth({1, 2.0, false}, {}));
  MirrorOptions bad;
  bad.normal.setZero();
  CHECK_THROWS(d.weights_mirror(bad));
  CHECK(d.undo_depth() == depth);
  CHECK(d.weights() == W);
}

TEST_CASE("the zero-weight report names the handles without influence") {
  Document d;
  make_strip_document(d);
  Eigen::MatrixXd W = d.weights();
  W.col(4) *= 1e-5;
  W.col(0) += W.col(4) * (1e5 - 1);  // rows still sum to 1
  d.set_weights(W, {});
  const auto r = d.weights_report(1e-3);
  REQUIRE(r.size() == 1);
  CHECK(r[0].handle == 4);
  CHECK(r[0].name == "l_outer");
  CHECK(r[0].max_weight == Approx(1e-5));
}

TEST_CASE("weights-* script commands reproduce the document commands exactly") {
  Document by_script, by_hand;
  make_strip_document(by_script);
  make_strip_document(by_hand);
  std::vector<std::string> printed;
  ScriptHost host;
  host.print = [&](const std::string& line) { printed.push_back(line); };
  run_script(by_script,
             parse_script("weights-limit 3 2\n"
                          "weights-smooth 2 0.25 cotan 1 3\n"
                          "weights-mirror x 0 flip\n"
                          "weights-mirror x 0.05 - 0.02\n"
                          "weights-normalize 0 4\n"
                          "weights-smooth\n"
                          "weights-report 0.5\n",
                          "s.txt"),
             "s.txt", host);
  by_hand.weights_limit({3, 2.0});
  by_hand.weights_smooth({2, 0.25, true}, {1, 3});
  MirrorOptions flip;
  flip.mode = MirrorMode::Flip;
  by_hand.weights_mirror(flip);
  MirrorOptions neg;
  neg.offset = 0.05;
  neg.mode = MirrorMode::NegativeToPositive;
  neg.tolerance = 0.02;
  by_hand.weights_mirror(neg);
  by_hand.weights_normalize({0, 4});
  by_hand.weights_smooth({}, {});
  CHECK(by_script.weights() == by_hand.weights());
  CHECK(by_script.undo_depth() == by_hand.undo_depth());
  REQUIRE(printed.size() == 7);
  CHECK(printed[0].find("weights-limit: ") == 0);
  // The report: every handle's largest weight is 1 at its own vertex, so none is below 0.5.
  CHECK(printed[6] == "weights-report: 0 of 6 handles have no weight of 0.5 or more");
  Eigen::MatrixXd W = by_hand.weights();
  W.col(4) *= 1e-4;
  W.col(0) += W.col(4) * (1e4 - 1);
  by_script.set_weights(W, {});
  printed.clear();
  run_script(by_script, parse_script("weights-report\n", "s.txt"), "s.txt", host);
  REQUIRE(printed.size() == 1);
  CHECK(printed[0] == "weights-report: 1 of 6 handles have no weight of 0.001 or more\n  handle 4 l_outer: max 0.0001");
}

TEST_CASE("weights-* arguments are checked before the script runs") {
  auto error_of = [](const std::string& text) {
    try {
      parse_script(text, "s.txt");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK_THAT(error_of("weights-limit 0\n"), Catch::StartsWith("s.txt:1:") && Catch::Contains("influence count"));
  CHECK_THAT(error_of("weights-limit 2.5\n"), Catch::Contains("integer"));
  CHECK_THAT(error_of("weights-limit 4 -1\n"), Catch::Contains("radius"));
  CHECK_THAT(error_of("weights-normalize 1 2.5\n"), Catch::Contains("handle '2.5' must be an integer"));  // a name waits for the run
  CHECK_THAT(error_of("weights-smooth 3 1.5\n"), Catch::Contains("factor"));
  CHECK_THAT(error_of("weights-smooth 3 0.5 gauss\n"), Catch::Contains("uniform or cotan"));
  CHECK_THAT(error_of("weights-smooth 3 0.5 uniform -2\n"), Catch::Contains("handle"));
  CHECK_THAT(error_of("\nweights-mirror w\n"), Catch::StartsWith("s.txt:2:") && Catch::Contains("x, y or z"));
  CHECK_THAT(error_of("weights-mirror x 0 sideways\n"), Catch::Contains("+, - or flip"));
  CHECK_THAT(error_of("weights-mirror x 0 + 1 2\n"), Catch::Contains("takes 1..4"));
  CHECK_THAT(error_of("weights-report nan\n"), Catch::Contains("not a finite number"));
  CHECK(error_of("weights-limit 4\nweights-normalize\nweights-smooth 2\nweights-mirror z\nweights-report\n").empty());
  Document d;
  d.set_surface(mirror_strip(), "strip");
  d.add_point({0, 0.3, 0});
  CHECK_THROWS_WITH(run_script(d, parse_script("weights-limit 4\n", "s.txt"), "s.txt"),
                    Catch::StartsWith("s.txt:1: weights-limit:") && Catch::Contains("needs weights"));
  CHECK_THROWS_WITH(run_script(d, parse_script("weights-report\n", "s.txt"), "s.txt"), Catch::Contains("needs weights"));
}
