// Issue 19: point handles on the input surface, or within 1% of its bbox diagonal, are accepted on the
// robust (winding number) volume of messy meshes (Jacobson 2013, section 8.3); a handle clearly outside
// is refused by name.
#include <catch2/catch.hpp>

#include <chrono>
#include <iostream>

#include "core/bind/bind.h"
#include "core/mesh/io.h"
#include "core/util/error.h"
#include "tests/test_support.h"
#include "tests/messy_test_meshes.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;

namespace {

double diagonal(const TriMesh& m) { return (m.V.colwise().maxCoeff() - m.V.colwise().minCoeff()).norm(); }

// Referenced vertices with min x, max x and max y (the extremes a new user clicks first).
std::vector<int> extreme_vertices(const TriMesh& m) {
  std::vector<char> used(m.V.rows(), 0);
  for (int f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) used[m.F(f, k)] = 1;
  std::vector<int> best(3, -1);
  auto better = [&](int i, int v, int c, double s) { return best[i] < 0 || s * m.V(v, c) > s * m.V(best[i], c); };
  for (int v = 0; v < m.V.rows(); ++v) {
    if (!used[v]) continue;
    if (better(0, v, 0, -1)) best[0] = v;
    if (better(1, v, 0, 1)) best[1] = v;
    if (better(2, v, 1, 1)) best[2] = v;
  }
  return best;
}

Rig point_rig(const TriMesh& m, const std::vector<int>& verts) {
  Rig rig;
  for (size_t i = 0; i < verts.size(); ++i) rig.points.push_back({m.V.row(verts[i]).transpose(), "point " + std::to_string(i)});
  return rig;
}

BindOptions coarse(const std::string& switches = "pq2Y") {
  BindOptions o;
  o.volume.tetgen_switches = switches;  // coarse: these binds must stay fast
  return o;
}

// Binds with handles on `verts`; weights in [0,1], rows summing to 1, each handle 1 at its own vertex.
BindResult check_binds(const TriMesh& m, const std::vector<int>& verts, const std::string& what,
                       const std::string& switches = "pq2Y") {
  const auto t0 = std::chrono::steady_clock::now();
  const BindResult r = bind_surface(m, point_rig(m, verts), coarse(switches));
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << what << ": " << m.num_vertices() << " vertices, " << r.volume.tets.num_tets() << " tets, bind " << s << " s\n";
  const Eigen::MatrixXd& W = r.weights;
  REQUIRE(W.rows() == m.num_vertices());
  REQUIRE(W.cols() == static_cast<int>(verts.size()));
  REQUIRE(W.allFinite());
  REQUIRE(W.minCoeff() >= -1e-9);
  REQUIRE(W.maxCoeff() <= 1 + 1e-9);
  REQUIRE((W.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-6);
  for (size_t h = 0; h < verts.size(); ++h) REQUIRE(W(verts[h], h) == Approx(1).margin(1e-6));
  return r;
}

// The constrained tet vertex at x (within 1e-9 of the diagonal), or -1.
int constrained_row_at(const BindVolume& v, const Eigen::Vector3d& x, double diag) {
  for (int i = 0; i < v.b.size(); ++i)
    if ((v.tets.V.row(v.b(i)).transpose() - x).norm() < 1e-9 * diag) return i;
  return -1;
}

// The three extreme-vertex handles bind, and a fourth 10% of the diagonal beyond the min-x vertex is
// refused by name.
void check_acceptance(const TriMesh& m, const std::string& what, const std::string& switches = "pq2Y") {
  const std::vector<int> ext = extreme_vertices(m);
  check_binds(m, ext, what, switches);
  Rig rig = point_rig(m, ext);
  rig.points.push_back({m.V.row(ext[0]).transpose() - Eigen::Vector3d(0.1 * diagonal(m), 0, 0), "far away"});
  REQUIRE_THROWS_WITH(bind_surface(m, rig, coarse(switches)), Catch::Contains("point handle \"far away\" lies outside the volume"));
}

// A unit sphere with the faces around its top vertex removed (a small hole), and apart from it a small
// sphere with inverted faces (a piece whose winding number is <= 0 everywhere, as in meshes made of
// inconsistently oriented pieces): without the 1% rule the robust volume drops every tet at its vertices.
TriMesh sphere_with_hole_and_inverted_piece() {
  const TriMesh s = dfm::test::icosphere(Eigen::Vector3d::Zero(), 1.0, 3);
  int top = 0;
  for (int v = 0; v < s.V.rows(); ++v)
    if (s.V(v, 1) > s.V(top, 1)) top = v;
  std::vector<int> keep;
  for (int f = 0; f < s.F.rows(); ++f)
    if (s.F(f, 0) != top && s.F(f, 1) != top && s.F(f, 2) != top) keep.push_back(f);
  TriMesh holed;
  holed.V = s.V;
  holed.F.resize(keep.size(), 3);
  for (size_t i = 0; i < keep.size(); ++i) holed.F.row(i) = s.F.row(keep[i]);
  TriMesh inv = dfm::test::icosphere(Eigen::Vector3d(2.5, 0, 0), 0.3, 1);
  inv.F.col(1).swap(inv.F.col(2));
  return dfm::test::concat(holed, inv);
}

}  // namespace

TEST_CASE("open sphere with a hole and an inverted piece: handles on the rim and the piece bind", "[volume][robust]") {
  const TriMesh m = sphere_with_hole_and_inverted_piece();
  check_binds(m, extreme_vertices(m), "sphere with hole and inverted piece");
}

TEST_CASE("handles near the surface are accepted, clearly outside ones refused by name", "[volume][robust]") {
  const TriMesh m = sphere_with_hole_and_inverted_piece();
  const double diag = diagonal(m);
  const std::vector<int> ext = extreme_vertices(m);
  Rig rig = point_rig(m, ext);
  // 0.5% of the diagonal off the inverted piece's tip and above the hole's rim (both outside by winding
  // number, within 1% of the surface): accepted, each handle 1 at its own point.
  rig.points[1].position += Eigen::Vector3d(0.005 * diag, 0, 0);
  rig.points[2].position += Eigen::Vector3d(0, 0.005 * diag, 0);
  const BindResult near = bind_surface(m, rig, coarse());
  REQUIRE(near.weights.minCoeff() >= -1e-9);
  REQUIRE(near.weights.maxCoeff() <= 1 + 1e-9);
  REQUIRE((near.weights.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-6);
  for (int h = 0; h < 3; ++h) {  // the tet vertex at each handle carries that handle alone
    bool found = false;
    for (int i = 0; i < near.volume.b.size(); ++i)
      if ((near.volume.tets.V.row(near.volume.b(i)).transpose() - rig.points[h].position).norm() < 1e-9 * diag) {
        found = true;
        REQUIRE(near.volume.bc(i, h) == Approx(1).margin(1e-12));
      }
    REQUIRE(found);
  }
  // 10% of the diagonal beyond the min-x vertex: refused, naming the handle.
  rig = point_rig(m, ext);
  rig.points.push_back({m.V.row(ext[0]).transpose() - Eigen::Vector3d(0.1 * diag, 0, 0), "far away"});
  REQUIRE_THROWS_WITH(bind_surface(m, rig, coarse()), Catch::Contains("point handle \"far away\" lies outside the volume"));
}

// Coarse TetGen without quality (~2 s release); the robust volume is section 8.3's.
TEST_CASE("open data mesh (camelhead): handles on extreme vertices bind", "[volume][robust][data]") {
  DFM_DATA_OR_SKIP(path, "camelhead.off");
  check_binds(read_surface(path), extreme_vertices(read_surface(path)), "camelhead.off", "pY");
}

// Hidden (~25 s release: the beetle needs quality tets for the solver to converge); run with [slow].
TEST_CASE("open data mesh (beetle): handles on extreme vertices bind", "[.][slow][volume][robust][data]") {
  DFM_DATA_OR_SKIP(path, "beetle.off");
  const TriMesh m = read_surface(path);
  check_binds(m, extreme_vertices(m), "beetle.off", "pq3Y");
}

// Issue 19's acceptance meshes (built in tests/messy_test_meshes.h).
TEST_CASE("50 overlapping finned boxes (non-manifold): extreme handles bind, far one refused", "[volume][robust]") {
  const TriMesh m = dfm::test::fifty_finned_boxes();
  REQUIRE(dfm::test::count_nonmanifold_edges(m.F) == 50);
  check_acceptance(m, "50 finned boxes");
}

TEST_CASE("open sphere with a small hole: extreme handles bind, far one refused", "[volume][robust]") {
  check_acceptance(dfm::test::sphere_with_small_hole(), "sphere with a small hole");
}

TEST_CASE("quad-dominant mesh read from OBJ: extreme handles bind, far one refused", "[volume]") {
  const TriMesh m = dfm::test::quad_dominant_box();
  REQUIRE(m.num_faces() == 2 * 6 * 36);  // every quad split in two, the 4 triangle pairs as written
  check_acceptance(m, "quad-dominant box");
}

// Every path on a closed surface: a handle within 1% of the diagonal outside is inserted too (TetGen: one
// tet on the nearest facet; robust volume: its most-inside tet kept).
TEST_CASE("closed mesh: a point handle and a bone tip 0.5% of the diagonal outside bind", "[volume]") {
  TriMesh m = dfm::test::icosphere(Eigen::Vector3d::Zero(), 1.0, 3);
  BindOptions opts = coarse();
  const bool robust = GENERATE(false, true);
  if (robust) opts.volume.robust = VolumeOptions::Robust::Always;
  else if (GENERATE(false, true)) m.F.col(1).swap(m.F.col(2));  // inside out: the glued tets face out all the same
  const double diag = diagonal(m);
  const std::vector<int> ext = extreme_vertices(m);
  Rig rig = point_rig(m, {ext[0], ext[2]});
  const Eigen::Vector3d out = m.V.row(ext[0]).transpose() * (1 + 0.005 * diag);  // radially outside
  rig.points[0].position = out;
  rig.skeleton.joints.resize(2, 3);
  rig.skeleton.joints.row(0) << 0, 0, 0;
  const Eigen::Vector3d tip = m.V.row(ext[1]).transpose() * (1 + 0.005 * diag);
  rig.skeleton.joints.row(1) = tip.transpose();
  rig.skeleton.bones.push_back({0, 1, -1, "arm"});
  const BindResult r = bind_surface(m, rig, opts);
  INFO([&] { std::string s; for (const auto& n : r.report.notes) s += n + "\n"; return s; }());
  const Eigen::MatrixXd& W = r.weights;
  REQUIRE(W.minCoeff() >= -1e-9);
  REQUIRE(W.maxCoeff() <= 1 + 1e-9);
  REQUIRE((W.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-6);
  const int p = constrained_row_at(r.volume, out, diag), t = constrained_row_at(r.volume, tip, diag);
  REQUIRE(p >= 0);
  REQUIRE(r.volume.bc(p, 0) == 1.0);
  REQUIRE(t >= 0);
  REQUIRE(r.volume.bc(t, 2) == 1.0);  // handle order: points, then bones
  // The volume is the (convex) sphere's, by the divergence theorem, plus the handles' slivers.
  double min_tet = 0;
  REQUIRE(dfm::test::tet_mesh_volume(r.volume.tets, &min_tet) ==
          Approx(std::abs(dfm::test::enclosed_volume(m.V, m.F))).epsilon(1e-3));
  REQUIRE(min_tet > 0);
  // A handle 10% outside is still refused by name.
  rig.points[0].position = m.V.row(ext[0]).transpose() * (1 + 0.1 * diag);
  REQUIRE_THROWS_WITH(bind_surface(m, rig, opts), Catch::Contains("point handle \"point 0\" lies outside the volume"));
}
