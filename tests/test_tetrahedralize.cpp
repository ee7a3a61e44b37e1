// TetGen as a subprocess: conformity to facets, segments and points, vertex order, orientation,
// volume, failures reported with TetGen's message, temporary folders cleaned up.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <set>

#include "core/bind/tetrahedralize.h"
#include "core/mesh/io.h"
#include "core/util/error.h"
#include "tests/test_support.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;
using dfm::test::box_mesh;
using dfm::test::enclosed_volume;
using dfm::test::tet_mesh_volume;

namespace {

// A temporary folder of this test's own as TMPDIR while it lives, so counting TetGen's folders is not
// disturbed by other tests running TetGen at the same time (ctest -j).
struct PrivateTmp {
  std::string dir, old;
  bool had_old = false;
  PrivateTmp() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "dfm-test-tmp-XXXXXX").string();
    REQUIRE(mkdtemp(tmpl.data()) != nullptr);
    dir = tmpl;
    if (const char* o = std::getenv("TMPDIR")) old = o, had_old = true;
    setenv("TMPDIR", dir.c_str(), 1);
  }
  ~PrivateTmp() {
    if (had_old) setenv("TMPDIR", old.c_str(), 1);
    else unsetenv("TMPDIR");
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
};

int temp_folders() {
  int n = 0;
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::temp_directory_path()))
    n += e.path().filename().string().rfind("dfm-tetgen-", 0) == 0;
  return n;
}

bool has_edge(const Eigen::MatrixXi& T, int a, int b) {
  for (int t = 0; t < T.rows(); ++t) {
    bool ha = false, hb = false;
    for (int k = 0; k < 4; ++k) ha |= T(t, k) == a, hb |= T(t, k) == b;
    if (ha && hb) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("cube with an inner segment and point: conforming, ordered, positive, exact volume", "[tetgen]") {
  TriMesh cube = box_mesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3));
  Plc plc;
  plc.V.resize(11, 3);
  plc.V.topRows(8) = cube.V;
  plc.V.row(8) << 0.2, 1.0, 1.5;
  plc.V.row(9) << 0.8, 1.0, 1.5;
  plc.V.row(10) << 0.5, 0.3, 0.7;  // an isolated point
  plc.F = cube.F;
  plc.E.resize(1, 2);
  plc.E << 8, 9;
  PrivateTmp tmp;
  const int before = temp_folders();
  TetgenResult r = tetrahedralize(plc, "pq1.414Y");
  REQUIRE(temp_folders() == before);
  REQUIRE(r.mesh.V.rows() >= 11);
  REQUIRE(r.mesh.V.topRows(11) == plc.V);  // exactly, not approximately
  for (int i = 0; i < 11; ++i) REQUIRE(r.input_to_tet(i) == i);
  double min_vol;
  REQUIRE(tet_mesh_volume(r.mesh, &min_vol) == Approx(6.0).epsilon(1e-12));
  REQUIRE(min_vol > 0);
  REQUIRE(has_edge(r.mesh.T, 8, 9));  // the segment is a tet edge (Y: no Steiner point on it)
  REQUIRE(r.log.find("Mesh tetrahedra") != std::string::npos);
}

TEST_CASE("a point outside the facets is dropped and reported as -1", "[tetgen]") {
  TriMesh cube = box_mesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  Plc plc;
  plc.V.resize(10, 3);
  plc.V.topRows(8) = cube.V;
  plc.V.row(8) << 3, 3, 3;      // outside
  plc.V.row(9) << 0.5, 0.5, 0.5;  // inside, after the dropped one
  plc.F = cube.F;
  TetgenResult r = tetrahedralize(plc, "pq1.414Y");
  REQUIRE(r.input_to_tet(8) == -1);
  REQUIRE(r.input_to_tet(9) >= 0);
  REQUIRE(r.mesh.V.row(r.input_to_tet(9)) == plc.V.row(9));
  REQUIRE(tet_mesh_volume(r.mesh) == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("point set without facets: the convex hull", "[tetgen]") {
  Plc plc;
  plc.V = box_mesh(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1)).V;
  TetgenResult r = tetrahedralize(plc, "pq1.414Y");  // p and Y are dropped for a point set
  REQUIRE(tet_mesh_volume(r.mesh) == Approx(8.0).epsilon(1e-12));
}

TEST_CASE("self-intersecting facets: dfm::Error carrying TetGen's message, folder removed", "[tetgen]") {
  TriMesh a = box_mesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  TriMesh b = box_mesh(Eigen::Vector3d(0.5, 0.5, 0.5), Eigen::Vector3d(1.5, 1.5, 1.5));
  TriMesh both = dfm::test::concat(a, b);
  Plc plc{both.V, both.F, {}};
  PrivateTmp tmp;
  const int before = temp_folders();
  try {
    tetrahedralize(plc, "pq1.414Y");
    FAIL("expected TetGen to fail");
  } catch (const Error& e) {
    INFO(e.what());
    REQUIRE(std::string(e.what()).find("TetGen") != std::string::npos);
    REQUIRE(std::string(e.what()).find("ntersect") != std::string::npos);  // TetGen's own words
  }
  REQUIRE(temp_folders() == before);
}

TEST_CASE("unsupported or malformed switches are refused before running", "[tetgen]") {
  Plc plc;
  plc.V = box_mesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1)).V;
  REQUIRE_THROWS_AS(tetrahedralize(plc, "pq1.414; rm -rf /"), Error);
  REQUIRE_THROWS_AS(tetrahedralize(plc, "po2"), Error);
  REQUIRE_THROWS_AS(tetrahedralize(plc, "pr"), Error);
  Plc bad = plc;
  bad.F = Eigen::MatrixXi::Constant(1, 3, 42);
  REQUIRE_THROWS_AS(tetrahedralize(bad, "p"), Error);
}

TEST_CASE("decimated knight: surface vertices first and exact; tet volume = enclosed volume", "[tetgen][data]") {
  DFM_DATA_OR_SKIP(path, "decimated-knight.off");
  TriMesh m = read_surface(path);
  TetgenResult r = tetrahedralize(Plc{m.V, m.F, {}}, "pq1.414Y");
  REQUIRE(r.mesh.V.topRows(m.V.rows()) == m.V);
  double min_vol;
  const double vol = tet_mesh_volume(r.mesh, &min_vol);
  REQUIRE(min_vol > 0);
  REQUIRE(vol == Approx(std::abs(enclosed_volume(m.V, m.F))).epsilon(1e-9));
  // Y keeps the surface: every input triangle is a face of some tet.
  std::set<std::array<int, 3>> faces;
  for (int t = 0; t < r.mesh.T.rows(); ++t)
    for (int c = 0; c < 4; ++c) {
      std::array<int, 3> f;
      for (int k = 0, j = 0; k < 4; ++k)
        if (k != c) f[j++] = r.mesh.T(t, k);
      std::sort(f.begin(), f.end());
      faces.insert(f);
    }
  for (int f = 0; f < m.F.rows(); ++f) {
    std::array<int, 3> key{m.F(f, 0), m.F(f, 1), m.F(f, 2)};
    std::sort(key.begin(), key.end());
    REQUIRE(faces.count(key) == 1);
  }
}
