// Every file in ../shared/data loads with the counts its README gives.
#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include "core/mesh/io.h"
#include "core/rig/rig_io.h"
#include "tests/test_support.h"

using namespace dfm;

static double tet_volume(const TetMesh& m, int t) {
  Eigen::Vector3d a = m.V.row(m.T(t, 0)), b = m.V.row(m.T(t, 1)), c = m.V.row(m.T(t, 2)), d = m.V.row(m.T(t, 3));
  return (b - a).cross(c - a).dot(d - a) / 6.0;
}

TEST_CASE("hand.mesh: 7,234 vertices, 29,998 positively oriented tets", "[io][data]") {
  DFM_DATA_OR_SKIP(path, "hand.mesh");
  TetMesh m = read_tet_mesh(path);
  REQUIRE(m.num_vertices() == 7234);
  REQUIRE(m.num_tets() == 29998);
  REQUIRE(m.F.rows() == 9556);
  // First vertex as in the file.
  REQUIRE(m.V(0, 0) == 0.013411);
  REQUIRE(m.V(0, 1) == -0.798051);
  int positive = 0;
  for (int t = 0; t < m.num_tets(); ++t) positive += tet_volume(m, t) > 0;
  REQUIRE(positive == m.num_tets());
  REQUIRE(m.T.minCoeff() == 0);
  REQUIRE(m.T.maxCoeff() < 7234);
}

TEST_CASE("octopus-low.mesh loads as a tet mesh", "[io][data]") {
  DFM_DATA_OR_SKIP(path, "octopus-low.mesh");
  TetMesh m = read_tet_mesh(path);
  REQUIRE(m.num_vertices() > 0);
  REQUIRE(m.num_tets() > 0);
  for (int t = 0; t < m.num_tets(); ++t) REQUIRE(tet_volume(m, t) >= 0);
}

TEST_CASE("hand.tgf: 21 joints, 20 bones forming one tree", "[io][data]") {
  DFM_DATA_OR_SKIP(path, "hand.tgf");
  TgfData t = read_tgf(path);
  REQUIRE(t.joints.rows() == 21);
  REQUIRE(t.edges.rows() == 20);
  REQUIRE(t.flags.col(0).sum() == 20);
  REQUIRE(t.joints(0, 0) == 0.11429762);
  Rig rig;
  add_tgf_to_rig(rig, t, "hand.tgf");
  REQUIRE(rig.skeleton.num_bones() == 20);
  REQUIRE(rig.skeleton.num_joints() == 21);
  REQUIRE(rig.points.empty());
  int roots = 0;
  for (const Bone& b : rig.skeleton.bones) roots += b.parent < 0;
  REQUIRE(roots == 1);
}

TEST_CASE("hand-pose.dmat: 80 x 1 unit quaternions", "[io][data]") {
  DFM_DATA_OR_SKIP(path, "hand-pose.dmat");
  Eigen::MatrixXd Q = read_dmat(path);
  REQUIRE(Q.rows() == 80);
  REQUIRE(Q.cols() == 1);
  REQUIRE(Q(0, 0) == 0.61618142029453848);
  for (int b = 0; b < 20; ++b) REQUIRE(Q.block<4, 1>(4 * b, 0).norm() == Approx(1.0).epsilon(1e-6));
}

TEST_CASE("arm and elephant: closed surfaces with skeletons", "[io][data]") {
  DFM_DATA_OR_SKIP(arm, "arm.obj");
  TriMesh a = read_surface(arm);
  REQUIRE(a.num_vertices() == 8311);
  REQUIRE(a.num_faces() == 16618);
  DFM_DATA_OR_SKIP(arm_tgf, "arm.tgf");
  Rig ra;
  add_tgf_to_rig(ra, read_tgf(arm_tgf), "arm.tgf");
  REQUIRE(ra.skeleton.num_bones() == 4);
  DFM_DATA_OR_SKIP(el, "elephant.obj");
  TriMesh e = read_surface(el);
  REQUIRE(e.num_vertices() == 6034);
  DFM_DATA_OR_SKIP(el_tgf, "elephant.tgf");
  Rig re;
  add_tgf_to_rig(re, read_tgf(el_tgf), "elephant.tgf");
  REQUIRE(re.skeleton.num_bones() == 24);
}

TEST_CASE("armadillo.obj: 43,243 vertices, 86,482 triangles", "[io][data]") {
  DFM_DATA_OR_SKIP(path, "armadillo.obj");
  TriMesh m = read_surface(path);
  REQUIRE(m.num_vertices() == 43243);
  REQUIRE(m.num_faces() == 86482);
}

TEST_CASE("OFF files load with their header counts", "[io][data]") {
  struct Case { const char* name; int nv, nf; };
  const Case cases[] = {{"decimated-knight.off", 502, 1000}, {"bunny.off", 3485, 6966},
                        {"cow.off", 2762, 5520},             {"cheburashka.off", 6669, 13334},
                        {"3holes.off", 3596, 7200},          {"camelhead.off", 11381, 22704},
                        {"beetle.off", 19887, 38656}};
  for (const Case& c : cases) {
    DFM_DATA_OR_SKIP(path, c.name);
    TriMesh m = read_surface(path);
    INFO(c.name);
    REQUIRE(m.num_vertices() == c.nv);
    REQUIRE(m.num_faces() == c.nf);
  }
}
