// The script's transfer-weights (issue 34): a bound scene's weights, or a mesh and its weights file,
// carried onto the document's surface (core/bind/weight_transfer.h) as one undo step.
#include <catch2/catch.hpp>

#include <filesystem>
#include <map>

#include <unistd.h>

#include "core/bind/weight_transfer.h"
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

namespace {

// p' = sum_j w_j (A_j p + t_j), written out.
Eigen::MatrixXd blend(const Eigen::MatrixXd& V, const Eigen::MatrixXd& W, const std::vector<Eigen::Affine3d>& T) {
  Eigen::MatrixXd U = Eigen::MatrixXd::Zero(V.rows(), 3);
  for (int i = 0; i < V.rows(); ++i)
    for (int j = 0; j < W.cols(); ++j) U.row(i) += W(i, j) * (T[j] * Eigen::Vector3d(V.row(i).transpose())).transpose();
  return U;
}

}  // namespace

TEST_CASE("transfer-weights onto a shirt cut from the teddy: rows a partition of unity; posed, it follows the posed body",
          "[transfer]") {
  Document teddy;
  teddy.load_scene(std::string(DFM_SOURCE_DIR) + "/assets/default.scene.json");
  if (!teddy.has_weights()) run(teddy, "bind\n");
  REQUIRE(teddy.has_weights());
  const TriMesh& body = teddy.surface();
  const Eigen::MatrixXd& W = teddy.weights();
  const double diag = (body.V.colwise().maxCoeff() - body.V.colwise().minCoeff()).norm(), offset = 0.02 * diag;
  const Eigen::MatrixXd BN = test::area_weighted_normals(body.V, body.F);
  // The torso's faces, each split into four at its edge midpoints (the shirt's own triangulation),
  // every vertex pushed out along the body's normal there by 2% of the diagonal. Per shirt vertex its
  // body edge (a, b): a midpoint, or a == b for a body vertex.
  std::map<std::pair<int, int>, int> at;
  std::vector<std::pair<int, int>> from;
  auto vertex = [&](int a, int b) {
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    const auto [it, fresh] = at.emplace(key, static_cast<int>(from.size()));
    if (fresh) from.push_back(key);
    return it->second;
  };
  std::vector<Eigen::RowVector3i> faces;
  for (int f = 0; f < body.F.rows(); ++f) {
    const Eigen::RowVector3d c = (body.V.row(body.F(f, 0)) + body.V.row(body.F(f, 1)) + body.V.row(body.F(f, 2))) / 3;
    if (std::abs(c.x()) > 0.42 || c.y() < -0.45 || c.y() > 0.4) continue;
    const int a = body.F(f, 0), b = body.F(f, 1), cc = body.F(f, 2);
    const int A = vertex(a, a), B = vertex(b, b), C = vertex(cc, cc), ab = vertex(a, b), bc = vertex(b, cc), ca = vertex(cc, a);
    faces.push_back({A, ab, ca}), faces.push_back({ab, B, bc}), faces.push_back({ca, bc, C}), faces.push_back({ab, bc, ca});
  }
  TriMesh shirt;
  shirt.F.resize(static_cast<int>(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f) shirt.F.row(static_cast<int>(f)) = faces[f];
  auto offset_surface = [&](const Eigen::MatrixXd& V, const Eigen::MatrixXd& N) {
    Eigen::MatrixXd S(from.size(), 3);
    for (size_t i = 0; i < from.size(); ++i) {
      const auto [a, b] = from[i];
      const Eigen::RowVector3d n = (N.row(a) + N.row(b)).normalized();
      S.row(static_cast<int>(i)) = 0.5 * (V.row(a) + V.row(b)) + offset * n;
    }
    return S;
  };
  shirt.V = offset_surface(body.V, BN);
  REQUIRE(shirt.V.rows() > 1000);

  WeightTransferReport r;
  const Eigen::MatrixXd T = transfer_weights(body.V, body.F, W, shirt.V, shirt.F, {}, &r);
  CHECK(T.minCoeff() >= 0);
  CHECK(T.maxCoeff() <= 1);
  CHECK((T.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-12);

  // A pose: the spine bent, both upper arms and the neck turned about their first joints.
  std::vector<Eigen::Affine3d> pose(W.cols(), Eigen::Affine3d::Identity());
  auto turn = [&](const std::string& name, double degrees, const Eigen::Vector3d& axis) {
    const int h = find_handle(teddy.rig(), name);
    const Bone& bone = teddy.rig().skeleton.bones[h - num_point_handles(teddy.rig())];
    const Eigen::Vector3d pivot = teddy.rig().skeleton.joints.row(bone.a).transpose();
    pose[h] = Eigen::Translation3d(pivot) * Eigen::AngleAxisd(degrees * M_PI / 180, axis.normalized()) * Eigen::Translation3d(-pivot);
  };
  turn("spine", 15, Eigen::Vector3d::UnitX());
  turn("l_upper_arm", 35, Eigen::Vector3d::UnitZ());
  turn("r_upper_arm", -30, Eigen::Vector3d(0, 1, 1));
  turn("neck", 20, Eigen::Vector3d::UnitY());
  const Eigen::MatrixXd posed_body = blend(body.V, W, pose);
  const Eigen::MatrixXd expected = offset_surface(posed_body, test::area_weighted_normals(posed_body, body.F));
  const Eigen::MatrixXd posed_shirt = blend(shirt.V, T, pose);
  const Eigen::VectorXd err = (posed_shirt - expected).rowwise().norm();
  WARN("shirt " << shirt.V.rows() << " vertices (" << r.matched << " matched, " << r.inpainted << " inpainted); posed, "
                << "off the posed body's offset by at most " << err.maxCoeff() / diag << " and on average " << err.mean() / diag
                << " of the diagonal");
  CHECK(err.maxCoeff() <= 0.01 * diag);
}
