#include <catch2/catch.hpp>

#include <atomic>
#include <string>
#include <vector>

#include "core/bind/bind.h"
#include "core/mesh/io.h"
#include "core/rig/rig_io.h"
#include "core/util/error.h"
#include "tests/test_support.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;

namespace {

// What every bind must satisfy: bounded, rows sum to 1, constraints honoured (1 on the own handle, 0 on
// the others at handle vertices), converged to the KKT tolerance.
void check_bind(const BindResult& r, int user_vertices, int handles) {
  REQUIRE(r.weights.rows() == user_vertices);
  REQUIRE(r.weights.cols() == handles);
  REQUIRE(r.weights.minCoeff() >= 0);
  REQUIRE(r.weights.maxCoeff() <= 1);
  REQUIRE((r.weights.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-9);
  REQUIRE((r.tet_weights.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-9);
  for (int k = 0; k < r.volume.b.size(); ++k)
    REQUIRE((r.tet_weights.row(r.volume.b(k)) - r.volume.bc.row(k)).cwiseAbs().maxCoeff() < 1e-12);
  REQUIRE(r.report.bbw.converged);
  REQUIRE(r.report.bbw.kkt_residual <= 1e-6);
  REQUIRE(r.report.max_row_sum_error < 1e-9);
}

// The tet vertex at position p (a handle's own vertex), -1 if none.
int tet_vertex_at(const BindResult& r, const Eigen::Vector3d& p) {
  for (int v = 0; v < r.volume.tets.V.rows(); ++v)
    if ((r.volume.tets.V.row(v).transpose() - p).norm() < 1e-9) return v;
  return -1;
}

}  // namespace

TEST_CASE("point handles off the input vertices: 1 at their own tet vertex, nearer handle dominates", "[bind]") {
  const TriMesh box = test::box_mesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 1, 1));
  Rig rig;
  rig.points.push_back({Eigen::Vector3d(0.4, 0.5, 0.5), "left"});
  rig.points.push_back({Eigen::Vector3d(1.6, 0.45, 0.55), "right"});
  BindOptions o;
  o.volume.tetgen_switches = "pq1.414a0.002";
  const BindResult r = bind_surface(box, rig, o);
  check_bind(r, 8, 2);
  for (int h = 0; h < 2; ++h) {
    const int v = tet_vertex_at(r, rig.points[h].position);
    REQUIRE(v >= 0);
    REQUIRE(r.tet_weights(v, h) == 1.0);
    REQUIRE(r.tet_weights(v, 1 - h) == 0.0);
  }
  for (int c = 0; c < 8; ++c) REQUIRE((r.weights(c, 0) > r.weights(c, 1)) == (box.V(c, 0) < 1));
  REQUIRE(r.report.tets == r.volume.tets.num_tets());
  REQUIRE(r.report.tets > 100);
}

TEST_CASE("two bones along a bar: bone vertices constrained, shared joint split, ends follow their bone", "[bind]") {
  const TriMesh bar = test::box_mesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(4, 1, 1));
  Rig rig;
  rig.skeleton.joints.resize(3, 3);
  rig.skeleton.joints << 0.5, 0.5, 0.5, 2, 0.5, 0.5, 3.5, 0.5, 0.5;
  rig.skeleton.bones = {{0, 1}, {1, 2}};
  compute_bone_parents(rig.skeleton);
  BindOptions o;
  o.volume.tetgen_switches = "pq1.414a0.005";
  const BindResult r = bind_surface(bar, rig, o);
  check_bind(r, 8, 2);
  const int shared = tet_vertex_at(r, Eigen::Vector3d(2, 0.5, 0.5));
  REQUIRE(shared >= 0);
  REQUIRE(r.tet_weights(shared, 0) == Approx(0.5));
  for (int c = 0; c < 8; ++c) REQUIRE(r.weights(c, bar.V(c, 0) < 2 ? 0 : 1) > 0.9);
  // Points on bone 0 (away from the shared joint) carry weight 1 for it.
  const int on_bone = tet_vertex_at(r, Eigen::Vector3d(0.5, 0.5, 0.5));
  REQUIRE(on_bone >= 0);
  REQUIRE(r.tet_weights(on_bone, 0) == 1.0);
}

TEST_CASE("open (partial) cage plus a point handle inside a box", "[bind]") {
  const TriMesh box = test::box_mesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  Rig rig;
  rig.points.push_back({Eigen::Vector3d(0.5, 0.5, 0.15), "p"});
  Cage sheet;
  sheet.mesh.V.resize(5, 3);
  sheet.mesh.V << 0.25, 0.25, 0.5, 0.75, 0.25, 0.5, 0.75, 0.75, 0.5, 0.25, 0.75, 0.5, 0.5, 0.5, 0.85;
  sheet.mesh.F.resize(2, 3);
  sheet.mesh.F << 0, 1, 2, 0, 2, 3;
  sheet.edges.resize(1, 2);
  sheet.edges << 2, 4;
  sheet.name = "sheet";
  rig.cages.push_back(sheet);
  BindOptions o;
  o.volume.tetgen_switches = "pq1.414a0.001";
  const BindResult r = bind_surface(box, rig, o);
  check_bind(r, 8, 6);
  // Cage vertices are handles 1..5: weight 1 at their own vertex.
  for (int h = 0; h < 5; ++h) {
    const int v = tet_vertex_at(r, sheet.mesh.V.row(h).transpose());
    REQUIRE(v >= 0);
    REQUIRE(r.tet_weights(v, 1 + h) == 1.0);
  }
  // Each box corner is dominated by the nearest handle (a sheet corner, 0.61 away, vs 0.72 for the rest).
  for (int c = 0; c < 8; ++c) {
    int best;
    r.weights.row(c).maxCoeff(&best);
    const int sheet_corner = (box.V(c, 0) > 0.5 ? (box.V(c, 1) > 0.5 ? 2 : 1) : (box.V(c, 1) > 0.5 ? 3 : 0));
    REQUIRE(best == 1 + sheet_corner);
  }
}

TEST_CASE("closed cage around a box: nearest cage corner dominates each corner", "[bind]") {
  const TriMesh box = test::box_mesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  Rig rig;
  rig.cages.push_back({test::box_mesh(Eigen::Vector3d(-0.3, -0.3, -0.3), Eigen::Vector3d(1.3, 1.3, 1.3)), {}, "cage"});
  BindOptions o;
  o.volume.tetgen_switches = "pq1.414a0.01";
  const BindResult r = bind_surface(box, rig, o);
  check_bind(r, 8, 8);
  for (int c = 0; c < 8; ++c) {
    int best;
    r.weights.row(c).maxCoeff(&best);
    REQUIRE(best == c);  // box_mesh numbers corners the same way for both boxes
  }
}

TEST_CASE("exact partition of unity through the whole bind", "[bind]") {
  const TriMesh box = test::box_mesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 1, 1));
  Rig rig;
  rig.points.push_back({Eigen::Vector3d(0.3, 0.5, 0.5), "a"});
  rig.points.push_back({Eigen::Vector3d(1.0, 0.5, 0.5), "b"});
  rig.points.push_back({Eigen::Vector3d(1.7, 0.5, 0.5), "c"});
  BindOptions o;
  o.volume.tetgen_switches = "pq1.414a0.01";
  o.bbw.exact_partition_of_unity = true;
  const BindResult r = bind_surface(box, rig, o);
  check_bind(r, 8, 3);
}

TEST_CASE("bind reports progress in order and can be cancelled", "[bind]") {
  const TriMesh box = test::box_mesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  Rig rig;
  rig.points.push_back({Eigen::Vector3d(0.3, 0.5, 0.5), "a"});
  rig.points.push_back({Eigen::Vector3d(0.7, 0.5, 0.5), "b"});
  BindOptions o;
  o.volume.tetgen_switches = "pq1.414a0.01";
  std::vector<std::string> stages;
  std::vector<double> fractions;
  o.progress = [&](const std::string& s, double f) { stages.push_back(s), fractions.push_back(f); };
  bind_surface(box, rig, o);
  REQUIRE(stages.front() == "meshing");
  REQUIRE(stages.back() == "done");
  for (size_t k = 1; k < fractions.size(); ++k) REQUIRE(fractions[k] >= fractions[k - 1]);
  std::atomic<bool> cancel{false};
  o.cancel = &cancel;
  o.progress = [&](const std::string& s, double) {
    if (s == "factorization") cancel = true;
  };
  REQUIRE_THROWS_WITH(bind_surface(box, rig, o), "cancelled");
}

TEST_CASE("a cancelled bind throws dfm::Cancelled from every stage, monotone included", "[bind]") {
  const TriMesh box = test::box_mesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  Rig rig;
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0.3, 0.5, 0.5), Eigen::Vector3d(0.7, 0.5, 0.5), Eigen::Vector3d(0.5, 0.3, 0.5)})
    rig.points.push_back({p, ""});
  for (const std::string stage : {"meshing", "assembly", "factorization", "solve", "monotone"}) {
    CAPTURE(stage);
    BindOptions o;
    o.volume.tetgen_switches = "pq1.414a0.01";
    o.bbw.monotone = true;
    std::atomic<bool> cancel{false};
    o.cancel = &cancel;
    o.progress = [&](const std::string& s, double) {
      if (s == stage) cancel = true;
    };
    REQUIRE_THROWS_AS(bind_surface(box, rig, o), Cancelled);
  }
  // A failure (a handle outside the surface) is an Error, not a Cancelled.
  Rig outside;
  outside.points.push_back({Eigen::Vector3d(5, 5, 5), "far"});
  CHECK(test::thrown_kind([&] { bind_surface(box, outside); }) == "error");
}

TEST_CASE("hand.mesh + hand.tgf bind as given (20 bones)", "[bind][data]") {
  DFM_DATA_OR_SKIP(mesh_path, "hand.mesh");
  DFM_DATA_OR_SKIP(tgf_path, "hand.tgf");
  const TetMesh tets = read_tet_mesh(mesh_path);
  Rig rig;
  add_tgf_to_rig(rig, read_tgf(tgf_path), tgf_path);
  const BindResult r = bind_tet_mesh(tets, rig);
  check_bind(r, tets.num_vertices(), 20);
  REQUIRE(r.report.zero_fraction > 0.3);  // weights are local
}
