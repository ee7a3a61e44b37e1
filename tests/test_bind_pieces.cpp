// Issue 19: pieces of the bind volume with no handle inside (the case where Blender's bone heat "failed to
// find a solution") take the weights at the nearest point of the nearest handled piece, constant over the
// piece (they move rigidly), and the bind names them; never an all-zero row.
#include <catch2/catch.hpp>

#include <string>

#include "core/bind/bind.h"
#include "core/util/error.h"
#include "tests/messy_test_meshes.h"

using namespace dfm;

namespace {

constexpr int kSphere = 162;  // vertices of a level-2 icosphere

// Brute force over the user's vertices: the vertex of sphere 0 nearest to sphere k (closest pair).
int nearest_in_first_sphere(const TriMesh& m, int k) {
  int best = -1;
  double bd = 1e300;
  for (int a = 0; a < kSphere; ++a)
    for (int b = k * kSphere; b < (k + 1) * kSphere; ++b) {
      const double d = (m.V.row(a) - m.V.row(b)).squaredNorm();
      if (d < bd) bd = d, best = a;
    }
  return best;
}

std::string notes_of(const BindResult& r) {
  std::string s;
  for (const std::string& n : r.report.notes) s += n + "\n";
  return s;
}

void check_rigid_spheres(const TriMesh& m, const BindResult& r) {
  INFO(notes_of(r));
  const Eigen::MatrixXd& W = r.weights;
  REQUIRE(W.rows() == 3 * kSphere);
  REQUIRE(W.allFinite());
  REQUIRE(W.minCoeff() >= -1e-9);
  REQUIRE(W.maxCoeff() <= 1 + 1e-9);
  REQUIRE((W.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-9);
  REQUIRE(W.rowwise().maxCoeff().minCoeff() > 0);  // no all-zero row
  // Pieces 1 and 2 (in vertex order) have no handle: named, with their vertex counts.
  REQUIRE(r.volume.rigid_pieces.size() == 2);
  for (int k = 1; k <= 2; ++k) {
    REQUIRE(r.volume.rigid_pieces[k - 1].piece == k);
    REQUIRE(r.volume.rigid_pieces[k - 1].vertices == kSphere);
  }
  REQUIRE(notes_of(r).find("2 of 3 pieces of the volume have no handle") != std::string::npos);
  REQUIRE(notes_of(r).find("piece 1 (162 vertices), piece 2 (162 vertices)") != std::string::npos);
  for (int k = 1; k <= 2; ++k) {
    // One row over the whole piece: the weights at sphere 0's vertex nearest to it.
    const Eigen::RowVectorXd ref = W.row(nearest_in_first_sphere(m, k));
    REQUIRE(ref.maxCoeff() < 1 - 1e-3);  // a blend of both handles there, not one handle's constraint
    for (int v = k * kSphere; v < (k + 1) * kSphere; ++v) REQUIRE((W.row(v) - ref).cwiseAbs().maxCoeff() < 1e-12);
  }
}

Rig two_points_in_first_sphere() {
  Rig rig;
  rig.points.push_back({Eigen::Vector3d(-0.5, 0, 0), "left"});
  rig.points.push_back({Eigen::Vector3d(0.4, 0.2, 0), "right"});
  return rig;
}

}  // namespace

TEST_CASE("three closed pieces, handles in one: the others move rigidly with it (TetGen volume)", "[bind][pieces]") {
  const TriMesh m = dfm::test::three_spheres();
  BindOptions o;
  o.volume.tetgen_switches = "pq2Y";  // Y: no Steiner points on the surface, so the nearest point is a vertex
  check_rigid_spheres(m, bind_surface(m, two_points_in_first_sphere(), o));
}

TEST_CASE("three closed pieces, handles in one: the others move rigidly with it (robust volume)", "[bind][pieces][robust]") {
  const TriMesh m = dfm::test::three_spheres();
  BindOptions o;
  o.volume.tetgen_switches = "pq2Y";
  o.volume.robust = VolumeOptions::Robust::Always;
  check_rigid_spheres(m, bind_surface(m, two_points_in_first_sphere(), o));
}

TEST_CASE("a rigid piece takes its anchor's solved weights, not a placeholder", "[bind][pieces]") {
  // bind_on_volume applies the pieces too: a volume whose rigid piece points at a chosen anchor.
  const TriMesh m = dfm::test::three_spheres();
  BindOptions o;
  o.volume.tetgen_switches = "pq2Y";
  const BindResult r = bind_surface(m, two_points_in_first_sphere(), o);
  BindVolume v = r.volume;
  v.rigid_pieces[0].anchor = 0;  // user vertex 0 of sphere 0 is tet vertex 0
  const BindResult again = bind_on_volume(v, o);
  for (int u = kSphere; u < 2 * kSphere; ++u)
    REQUIRE((again.weights.row(u) - again.weights.row(0)).cwiseAbs().maxCoeff() < 1e-12);
}
