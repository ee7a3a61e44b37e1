// glTF export: TRS decomposition, influence pruning, and the export -> import -> skin round trip
// on a synthetic rig with every handle kind (the validator run lives in test_gltf_validator.cpp).
#include <filesystem>
#include <random>

#include <unistd.h>

#include <catch2/catch.hpp>

#include "core/export/export_document.h"
#include "core/export/gltf_export.h"
#include "core/export/gltf_rig_extras.h"
#include "core/export/gltf_import.h"
#include "core/export/gltf_verify.h"
#include "core/export/prune.h"
#include "core/export/trs.h"
#include "core/rig/pose_params.h"
#include "core/scene/document.h"
#include "core/scene/script.h"
#include "core/skin/lbs.h"
#include "core/util/error.h"
#include "tests/test_gltf_fixtures.h"

using namespace dfm;
namespace fs = std::filesystem;

namespace {

fs::path temp_dir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("dfm_test_gltf_" + name + "_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

double max_row_distance(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  REQUIRE(A.rows() == B.rows());
  return (A - B).rowwise().norm().maxCoeff();
}

bool has_note(const GltfExportReport& rep, const std::string& text) {
  for (const auto& n : rep.notes)
    if (n.find(text) != std::string::npos) return true;
  return false;
}

// The file at `path` plays the document's keys at t = 0, 1, 2 as the document shows them (within 1e-5 of
// the diagonal), and at t = 1, 2 LBS of the rig's weights with the key's pose misses that frame by more
// than lbs_miss diagonals (what the file needs beyond joints).
void check_keys_played(Document& doc, const std::string& path, double diag, double lbs_miss) {
  const GltfDocument g = read_gltf(path);
  for (double t : {0.0, 1.0, 2.0}) {
    INFO("t = " << t);
    doc.set_time(t);
    const Eigen::MatrixXd want = posed_surface(doc).V;
    CHECK(max_row_distance(gltf_skinned_positions(g, t), want) < 1e-5 * diag);
    if (t > 0)
      CHECK(max_row_distance(lbs(doc.surface().V, doc.weights(), doc.key_poses()[static_cast<int>(t)]), want) >
            lbs_miss * diag);
  }
}

}  // namespace

TEST_CASE("TRS: compose(decompose(M)) == M for random TRS, including reflections", "[gltf][trs]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 200; ++i) {
    Trs t;
    t.translation = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 10;
    t.rotation = Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized());
    t.scale = Eigen::Vector3d(0.1 + std::abs(u(rng)) * 3, 0.1 + std::abs(u(rng)) * 3, 0.1 + std::abs(u(rng)) * 3);
    if (i % 3 == 0) t.scale.y() = -t.scale.y();  // a reflection
    // Independent construction of the matrix: scale first, then rotate, then translate.
    Eigen::Affine3d M = Eigen::Translation3d(t.translation) * t.rotation * Eigen::Scaling(t.scale);
    const TrsFit fit = decompose_trs(M);
    CHECK(fit.shear < 1e-12);
    CHECK(std::abs(fit.trs.rotation.norm() - 1) < 1e-12);
    CHECK((compose_trs(fit.trs).matrix() - M.matrix()).norm() < 1e-10 * M.matrix().norm());
    CHECK(fit.trs.rotation.toRotationMatrix().determinant() > 0);
  }
}

TEST_CASE("TRS: shear is reported, singular transforms throw", "[gltf][trs]") {
  Eigen::Affine3d M = Eigen::Affine3d::Identity();
  M.linear() << 1, 0.5, 0, 0, 1, 0, 0, 0, 1;
  const TrsFit fit = decompose_trs(M);
  CHECK(fit.shear > 0.1);
  // The residual is what the fit leaves out, measured independently.
  CHECK(std::abs((compose_trs(fit.trs).linear() - M.linear()).norm() / M.linear().norm() - fit.shear) < 1e-12);
  Eigen::Affine3d Z = Eigen::Affine3d::Identity();
  Z.linear()(2, 2) = 0;
  CHECK_THROWS_AS(decompose_trs(Z), Error);
  Eigen::Affine3d Nan = Eigen::Affine3d::Identity();
  Nan.translation().x() = std::nan("");
  CHECK_THROWS_AS(decompose_trs(Nan), Error);
}

TEST_CASE("pruning for export: top k, renormalized, non-negative, never all zero", "[gltf][prune]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.05, 1);
  Eigen::MatrixXd W(300, 11);
  for (int i = 0; i < W.rows(); ++i)
    for (int j = 0; j < W.cols(); ++j) W(i, j) = u(rng);
  W.row(5).setZero();
  W.row(6).setConstant(-0.1);
  W(6, 7) = -0.5;
  for (int k : {1, 4, 8, 11, 16}) {
    const Influences inf = prune_for_export(W, k);
    REQUIRE(inf.k() == k);
    for (int v = 0; v < W.rows(); ++v) {
      CHECK(std::abs(inf.weight.row(v).sum() - 1) < 1e-12);
      CHECK(inf.weight.row(v).minCoeff() >= 0);
      for (int j = 0; j < k; ++j)
        if (inf.weight(v, j) == 0) CHECK(inf.index(v, j) == 0);
    }
    // Reference: brute force, keep the k largest positive weights.
    for (int v : {0, 17, 299}) {
      std::vector<std::pair<double, int>> all;
      for (int j = 0; j < W.cols(); ++j) all.push_back({W(v, j), j});
      std::sort(all.begin(), all.end(), [](auto& a, auto& b) { return a.first > b.first; });
      double sum = 0;
      for (int j = 0; j < std::min<int>(k, W.cols()); ++j) sum += std::max(0.0, all[j].first);
      const Eigen::MatrixXd D = influences_to_dense(inf, W.cols());
      for (int j = 0; j < std::min<int>(k, W.cols()); ++j)
        CHECK(std::abs(D(v, all[j].second) - std::max(0.0, all[j].first) / sum) < 1e-12);
    }
    // All-zero and all-negative rows: weight 1 on the largest-magnitude handle.
    CHECK(inf.weight(5, 0) == 1.0);
    CHECK(inf.weight(6, 0) == 1.0);
    CHECK(inf.index(6, 0) == 7);
  }
  CHECK_THROWS_AS(prune_for_export(W, 0), Error);
}

TEST_CASE("glTF round trip: re-imported skin reproduces LBS at every key (synthetic rig, all handle kinds)",
          "[gltf][roundtrip]") {
  const GltfExportInput in = test::synthetic_input();
  const fs::path dir = temp_dir("roundtrip");
  const int nh = num_handles(in.rig);
  const double diag = (in.surface.V.colwise().maxCoeff() - in.surface.V.colwise().minCoeff()).norm();
  double prune_err[2] = {0, 0};
  for (int ki = 0; ki < 2; ++ki) {
    const int k = ki == 0 ? 4 : 8;
    for (const std::string ext : {"glb", "gltf"}) {
      const std::string path = (dir / ("tube" + std::to_string(k) + "." + ext)).string();
      // Plain pruning here (refit off): the stored weights have an independent reference.
      const GltfExportReport rep = export_gltf(path, in, {k, false});
      CHECK(rep.sheared_transforms == 0);
      CHECK(rep.max_shear < 1e-9);
      CHECK(rep.joints == nh);
      const GltfDocument doc = read_gltf(path);
      if (ext == "gltf") CHECK(fs::exists(dir / ("tube" + std::to_string(k) + ".bin")));
      REQUIRE(doc.joints.size() == static_cast<size_t>(nh));
      REQUIRE(doc.skinned.weights.cols() == k);
      CHECK(max_row_distance(doc.skinned.V, in.surface.V) < 1e-6 * diag);
      CHECK(doc.skinned.F == in.surface.F);
      // Stored influences are the pruned ones.
      const Eigen::MatrixXd Wp = influences_to_dense(prune_for_export(in.weights, k), nh);
      Influences stored;
      stored.index = doc.skinned.joints;
      stored.weight = doc.skinned.weights;
      CHECK((influences_to_dense(stored, nh) - Wp).cwiseAbs().maxCoeff() < 1e-6);
      const std::vector<double> times = doc.key_times();
      REQUIRE(times.size() == in.keys.size());
      double worst_full = 0;
      for (size_t i = 0; i < in.keys.size(); ++i) {
        CHECK(std::abs(times[i] - in.keys[i].time) < 1e-6);
        const Eigen::MatrixXd U = gltf_skinned_positions(doc, times[i]);
        // Same weights as stored: only float rounding separates the two.
        CHECK(max_row_distance(U, lbs(in.surface.V, Wp, in.keys[i].pose)) < 1e-5 * diag);
        worst_full = std::max(worst_full, max_row_distance(U, lbs(in.surface.V, in.weights, in.keys[i].pose)));
      }
      // The current pose is the nodes' default transforms: skin with the animation ignored.
      GltfDocument still = doc;
      still.channels.clear();
      const Eigen::MatrixXd Uc = gltf_skinned_positions(still, 0.0);
      CHECK(max_row_distance(Uc, lbs(in.surface.V, Wp, in.current)) < 1e-5 * diag);
      worst_full = std::max(worst_full, max_row_distance(Uc, lbs(in.surface.V, in.weights, in.current)));
      // The exporter's pruning report matches what the file actually does.
      CHECK(std::abs(worst_full - rep.max_prune_error) < 1e-5 * diag);
      prune_err[ki] = rep.max_prune_error;
    }
  }
  WARN("synthetic tube (10 handles, inverse-distance weights): pruning error / bbox diagonal: k=4 "
       << prune_err[0] / diag << ", k=8 " << prune_err[1] / diag);
  CHECK(prune_err[0] > 0);
  CHECK(prune_err[1] < prune_err[0]);
  fs::remove_all(dir);
}

TEST_CASE("refit of pruned weights: same support, valid weights, lower error over the fitted poses; in the file",
          "[gltf][prune]") {
  const GltfExportInput in = test::synthetic_input();
  const int nh = num_handles(in.rig);
  std::vector<Pose> poses = {in.current};
  for (const auto& k : in.keys) poses.push_back(k.pose);
  auto sq_error = [&](const Influences& inf) {
    double e = 0;
    for (const auto& p : poses)
      e += (lbs(in.surface.V, influences_to_dense(inf, nh), p) - lbs(in.surface.V, in.weights, p)).squaredNorm();
    return e;
  };
  for (int k : {4, 8}) {
    const Influences plain = prune_for_export(in.weights, k);
    Influences fit = plain;
    const int n = refit_influences(fit, in.surface.V, in.weights, poses);
    CHECK(n > 0);
    for (int v = 0; v < fit.num_vertices(); ++v) {
      CHECK(std::abs(fit.weight.row(v).sum() - 1) < 1e-12);
      CHECK(fit.weight.row(v).minCoeff() >= 0);
      for (int j = 0; j < k; ++j)
        if (fit.weight(v, j) > 0) CHECK(plain.weight.row(v).cwiseProduct((plain.index.row(v).array() == fit.index(v, j)).matrix().cast<double>()).sum() > 0);
    }
    CHECK(sq_error(fit) < 0.5 * sq_error(plain));
    // The exported file (refit on by default) skins like the refit weights, and the report says so.
    const fs::path dir = temp_dir("refit");
    const std::string path = (dir / "refit.glb").string();
    const GltfExportReport rep = export_gltf(path, in, {k});
    CHECK(rep.refit_vertices == n);
    const GltfDocument doc = read_gltf(path);
    const Eigen::MatrixXd Wf = influences_to_dense(fit, nh);
    double worst = 0;
    for (size_t i = 0; i < in.keys.size(); ++i) {
      const Eigen::MatrixXd U = gltf_skinned_positions(doc, in.keys[i].time);
      CHECK(max_row_distance(U, lbs(in.surface.V, Wf, in.keys[i].pose)) < 1e-5 * rep.bbox_diagonal);
      worst = std::max(worst, max_row_distance(U, lbs(in.surface.V, in.weights, in.keys[i].pose)));
    }
    CHECK(worst <= rep.max_prune_error + 1e-5 * rep.bbox_diagonal);
    fs::remove_all(dir);
  }
}

TEST_CASE("glTF export: baked frames as morph targets play back exactly at their times", "[gltf][morph]") {
  GltfExportInput in = test::synthetic_input();
  for (size_t i = 0; i < in.keys.size(); ++i) {
    in.morph_frames.push_back(lbs(in.surface.V, in.weights, in.keys[i].pose));
    in.morph_times.push_back(in.keys[i].time);
  }
  const fs::path dir = temp_dir("morph");
  const std::string path = (dir / "morph.glb").string();
  const GltfExportReport rep = export_gltf(path, in, {8});
  CHECK(rep.morph_targets == 3);
  const GltfDocument doc = read_gltf(path);
  REQUIRE(doc.morph_node >= 0);
  REQUIRE(doc.morph.targets.size() == 3);
  const double diag = rep.bbox_diagonal;
  for (size_t i = 0; i < in.keys.size(); ++i)
    CHECK(max_row_distance(gltf_morphed_positions(doc, in.morph_times[i]), in.morph_frames[i]) < 1e-5 * diag);
  // Halfway between two frames glTF blends them linearly.
  const double tm = 0.5 * (in.morph_times[0] + in.morph_times[1]);
  CHECK(max_row_distance(gltf_morphed_positions(doc, tm), 0.5 * (in.morph_frames[0] + in.morph_frames[1])) < 1e-5 * diag);
  fs::remove_all(dir);
}

TEST_CASE("glTF export: shear is reported, bad input throws", "[gltf][errors]") {
  GltfExportInput in = test::synthetic_input();
  in.keys[1].pose = test::synthetic_pose(in.rig, 1.0, /*shear=*/true);
  const fs::path dir = temp_dir("errors");
  const GltfExportReport rep = export_gltf((dir / "shear.glb").string(), in, {4});
  CHECK(rep.sheared_transforms == 1);
  CHECK(rep.max_shear > 0.05);
  REQUIRE(!rep.notes.empty());
  CHECK(rep.notes[0].find("base") != std::string::npos);  // names the region's node

  GltfExportInput bad = test::synthetic_input();
  bad.weights.conservativeResize(Eigen::NoChange, bad.weights.cols() - 1);
  CHECK_THROWS_AS(export_gltf((dir / "a.glb").string(), bad, {4}), Error);
  bad = test::synthetic_input();
  bad.keys[2].time = bad.keys[1].time;
  CHECK_THROWS_AS(export_gltf((dir / "b.glb").string(), bad, {4}), Error);
  bad = test::synthetic_input();
  bad.current.transforms.pop_back();
  CHECK_THROWS_AS(export_gltf((dir / "c.glb").string(), bad, {4}), Error);
  CHECK_THROWS_AS(export_gltf((dir / "d.obj").string(), test::synthetic_input(), {4}), Error);
  CHECK_THROWS_AS(export_gltf((dir / "e.glb").string(), test::synthetic_input(), {5}), Error);
  CHECK_THROWS_AS(export_gltf((dir / "no_such_dir" / "f.glb").string(), test::synthetic_input(), {4}), Error);
  CHECK(!fs::exists(dir / "a.glb"));
  CHECK_THROWS_AS(read_gltf((dir / "missing.glb").string()), Error);
  fs::remove_all(dir);
}

TEST_CASE("residual morph targets: the file reproduces LBS with all weights at every key and the current pose",
          "[gltf][residual]") {
  GltfExportInput in = test::synthetic_input();
  const fs::path dir = temp_dir("residual");
  const double diag = (in.surface.V.colwise().maxCoeff() - in.surface.V.colwise().minCoeff()).norm();
  std::vector<double> times;
  std::vector<Pose> poses;
  for (const auto& k : in.keys) times.push_back(k.time), poses.push_back(k.pose);
  for (int k : {4, 8}) {
    GltfExportOptions o;
    o.influences = k;
    o.refit = false;
    o.residual_morph_tolerance = 1e-6;
    const std::string path = (dir / ("residual" + std::to_string(k) + ".glb")).string();
    const GltfExportReport rep = export_gltf(path, in, o);
    // The current pose is not a key: one target per key plus one for it.
    REQUIRE(rep.residual_targets == static_cast<int>(in.keys.size()) + 1);
    CHECK(rep.max_prune_error > 1e-4 * diag);  // the skin alone is far off: the targets have work to do
    CHECK(!rep.notes.empty());
    const GltfDocument doc = read_gltf(path);
    REQUIRE(doc.skinned.targets.size() == in.keys.size() + 1);
    // Stored weights are the plain pruned ones; the targets do not change the skin.
    const Eigen::MatrixXd Wp = influences_to_dense(prune_for_export(in.weights, k), num_handles(in.rig));
    Influences stored;
    stored.index = doc.skinned.joints;
    stored.weight = doc.skinned.weights;
    CHECK((influences_to_dense(stored, num_handles(in.rig)) - Wp).cwiseAbs().maxCoeff() < 1e-6);
    for (size_t i = 0; i < in.keys.size(); ++i) {
      const std::vector<double> w = gltf_morph_weights(doc, doc.skinned_node, doc.skinned, in.keys[i].time);
      for (size_t t = 0; t < w.size(); ++t) CHECK(w[t] == (t == i ? 1.0 : 0.0));
      CHECK(max_row_distance(gltf_skinned_positions(doc, in.keys[i].time), lbs(in.surface.V, in.weights, in.keys[i].pose)) <
            1e-5 * diag);
    }
    GltfDocument still = doc;
    still.channels.clear();
    CHECK(max_row_distance(gltf_skinned_positions(still, 0.0), lbs(in.surface.V, in.weights, in.current)) < 1e-5 * diag);
    const GltfVerifyResult v = verify_gltf_export(path, in.surface.V, in.weights, in.current, times, poses);
    CHECK(v.max_error < 1e-5 * diag);
    // Between keys the correction blends linearly: half of each neighbour's target.
    const double tm = 0.5 * (in.keys[0].time + in.keys[1].time);
    const std::vector<double> wm = gltf_morph_weights(doc, doc.skinned_node, doc.skinned, tm);
    CHECK(std::abs(wm[0] - 0.5) < 1e-6);
    CHECK(std::abs(wm[1] - 0.5) < 1e-6);
  }
  // Current pose == a key: no extra target; the default morph weights select that key's target.
  in.current = in.keys[1].pose;
  GltfExportOptions o;
  o.residual_morph_tolerance = 1e-6;
  const std::string path = (dir / "residual-key.gltf").string();
  REQUIRE(export_gltf(path, in, o).residual_targets == static_cast<int>(in.keys.size()));
  GltfDocument doc = read_gltf(path);
  doc.channels.clear();
  CHECK(doc.skinned.default_weights == std::vector<double>{0.0, 1.0, 0.0});
  CHECK(max_row_distance(gltf_skinned_positions(doc, 0.0), lbs(in.surface.V, in.weights, in.current)) < 1e-5 * diag);
  // A tolerance above the pruning error: no targets.
  o.residual_morph_tolerance = 1.0;
  const GltfExportReport rep = export_gltf(path, in, o);
  CHECK(rep.residual_targets == 0);
  CHECK(read_gltf(path).skinned.targets.empty());
  fs::remove_all(dir);
}

TEST_CASE("export_document_gltf: File > Export of a bound, posed, keyed document", "[gltf][document]") {
  Document doc;
  doc.set_surface(test::tube(21, 12, 3.0, 0.3), "tube.obj");
  doc.add_point(Eigen::Vector3d(0.5, 0.6, 0.0), "p0");
  doc.add_bone_chain({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(3, 0, 0)});
  const fs::path dir = temp_dir("document");
  const std::string path = (dir / "doc.glb").string();
  // Not bound: a clear error, no file.
  try {
    export_document_gltf(doc, path);
    FAIL("exported an unbound document");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find("no weights") != std::string::npos);
  }
  CHECK(!fs::exists(path));
  doc.set_weights(test::inverse_distance_weights(doc.surface(), doc.rig()), BindStats{});
  REQUIRE(doc.has_weights());
  auto bent = [&](double s) {
    PoseParams p = rest_pose_params(doc.rig());
    for (size_t b = 0; b < p.bone_rotation.size(); ++b)
      p.bone_rotation[b] = test::axis_angle(s * (b % 2 ? 0.4 : -0.6), Eigen::Vector3d(0, 0, 1));
    p.point_translation[0] = Eigen::Vector3d(0, 0.2 * s, 0);
    return p;
  };
  for (int i = 0; i < 3; ++i) {
    doc.set_pose_params(bent(i - 1.0));
    doc.set_key(0.5 * i);
  }
  doc.set_pose_params(bent(0.3));
  GltfExportOptions o;
  o.influences = 8;
  o.residual_morph_tolerance = 1e-4;
  const GltfExportReport rep = export_document_gltf(doc, path, o);
  CHECK(rep.keys == 3);
  CHECK(rep.joints == doc.num_handles());
  CHECK(rep.vertices == doc.surface().num_vertices());
  const GltfDocument g = read_gltf(path);
  CHECK(g.nodes.at(g.skinned_node).name == "tube");  // named after the surface until the scene is saved
  REQUIRE(g.key_times().size() == 3);
  for (int i = 0; i < 3; ++i) CHECK(std::abs(g.key_times()[i] - 0.5 * i) < 1e-6);
  const GltfVerifyResult v =
      verify_gltf_export(path, doc.surface().V, doc.weights(), doc.pose(), doc.key_times(), doc.key_poses());
  CHECK(v.max_error <= 1e-4 * v.bbox_diagonal);
  CHECK(v.current_error <= 1e-4 * v.bbox_diagonal);  // the current pose is the nodes' default transforms
  // The same as exporting the document's input by hand.
  const GltfExportInput in = gltf_input_from_document(doc);
  CHECK(in.keys.size() == 3);
  CHECK(in.weights == doc.weights());
  // glTF plays LBS: a DQS document is exported with a note saying so.
  doc.set_method(SkinMethod::DQS);
  const GltfExportReport dq = export_document_gltf(doc, path, o);
  CHECK(has_note(dq, "LBS"));
  fs::remove_all(dir);
}

TEST_CASE("export_document_gltf: a twisted, stretched STBS document plays its keys as the document shows them",
          "[gltf][document][stbs]") {
  Document doc;
  doc.set_surface(test::tube(21, 12, 3.0, 0.3), "tube.obj");
  doc.add_bone_chain({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1.5, 0, 0), Eigen::Vector3d(3, 0, 0)});
  doc.set_weights(test::inverse_distance_weights(doc.surface(), doc.rig()), BindStats{});
  doc.set_method(SkinMethod::STBS);
  doc.set_key(0);
  doc.set_bone_twist_stretch(0, {M_PI / 2, 1.2});  // spread along the first bone: no LBS skin shows it
  doc.set_key(1);
  doc.set_bone_twist_stretch(1, {-M_PI / 3, 0.8});
  doc.set_key(2);
  const fs::path dir = temp_dir("stbs");
  const std::string path = (dir / "stbs.glb").string();
  GltfExportOptions o;
  o.residual_morph_tolerance = 1e-6;
  const GltfExportReport rep = export_document_gltf(doc, path, o);
  CHECK(rep.residual_targets == 3);  // the current pose is the last key's
  CHECK(has_note(rep, "residual morph targets make its keys"));
  const double diag = rep.bbox_diagonal;
  check_keys_played(doc, path, diag, 0.05);  // the twisted keys: no LBS skin of their poses shows them
  // Without residual targets the pruning error reads against the document's surface.
  const GltfExportReport plain = export_document_gltf(doc, path, GltfExportOptions{});
  CHECK(plain.residual_targets == 0);
  CHECK(plain.max_prune_error > 0.05 * diag);
  fs::remove_all(dir);
}

// Additional weights (Jacobson 2013, 7.3.3) are baked (export_document.h): the file's joints are the
// rig's, and the residual morph targets carry what the additional handles FAST solved add.
TEST_CASE("export_document_gltf: a document with additional weights plays its keys as the document shows them",
          "[gltf][document][additional]") {
  Document doc;
  doc.set_surface(test::tube(21, 12, 3.0, 0.3), "tube.obj");
  doc.add_bone_chain({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1.5, 0, 0), Eigen::Vector3d(3, 0, 0)});
  const Eigen::MatrixXd& V = doc.surface().V;
  Eigen::MatrixXd A(V.rows(), 3);  // bumps along the tube, as a bind's additional weights would be
  for (int e = 0; e < 3; ++e)
    for (int i = 0; i < V.rows(); ++i) A(i, e) = std::exp(-std::pow((V(i, 0) - 0.75 * (e + 1)) / 0.4, 2));
  doc.set_weights(test::inverse_distance_weights(doc.surface(), doc.rig()), BindStats{}, {}, A);
  REQUIRE(doc.num_additional() == 3);
  PosingSettings p = doc.posing();
  p.fast = true;
  p.iterations = 30;
  doc.set_posing(p);
  doc.set_key(0);
  for (int k = 1; k <= 2; ++k) {
    doc.rotate_handle(1, Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d(0, 0, 1))));
    REQUIRE(doc.pose_params().solved.count(doc.num_handles()) == 1);  // FAST solved the additional handles
    doc.set_key(k);
  }
  const fs::path dir = temp_dir("additional");
  const std::string path = (dir / "additional.glb").string();
  GltfExportOptions o;
  o.residual_morph_tolerance = 1e-6;
  const GltfExportReport rep = export_document_gltf(doc, path, o);
  CHECK(rep.joints == doc.num_handles());  // baked: no joint for an additional handle
  CHECK(rep.residual_targets >= 2);
  CHECK(has_note(rep, "3 additional weights baked"));
  // The additional handles' share: LBS of the rig's weights alone misses it.
  check_keys_played(doc, path, rep.bbox_diagonal, 1e-3);
  fs::remove_all(dir);
}

TEST_CASE("rig extras: every kind of handle through the glTF rig node's JSON text and back", "[gltf]") {
  Rig rig;
  rig.points = {{Eigen::Vector3d(0.1, 0.2, 0.3), "l_ear"}, {Eigen::Vector3d(-0.1, 0.2, 0.3), "r_ear"}};
  rig.pseudo_edges = {{0, 1}};
  rig.skeleton.joints.resize(4, 3);
  rig.skeleton.joints << 0, 0, 0, 0, 1, 0, 0, 2, 0, 1, 1, 0;
  rig.skeleton.bones = {{0, 1, -1, "spine"}, {1, 2, -1, "neck"}, {1, 3, -1, "arm"}};
  compute_bone_parents(rig.skeleton);
  Cage cage;
  cage.name = "box";
  cage.mesh.V = Eigen::MatrixXd::Random(4, 3);
  cage.mesh.F.resize(4, 3);
  cage.mesh.F << 0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2;
  cage.edges.resize(1, 2);
  cage.edges << 0, 3;
  rig.cages = {cage};
  rig.regions = {{{4, 5, 9}, "belly"}};
  const Rig back = rig_from_extras_json(rig_extras_json(rig), 10, "x.glb");
  REQUIRE(back.points.size() == 2);
  CHECK(back.points[1].name == "r_ear");
  CHECK(back.points[1].position == rig.points[1].position);  // doubles printed round-trip exactly
  CHECK(back.pseudo_edges == rig.pseudo_edges);
  CHECK(back.skeleton.joints == rig.skeleton.joints);
  REQUIRE(back.skeleton.num_bones() == 3);
  for (int b = 0; b < 3; ++b) {
    CHECK(back.skeleton.bones[b].name == rig.skeleton.bones[b].name);
    CHECK(back.skeleton.bones[b].a == rig.skeleton.bones[b].a);
    CHECK(back.skeleton.bones[b].b == rig.skeleton.bones[b].b);
    CHECK(back.skeleton.bones[b].parent == rig.skeleton.bones[b].parent);
  }
  REQUIRE(back.cages.size() == 1);
  CHECK(back.cages[0].mesh.V == cage.mesh.V);
  CHECK(back.cages[0].mesh.F == cage.mesh.F);
  CHECK(back.cages[0].edges == cage.edges);
  REQUIRE(back.regions.size() == 1);
  CHECK(back.regions[0].vertices == rig.regions[0].vertices);
  CHECK(num_handles(back) == num_handles(rig));
  // Text that is not such a rig is refused, naming the file.
  CHECK_THROWS_WITH(rig_from_extras_json("{", 10, "x.glb"), Catch::Contains("x.glb") && Catch::Contains("not JSON"));
  CHECK_THROWS_WITH(rig_from_extras_json(rig_extras_json(rig), 9, "x.glb"), Catch::Contains("region"));
  std::string bad = rig_extras_json(rig);
  bad.replace(bad.find("\"a\":1"), 5, "\"a\":7");
  CHECK_THROWS_WITH(rig_from_extras_json(bad, 10, "x.glb"), Catch::Contains("out of range"));
}
