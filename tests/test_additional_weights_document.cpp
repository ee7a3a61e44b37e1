// Additional weights as part of the document's bind (Jacobson 2013, 7.3.3; issue 36): the bind
// option, FAST solving the additional handles, skinning with them against a sum written here, undo,
// the scene file (bit-exact round trip, old scenes, malformed values) and the script command.
#include <cmath>
#include <fstream>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/rig/additional_handles.h"
#include "core/scene/bind_document.h"
#include "core/scene/command.h"
#include "core/scene/document.h"
#include "core/scene/script.h"
#include "core/skin/lbs.h"
#include "core/util/error.h"
#include "tests/capsule_test_mesh.h"
#include "tests/scratch_dir.h"

using namespace dfm;
using Eigen::MatrixXd;
using Eigen::Vector3d;

namespace {

// The cigar of Fig. 7.7 with its two end regions as region handles (0: left, 1: right).
void cigar_document(Document& doc) {
  const double a = 2.0;
  doc.set_surface(test::capsule(a, 0.5, 4, 24, 12), "cigar.obj");
  std::vector<int> left, right;
  for (int i = 0; i < doc.surface().num_vertices(); ++i) {
    if (doc.surface().V(i, 0) < -a + 0.25) left.push_back(i);
    if (doc.surface().V(i, 0) > a - 0.25) right.push_back(i);
  }
  doc.paint_region(doc.add_region("left"), left, false);
  doc.paint_region(doc.add_region("right"), right, false);
}

double diagonal(const MatrixXd& V) { return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm(); }

// sum_j W_ij T_j v_i + sum_e A_ie S_e v_i, with S_e the solved transform of handle nh + e (zero if none).
MatrixXd brute_force_skin(const Document& doc) {
  const MatrixXd& V = doc.surface().V;
  const MatrixXd &W = doc.weights(), &A = doc.additional_weights();
  const Pose T = evaluate_pose(doc.rig(), doc.pose_params());
  const int nh = doc.num_handles();
  MatrixXd U = MatrixXd::Zero(V.rows(), 3);
  for (int i = 0; i < V.rows(); ++i) {
    const Vector3d v = V.row(i).transpose();
    for (int j = 0; j < nh; ++j) U.row(i) += W(i, j) * (T.transforms[j] * v).transpose();
    for (int e = 0; e < A.cols(); ++e) {
      const auto it = doc.pose_params().solved.find(nh + e);
      if (it != doc.pose_params().solved.end()) U.row(i) += A(i, e) * (it->second.matrix().topRows(3) * v.homogeneous()).transpose();
    }
  }
  return U;
}

// Bends the cigar: the right region turned 90 degrees about z with FAST on.
void bend(Document& doc) {
  PosingSettings p = doc.posing();
  p.fast = true;
  p.iterations = 40;
  doc.set_posing(p);
  doc.rotate_handle(1, Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitZ())));
  doc.translate_handle(1, Vector3d(-1.0, 1.5, 0));
}

// The cigar bound with 4 additional weights, bent by FAST and keyed at 0.
void keyed_bent_cigar(Document& doc) {
  cigar_document(doc);
  run_command(doc, {"bind-additional", "4"});
  run_bind_blocking(doc);
  bend(doc);
  doc.set_key(0);
}

}  // namespace

TEST_CASE("a bind with additional weights: originals unchanged, FAST solves the extras, the skin is their sum",
          "[weights][additional]") {
  Document doc;
  cigar_document(doc);
  run_bind_blocking(doc);
  const MatrixXd W0 = doc.weights();
  REQUIRE(doc.num_additional() == 0);
  REQUIRE(doc.bind_settings().additional_weights == 0);

  run_command(doc, {"bind-additional", "6"});
  CHECK(doc.bind_settings().additional_weights == 6);
  CHECK(doc.undo_name() == "bind settings");
  run_bind_blocking(doc);
  REQUIRE(doc.num_additional() == 6);
  const MatrixXd A = doc.additional_weights();
  REQUIRE(A.rows() == doc.surface().num_vertices());
  // The original columns are the same bind, bit for bit, and keep the partition of unity.
  CHECK(doc.weights() == W0);
  CHECK((doc.weights().rowwise().sum().array() - 1).abs().maxCoeff() < 1e-12);
  CHECK(A.minCoeff() >= -1e-9);
  CHECK(A.maxCoeff() <= 1 + 1e-9);
  CHECK(A.maxCoeff() > 0.5);  // each is one at its sample
  // Zero on the handles (7.3.3: the constraints stay trivially feasible).
  for (const Region& r : doc.rig().regions)
    for (int v : r.vertices) CHECK(A.row(v).cwiseAbs().maxCoeff() < 1e-9);

  // At rest, unsolved, the additional handles add nothing (zero transforms).
  const double diag = diagonal(doc.surface().V);
  CHECK((posed_surface(doc).V - doc.surface().V).cwiseAbs().maxCoeff() < 1e-12 * diag);

  bend(doc);
  const int nh = doc.num_handles();
  for (int e = 0; e < 6; ++e) CHECK(doc.pose_params().solved.count(nh + e) == 1);
  const MatrixXd U = posed_surface(doc).V;
  CHECK((U - brute_force_skin(doc)).rowwise().norm().maxCoeff() < 1e-12 * diag);
  // The additional handles moved the surface away from plain LBS of the regions (which pinches).
  const double off_lbs = (U - lbs(doc.surface().V, doc.weights(), doc.pose())).rowwise().norm().maxCoeff();
  WARN("cigar bent with 6 additional weights: max distance from LBS of the two regions " << off_lbs / diag
                                                                                         << " of the diagonal");
  CHECK(off_lbs > 0.01 * diag);
  // Both regions stay where the pose puts them (the additional weights vanish there).
  const Pose T = doc.pose();
  for (int v : doc.rig().regions[1].vertices)
    CHECK((U.row(v).transpose() - T.transforms[1] * Vector3d(doc.surface().V.row(v).transpose())).norm() < 1e-9 * diag);

  // DQS: the dual-quaternion skin of the regions plus the additional handles' linear term.
  doc.set_method(SkinMethod::DQS);
  const SkinBinding rig_only = make_skin_binding(doc.surface().V, MatrixXd(), doc.weights(), doc.rig(), 0);
  const MatrixXd dq = skin(SkinMethod::DQS, rig_only, doc.pose()).V;
  CHECK((posed_surface(doc).V - (dq + brute_force_skin(doc) - lbs(doc.surface().V, doc.weights(), doc.pose())))
            .rowwise()
            .norm()
            .maxCoeff() < 1e-12 * diag);
  doc.set_method(SkinMethod::LBS);

  // Undo: the bend, then the bind with the additional weights; redo brings them back.
  while (doc.can_undo() && doc.undo_name() != "bind") doc.undo();
  REQUIRE(doc.undo_name() == "bind");
  doc.undo();
  CHECK(doc.num_additional() == 0);
  CHECK(doc.weights() == W0);
  doc.redo();
  CHECK(doc.additional_weights() == A);

  // A rig edit clears them with the weights, and the new handle does not take an additional one's transform.
  bend(doc);
  doc.add_point(Vector3d(0, 0, 0), "middle");
  CHECK(doc.additional_weights().size() == 0);
  CHECK(doc.pose_params().solved.count(nh) == 0);
}

TEST_CASE("a rebind that changes the additional weights leaves their transforms unsolved in the pose and keys",
          "[weights][additional]") {
  Document doc;
  keyed_bent_cigar(doc);
  const int nh = doc.num_handles();
  auto extras = [&](const PoseParams& p) {
    int n = 0;
    for (const auto& [h, T] : p.solved) n += h >= nh;
    return n;
  };
  REQUIRE(extras(doc.pose_params()) == 4);
  REQUIRE(extras(doc.keys()[0].params) == 4);
  // The same bind again: the same weight functions, so their solved transforms still apply.
  run_bind_blocking(doc);
  CHECK(extras(doc.pose_params()) == 4);
  CHECK(extras(doc.keys()[0].params) == 4);
  // Other functions: transforms solved for the old ones would skin the new ones wrongly; they go, so
  // the key shows the original bind's skin (zero transforms) until FAST solves again.
  run_command(doc, {"bind-additional", "2"});
  run_bind_blocking(doc);
  REQUIRE(doc.num_additional() == 2);
  CHECK(extras(doc.pose_params()) == 0);
  CHECK(extras(doc.keys()[0].params) == 0);
  CHECK((posed_surface(doc).V - lbs(doc.surface().V, doc.weights(), doc.pose())).cwiseAbs().maxCoeff() < 1e-12);
  // One undo step: the transforms come back with the old weights.
  doc.undo();
  CHECK(doc.num_additional() == 4);
  CHECK(extras(doc.keys()[0].params) == 4);
}

TEST_CASE("additional weights in the scene file: bit-exact round trip, old scenes, malformed values",
          "[weights][additional][scene]") {
  test::ScratchDir dir("additional_weights_scene");
  Document doc;
  keyed_bent_cigar(doc);
  const std::string path = dir / "cigar.scene.json";
  doc.save_scene(path);

  Document back;
  back.load_scene(path);
  CHECK(back.bind_settings().additional_weights == 4);
  CHECK(back.additional_weights() == doc.additional_weights());
  CHECK(back.weights() == doc.weights());
  REQUIRE(back.pose_params().solved.size() == doc.pose_params().solved.size());
  for (const auto& [h, T] : doc.pose_params().solved) CHECK(back.pose_params().solved.at(h).matrix() == T.matrix());
  CHECK(back.keys()[0].params.solved.size() == doc.keys()[0].params.solved.size());
  CHECK(posed_surface(back).V == posed_surface(doc).V);

  auto rewrite = [&](const std::function<void(nlohmann::json&)>& f) {
    std::ifstream in(path);
    nlohmann::json j = nlohmann::json::parse(in);
    f(j);
    const std::string out = dir / "edited.scene.json";
    std::ofstream(out) << j.dump();
    // The sidecar stays the original's (its name is in the JSON).
    return out;
  };
  // A scene from before the option: no setting, no matrix, no additional transforms -> k = 0.
  {
    const std::string old = rewrite([](nlohmann::json& j) {
      j["bind_settings"].erase("additional_weights");
      j.erase("additional_weights");
      j["pose"].erase("solved");
      for (auto& k : j["keys"]) k["params"].erase("solved");
    });
    Document d;
    d.load_scene(old);
    CHECK(d.bind_settings().additional_weights == 0);
    CHECK(d.num_additional() == 0);
    CHECK(d.has_weights());
  }
  // Malformed values: errors naming the file and the field.
  for (const nlohmann::json& bad : {nlohmann::json(-2), nlohmann::json(2.5), nlohmann::json("four"), nlohmann::json(101)}) {
    const std::string p = rewrite([&](nlohmann::json& j) { j["bind_settings"]["additional_weights"] = bad; });
    Document d;
    INFO(bad.dump());
    CHECK_THROWS_WITH(d.load_scene(p), Catch::Contains("edited.scene.json") && Catch::Contains("bind_settings.additional_weights"));
  }
  // A solved transform past the additional handles, and additional weights without the bind's.
  {
    const std::string p = rewrite([&](nlohmann::json& j) { j.erase("additional_weights"); });
    Document d;
    CHECK_THROWS_WITH(d.load_scene(p), Catch::Contains("solved") && Catch::Contains("handle index"));
  }
  {
    const std::string p = rewrite([&](nlohmann::json& j) {
      j["weights"] = j["mask"];  // an empty array
      j["pose"].erase("solved");
      for (auto& k : j["keys"]) k["params"].erase("solved");
    });
    Document d;
    CHECK_THROWS_WITH(d.load_scene(p), Catch::Contains("'additional_weights' without 'weights'"));
  }
}

TEST_CASE("bind-additional: the script's checks", "[weights][additional][script]") {
  Document doc;
  cigar_document(doc);
  for (const char* bad : {"-1", "2.5", "101", "x"}) {
    INFO(bad);
    CHECK_THROWS_AS(run_command(doc, {"bind-additional", bad}), Error);
  }
  CHECK(doc.bind_settings().additional_weights == 0);
  run_command(doc, {"bind-additional", "3"});
  CHECK(doc.bind_settings().additional_weights == 3);
  doc.undo();
  CHECK(doc.bind_settings().additional_weights == 0);
}
