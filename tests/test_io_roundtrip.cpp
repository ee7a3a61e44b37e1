// Write then read gives identical V, F (and normals where the format has them) for every format.
#include <filesystem>
#include <random>

#include <unistd.h>

#include <catch2/catch.hpp>

#include "core/mesh/io.h"
#include "core/rig/rig_io.h"
#include "core/util/error.h"

using namespace dfm;
namespace fs = std::filesystem;

static fs::path tmp_dir() {
  fs::path d = fs::temp_directory_path() / ("dfm_test_io_rt_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

// An octahedron with awkward coordinates (no short decimal form, tiny and huge magnitudes, -0), whose
// vertices appear in F in index order (so STL's first-appearance numbering is the identity).
static TriMesh octahedron(bool float_exact) {
  TriMesh m;
  m.V.resize(6, 3);
  m.V << 0.1, 1.0 / 3.0, -2.0 / 7.0,  //
      1e-300, -0.0, 12345678.901234567,   //
      -1.0, std::sqrt(2.0), 0.5,      //
      3.0, -1e10, 1.0 / 9.0,          //
      0.0, 0.0, 1.0,                  //
      -5.5, 2.25, -1e-7;
  if (float_exact) m.V = m.V.cast<float>().cast<double>();
  m.F.resize(8, 3);
  m.F << 0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1, 5, 2, 1, 5, 3, 2, 5, 4, 3, 5, 1, 4;
  return m;
}

static void require_same(const TriMesh& a, const TriMesh& b) {
  REQUIRE(a.V.rows() == b.V.rows());
  REQUIRE(a.F.rows() == b.F.rows());
  for (int i = 0; i < a.V.size(); ++i) REQUIRE(a.V.data()[i] == b.V.data()[i]);
  REQUIRE(a.F == b.F);
}

TEST_CASE("surface round trips are exact: OBJ, OFF, PLY ascii/binary, STL ascii", "[io][roundtrip]") {
  fs::path d = tmp_dir();
  TriMesh m = octahedron(false);
  for (const char* name : {"a.obj", "a.off", "a.ply", "b.ply", "a.stl"}) {
    INFO(name);
    const bool binary = std::string(name) == "b.ply";
    write_surface((d / name).string(), m, binary);
    TriMesh r = read_surface((d / name).string());
    require_same(m, r);
    REQUIRE(r.N.size() == 0);
  }
  fs::remove_all(d);
}

TEST_CASE("binary STL round trip is exact for float-representable coordinates", "[io][roundtrip]") {
  fs::path d = tmp_dir();
  TriMesh m = octahedron(true);
  write_surface((d / "b.stl").string(), m, true);
  REQUIRE(fs::file_size(d / "b.stl") == 84 + 50 * 8);
  require_same(m, read_surface((d / "b.stl").string()));
  fs::remove_all(d);
}

TEST_CASE("normals round trip in OBJ, OFF (NOFF) and PLY", "[io][roundtrip]") {
  fs::path d = tmp_dir();
  TriMesh m = octahedron(false);
  m.N = m.V.rowwise().normalized();
  m.N(1, 0) = 1.0 / 3.0;
  for (const char* name : {"n.obj", "n.off", "n.ply", "nb.ply"}) {
    INFO(name);
    write_surface((d / name).string(), m, std::string(name) == "nb.ply");
    TriMesh r = read_surface((d / name).string());
    require_same(m, r);
    REQUIRE(r.N == m.N);
  }
  fs::remove_all(d);
}

TEST_CASE("random meshes round trip exactly in every surface format", "[io][roundtrip]") {
  fs::path d = tmp_dir();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  TriMesh m;
  const int nv = 201, nf = 500;  // nv divisible by 3: the first nv/3 faces use every vertex in order
  m.V.resize(nv, 3);
  for (int i = 0; i < m.V.size(); ++i) m.V.data()[i] = u(rng) * std::pow(10.0, int(u(rng)) % 12);
  m.F.resize(nf, 3);
  for (int f = 0; f < nf; ++f)
    for (int c = 0; c < 3; ++c) m.F(f, c) = (f < nv / 3 ? 3 * f + c : int(rng() % nv));  // every vertex used, in order
  for (const char* name : {"r.obj", "r.off", "r.ply", "rb.ply", "r.stl"}) {
    INFO(name);
    write_surface((d / name).string(), m, std::string(name) == "rb.ply");
    require_same(m, read_surface((d / name).string()));
  }
  fs::remove_all(d);
}

TEST_CASE("tet mesh round trips: .mesh and .node/.ele", "[io][roundtrip]") {
  fs::path d = tmp_dir();
  TetMesh m;
  m.V.resize(5, 3);
  m.V << 0, 0, 0, 1.0 / 3.0, 0, 0, 0, 1, 0, 0, 0, 1, 1e-9, 2.0 / 3.0, 7.25;
  m.T.resize(2, 4);
  m.T << 0, 1, 2, 3, 1, 2, 3, 4;  // both positively oriented
  m.F.resize(1, 3);
  m.F << 0, 2, 1;
  write_tet_mesh((d / "t.mesh").string(), m);
  TetMesh r = read_tet_mesh((d / "t.mesh").string());
  REQUIRE(r.V == m.V);
  REQUIRE(r.T == m.T);
  REQUIRE(r.F == m.F);
  write_tet_mesh((d / "t.node").string(), m);
  REQUIRE(fs::exists(d / "t.ele"));
  r = read_tet_mesh((d / "t.ele").string());
  REQUIRE(r.V == m.V);
  REQUIRE(r.T == m.T);
  fs::remove_all(d);
}

TEST_CASE("negatively oriented tets are flipped on reading", "[io]") {
  fs::path d = tmp_dir();
  TetMesh m;
  m.V.resize(4, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  m.T.resize(1, 4);
  m.T << 0, 2, 1, 3;  // negative volume as written
  write_tet_mesh((d / "neg.mesh").string(), m);
  TetMesh r = read_tet_mesh((d / "neg.mesh").string());
  Eigen::RowVector4i expected(0, 2, 3, 1);
  REQUIRE(r.T.row(0) == expected);
  fs::remove_all(d);
}

TEST_CASE("dmat round trips exactly, text and binary", "[io][roundtrip]") {
  fs::path d = tmp_dir();
  Eigen::MatrixXd M(3, 4);
  M << 1.0 / 3, -0.0, 1e-300, 1e300, 2, 3, 4, 5, std::sqrt(2.0), -7, 0.1, 0.2;
  for (bool binary : {false, true}) {
    write_dmat((d / "m.dmat").string(), M, binary);
    Eigen::MatrixXd R = read_dmat((d / "m.dmat").string());
    REQUIRE(R.rows() == 3);
    REQUIRE(R.cols() == 4);
    REQUIRE(R == M);
  }
  // Binary layout: "0 0\n", "cols rows\n", then doubles column by column.
  write_dmat((d / "b.dmat").string(), M, true);
  REQUIRE(fs::file_size(d / "b.dmat") == 4 + 4 + 12 * 8);
  // Empty and single-column matrices.
  for (Eigen::MatrixXd E : {Eigen::MatrixXd(), Eigen::MatrixXd(0, 3), Eigen::MatrixXd(Eigen::VectorXd::LinSpaced(5, 0, 1))}) {
    write_dmat((d / "e.dmat").string(), E, false);
    Eigen::MatrixXd R = read_dmat((d / "e.dmat").string());
    REQUIRE(R.rows() == E.rows());
    REQUIRE(R.cols() == E.cols());
    REQUIRE(R == E);
  }
  fs::remove_all(d);
}

TEST_CASE("points round trip", "[io][roundtrip]") {
  fs::path d = tmp_dir();
  Eigen::MatrixXd P(3, 3);
  P << 1.0 / 3, 2, 3, -4, 5e-20, 6, 7, 8, 9.125;
  write_points((d / "p.txt").string(), P);
  REQUIRE(read_points((d / "p.txt").string()) == P);
  fs::remove_all(d);
}

TEST_CASE("tgf and rig round trip: bones, point handles, pseudo-edges, cage edges", "[io][roundtrip][rig]") {
  fs::path d = tmp_dir();
  TgfData t;
  t.joints.resize(8, 3);
  for (int i = 0; i < 8; ++i) t.joints.row(i) << i / 3.0, -i, i * i;
  // joints 0-1-2 chain of bones, 3 and 4 point handles joined by a pseudo-edge, 5 a lone point handle,
  // 6-7 a cage edge.
  t.edges.resize(4, 2);
  t.flags.resize(4, 3);
  t.edges << 1, 2, 0, 1, 3, 4, 6, 7;
  t.flags << 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  write_tgf((d / "s.tgf").string(), t);
  TgfData r = read_tgf((d / "s.tgf").string());
  REQUIRE(r.joints == t.joints);
  REQUIRE(r.edges == t.edges);
  REQUIRE(r.flags == t.flags);

  Rig rig;
  add_tgf_to_rig(rig, r, "s.tgf");
  REQUIRE(rig.skeleton.num_joints() == 3);
  REQUIRE(rig.skeleton.num_bones() == 2);
  REQUIRE(rig.skeleton.bones[0].parent == 1);  // (1,2) hangs off (0,1)
  REQUIRE(rig.skeleton.bones[1].parent == -1);
  REQUIRE(rig.points.size() == 3);
  REQUIRE(rig.points[0].position == t.joints.row(3).transpose());
  REQUIRE(rig.points[2].position == t.joints.row(5).transpose());
  REQUIRE(rig.pseudo_edges.size() == 1);
  REQUIRE(rig.pseudo_edges[0] == std::make_pair(0, 1));
  REQUIRE(rig.cages.size() == 1);
  REQUIRE(rig.cages[0].mesh.num_vertices() == 2);
  REQUIRE(rig.cages[0].edges.rows() == 1);

  // rig -> tgf -> rig is the identity.
  Rig again;
  add_tgf_to_rig(again, rig_to_tgf(rig), "again");
  REQUIRE(again.skeleton.joints == rig.skeleton.joints);
  REQUIRE(again.skeleton.num_bones() == 2);
  for (int b = 0; b < 2; ++b) {
    REQUIRE(again.skeleton.bones[b].a == rig.skeleton.bones[b].a);
    REQUIRE(again.skeleton.bones[b].b == rig.skeleton.bones[b].b);
    REQUIRE(again.skeleton.bones[b].parent == rig.skeleton.bones[b].parent);
  }
  REQUIRE(again.points.size() == 3);
  for (int p = 0; p < 3; ++p) REQUIRE(again.points[p].position == rig.points[p].position);
  REQUIRE(again.pseudo_edges == rig.pseudo_edges);
  REQUIRE(again.cages[0].mesh.V == rig.cages[0].mesh.V);
  REQUIRE(again.cages[0].edges == rig.cages[0].edges);

  // A second TGF adds after what is there: point indices and joints continue.
  add_tgf_to_rig(again, r, "second");
  REQUIRE(again.points.size() == 6);
  REQUIRE(again.skeleton.num_bones() == 4);
  REQUIRE(again.skeleton.bones[2].a == 4);
  REQUIRE(again.pseudo_edges.back() == std::make_pair(3, 4));
  fs::remove_all(d);
}

TEST_CASE("writers refuse invalid meshes and keep the previous file", "[io]") {
  fs::path d = tmp_dir();
  TriMesh m = octahedron(false);
  const std::string p = (d / "keep.obj").string();
  write_surface(p, m);
  TriMesh bad = m;
  bad.F(3, 1) = 99;
  REQUIRE_THROWS_WITH(write_surface(p, bad), Catch::Contains("keep.obj") && Catch::Contains("face index"));
  require_same(read_surface(p), m);
  REQUIRE_THROWS_WITH(write_surface((d / "x.xyz").string(), m), Catch::Contains("unknown surface extension"));
  fs::remove_all(d);
}
