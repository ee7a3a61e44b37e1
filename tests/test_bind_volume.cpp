// The bind volume: handles inside the tet mesh, boundary conditions, surface order, cages, tet-mesh
// input, and the robust (winding number) volume on messy surfaces.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <random>

#include "core/bind/bind_volume.h"
#include "core/bind/robust_volume.h"
#include "core/bind/winding_bvh.h"
#include "core/mesh/io.h"
#include "core/rig/rig_io.h"
#include "core/util/error.h"
#include "tests/test_support.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;
using dfm::test::box_mesh;
using dfm::test::enclosed_volume;
using dfm::test::icosphere;
using dfm::test::tet_mesh_volume;

namespace {

// Invariants every bind volume must satisfy.
void check_volume(const BindVolume& v, const Rig& rig, int user_vertices) {
  const int nh = num_handles(rig);
  double min_vol;
  tet_mesh_volume(v.tets, &min_vol);
  REQUIRE(min_vol > 0);
  REQUIRE(v.b.size() == v.bc.rows());
  REQUIRE(v.bc.cols() == nh);
  for (int i = 0; i < v.b.size(); ++i) {
    REQUIRE(v.b(i) >= 0);
    REQUIRE(v.b(i) < v.tets.V.rows());
    if (i) REQUIRE(v.b(i) > v.b(i - 1));
  }
  if (v.bc.size()) {
    REQUIRE(v.bc.minCoeff() >= 0);
    REQUIRE(v.bc.maxCoeff() <= 1);
    REQUIRE((v.bc.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-12);
  }
  // Every handle constrains something, and every tet vertex is used.
  for (int h = 0; h < nh; ++h) REQUIRE(v.bc.col(h).maxCoeff() > 0);
  std::vector<char> used(v.tets.V.rows(), 0);
  for (int t = 0; t < v.tets.T.rows(); ++t)
    for (int k = 0; k < 4; ++k) used[v.tets.T(t, k)] = 1;
  for (char u : used) REQUIRE(u);
  REQUIRE(v.to_user.rows() == user_vertices);
  REQUIRE(v.to_user.cols() == v.tets.V.rows());
  Eigen::VectorXd rs = v.to_user * Eigen::VectorXd::Ones(v.tets.V.rows());
  REQUIRE((rs.array() - 1).abs().maxCoeff() < 1e-12);
}

// The handle's own rows: exactly one vertex, at its position, weight 1.
void check_point_handle(const BindVolume& v, int h, const Eigen::Vector3d& x) {
  int n = 0;
  for (int i = 0; i < v.b.size(); ++i)
    if (v.bc(i, h) > 0) {
      ++n;
      REQUIRE(v.bc(i, h) == 1.0);
      REQUIRE((v.tets.V.row(v.b(i)).transpose() - x).norm() == 0.0);
    }
  REQUIRE(n == 1);
}

// A cage vertex: weight 1 exactly at its own position; elsewhere (its facets) less than 1.
void check_cage_vertex(const BindVolume& v, int h, const Eigen::Vector3d& x) {
  int own = 0;
  for (int i = 0; i < v.b.size(); ++i) {
    const bool here = (v.tets.V.row(v.b(i)).transpose() - x).norm() == 0.0;
    if (here) {
      REQUIRE(v.bc(i, h) == 1.0);
      ++own;
    } else {
      REQUIRE(v.bc(i, h) < 1.0);
    }
  }
  REQUIRE(own == 1);
}

bool is_identity_prefix(const Eigen::SparseMatrix<double>& S) {
  if (S.nonZeros() != S.rows()) return false;
  for (int k = 0; k < S.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(S, k); it; ++it)
      if (it.row() != it.col() || it.value() != 1.0) return false;
  return true;
}

bool note_contains(const BindVolume& v, const std::string& s) {
  for (const auto& n : v.notes)
    if (n.find(s) != std::string::npos) return true;
  return false;
}

std::string all_notes(const BindVolume& v) {
  std::string s;
  for (const auto& n : v.notes) s += n + "\n";
  return s;
}

}  // namespace

TEST_CASE("knight + point handles (at vertices and inside): one tet vertex each, surface first", "[volume][data]") {
  DFM_DATA_OR_SKIP(path, "decimated-knight.off");
  TriMesh m = read_surface(path);
  Rig rig;
  for (int i : {0, 100, 300}) rig.points.push_back({m.V.row(i).transpose(), "v" + std::to_string(i)});
  // Two interior points that are not vertices, picked by the winding number (independent of TetGen).
  WindingTree tree = build_winding_tree(m.V, m.F);
  std::mt19937 rng(5);
  const Eigen::RowVector3d lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
  std::uniform_real_distribution<double> u(0, 1);
  while (rig.points.size() < 5) {
    Eigen::Vector3d p = (lo + Eigen::RowVector3d(u(rng), u(rng), u(rng)).cwiseProduct(hi - lo)).transpose();
    if (winding_number(tree, p) > 0.99) rig.points.push_back({p, "inner"});
  }
  BindVolume v = build_bind_volume(m, rig);
  INFO(all_notes(v));
  check_volume(v, rig, m.num_vertices());
  REQUIRE(v.tets.V.topRows(m.V.rows()) == m.V);
  REQUIRE(is_identity_prefix(v.to_user));
  REQUIRE(v.b.size() == 5);
  for (int h = 0; h < 5; ++h) check_point_handle(v, h, rig.points[h].position);
  REQUIRE(tet_mesh_volume(v.tets) == Approx(std::abs(enclosed_volume(m.V, m.F))).epsilon(1e-9));
  REQUIRE(v.tets.F.rows() == m.F.rows());  // boundary of the volume = the surface (Y)
  REQUIRE_FALSE(note_contains(v, "robust"));

  rig.points.push_back({(hi + (hi - lo)).transpose(), "far away"});
  try {
    build_bind_volume(m, rig);
    FAIL("a handle outside the surface must be refused");
  } catch (const Error& e) {
    REQUIRE(std::string(e.what()).find("far away") != std::string::npos);
  }
}

TEST_CASE("arm + arm.tgf: bone samples on their bones, shared joints split equally", "[volume][data]") {
  DFM_DATA_OR_SKIP(mesh_path, "arm.obj");
  DFM_DATA_OR_SKIP(tgf_path, "arm.tgf");
  TriMesh m = read_surface(mesh_path);
  Rig rig;
  add_tgf_to_rig(rig, read_tgf(tgf_path), tgf_path);
  REQUIRE(rig.skeleton.num_bones() == 4);
  BindVolume v = build_bind_volume(m, rig);
  INFO(all_notes(v));
  check_volume(v, rig, m.num_vertices());
  REQUIRE(v.tets.V.topRows(m.V.rows()) == m.V);
  REQUIRE(tet_mesh_volume(v.tets) == Approx(std::abs(enclosed_volume(m.V, m.F))).epsilon(1e-9));
  const double diag = (m.V.colwise().maxCoeff() - m.V.colwise().minCoeff()).norm();
  const int np = num_point_handles(rig);
  std::vector<int> samples(rig.skeleton.num_bones(), 0);
  for (int i = 0; i < v.b.size(); ++i) {
    const Eigen::Vector3d p = v.tets.V.row(v.b(i));
    int k = 0;
    for (int j = 0; j < rig.skeleton.num_bones(); ++j) {
      if (v.bc(i, np + j) == 0) continue;
      ++k;
      ++samples[j];
      const Eigen::Vector3d a = rig.skeleton.joints.row(rig.skeleton.bones[j].a);
      const Eigen::Vector3d b = rig.skeleton.joints.row(rig.skeleton.bones[j].b);
      const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      REQUIRE((a + t * (b - a) - p).norm() < 1e-12 * diag);  // on the segment
    }
    // A vertex on k bones (a shared joint) gets 1/k for each.
    for (int j = 0; j < rig.skeleton.num_bones(); ++j)
      if (v.bc(i, np + j) > 0) REQUIRE(v.bc(i, np + j) == Approx(1.0 / k).epsilon(1e-14));
  }
  int shared = 0;
  for (int i = 0; i < v.b.size(); ++i) shared += (v.bc.row(i).segment(np, 4).array() > 0).count() > 1;
  REQUIRE(shared >= 1);  // the arm's inner joints are inside it
  for (int j = 0; j < 4; ++j) REQUIRE(samples[j] >= 2);
}

TEST_CASE("closed cage around the knight: union domain, barycentric facet constraints", "[volume][data]") {
  DFM_DATA_OR_SKIP(path, "decimated-knight.off");
  TriMesh m = read_surface(path);
  const Eigen::Vector3d lo = m.V.colwise().minCoeff().transpose(), hi = m.V.colwise().maxCoeff().transpose();
  const Eigen::Vector3d pad = 0.2 * (hi - lo);
  Rig rig;
  rig.cages.push_back({box_mesh(lo - pad, hi + pad), {}, "box"});
  VolumeOptions opts;
  opts.tetgen_switches = "pq1.414a" + std::to_string((hi - lo).prod() / 2000);  // no Y: Steiner points on facets
  BindVolume v = build_bind_volume(m, rig, opts);
  INFO(all_notes(v));
  check_volume(v, rig, m.num_vertices());
  REQUIRE(v.tets.V.topRows(m.V.rows()) == m.V);
  REQUIRE(tet_mesh_volume(v.tets) == Approx((hi - lo + 2 * pad).prod()).epsilon(1e-9));
  for (int h = 0; h < 8; ++h) check_cage_vertex(v, h, rig.cages[0].mesh.V.row(h).transpose());
  REQUIRE(v.b.size() > 8);  // facet vertices besides the corners
  // Linear precision: the constraints reproduce each constrained vertex's position.
  const Eigen::MatrixXd recon = v.bc * rig.cages[0].mesh.V;
  for (int i = 0; i < v.b.size(); ++i)
    REQUIRE((recon.row(i) - v.tets.V.row(v.b(i))).norm() < 1e-9 * (hi - lo).norm());
}

TEST_CASE("open cage inside a box, plus a point handle off the vertices", "[volume]") {
  TriMesh box = box_mesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  Rig rig;
  rig.points.push_back({Eigen::Vector3d(0.5, 0.5, 0.15), "p"});
  Cage sheet;
  sheet.mesh.V.resize(5, 3);
  sheet.mesh.V << 0.25, 0.25, 0.5, 0.75, 0.25, 0.5, 0.75, 0.75, 0.5, 0.25, 0.75, 0.5, 0.5, 0.5, 0.85;
  sheet.mesh.F.resize(2, 3);
  sheet.mesh.F << 0, 1, 2, 0, 2, 3;
  sheet.edges.resize(1, 2);
  sheet.edges << 2, 4;  // a partial cage: an edge without faces
  sheet.name = "sheet";
  rig.cages.push_back(sheet);
  VolumeOptions opts;
  opts.tetgen_switches = "pq1.414a0.0005";
  BindVolume v = build_bind_volume(box, rig, opts);
  INFO(all_notes(v));
  check_volume(v, rig, 8);
  REQUIRE(tet_mesh_volume(v.tets) == Approx(1.0).epsilon(1e-12));
  check_point_handle(v, 0, rig.points[0].position);
  for (int h = 0; h < 5; ++h) check_cage_vertex(v, 1 + h, sheet.mesh.V.row(h).transpose());
  int on_sheet = 0;
  for (int i = 0; i < v.b.size(); ++i) {
    if (v.bc(i, 0) > 0) continue;
    ++on_sheet;
    const Eigen::RowVector3d recon = v.bc.row(i).tail(5) * sheet.mesh.V;
    REQUIRE((recon - v.tets.V.row(v.b(i))).norm() < 1e-12);
  }
  REQUIRE(on_sheet > 5);  // Steiner points on the sheet and the edge were constrained too
}

TEST_CASE("hand.mesh + hand.tgf used as given; missing handles are named", "[volume][data]") {
  DFM_DATA_OR_SKIP(mesh_path, "hand.mesh");
  DFM_DATA_OR_SKIP(tgf_path, "hand.tgf");
  TetMesh t = read_tet_mesh(mesh_path);
  Rig rig;
  add_tgf_to_rig(rig, read_tgf(tgf_path), tgf_path);
  REQUIRE(rig.skeleton.num_bones() == 20);
  BindVolume v = bind_volume_from_tets(t, rig);
  INFO(all_notes(v));
  check_volume(v, rig, t.num_vertices());
  REQUIRE(v.tets.V == t.V);
  REQUIRE(is_identity_prefix(v.to_user));
  const int np = num_point_handles(rig);
  for (int j = 0; j < 20; ++j) REQUIRE((v.bc.col(np + j).array() > 0).count() >= 2);

  Rig outside = rig;
  outside.points.push_back({Eigen::Vector3d(100, 100, 100), "nowhere"});
  try {
    bind_volume_from_tets(t, outside);
    FAIL();
  } catch (const Error& e) {
    REQUIRE(std::string(e.what()).find("\"nowhere\" lies outside") != std::string::npos);
  }
  Rig inner = rig;
  const Eigen::Vector3d c = 0.25 * (t.V.row(t.T(0, 0)) + t.V.row(t.T(0, 1)) + t.V.row(t.T(0, 2)) + t.V.row(t.T(0, 3))).transpose();
  inner.points.push_back({c, "between vertices"});
  try {
    bind_volume_from_tets(t, inner);
    FAIL();
  } catch (const Error& e) {
    REQUIRE(std::string(e.what()).find("\"between vertices\" is not a vertex") != std::string::npos);
  }
}

static void check_robust(const std::string& path) {
  TriMesh m = read_surface(path);
  Rig rig;
  for (int i : {0, m.num_vertices() / 2, m.num_vertices() - 1}) rig.points.push_back({m.V.row(i).transpose(), ""});
  VolumeOptions opts;
  opts.tetgen_switches = "pq2Y";  // coarser than the default: keeps the test quick on a shared machine
  BindVolume v = build_bind_volume(m, rig, opts);
  INFO(path << "\n" << all_notes(v));
  REQUIRE(note_contains(v, "boundary edges"));
  REQUIRE(note_contains(v, "robust volume"));
  check_volume(v, rig, m.num_vertices());
  for (int h = 0; h < 3; ++h) check_point_handle(v, h, rig.points[h].position);
  // Interpolation weights are convex and put every user vertex near where it is.
  const double diag = (m.V.colwise().maxCoeff() - m.V.colwise().minCoeff()).norm();
  for (int k = 0; k < v.to_user.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(v.to_user, k); it; ++it) REQUIRE(it.value() >= 0);
  const Eigen::MatrixXd moved = v.to_user * v.tets.V;
  REQUIRE((moved - m.V).rowwise().norm().maxCoeff() < 0.05 * diag);
}

// [heavy]: release only; under the sanitizers the robust volume of an open surface runs in
// test_messy_handles (open sphere with a hole; camelhead) and in the lighter robust cases below.
TEST_CASE("open surfaces (beetle, camelhead) bind through the robust volume", "[volume][robust][data][heavy]") {
  DFM_DATA_OR_SKIP(beetle, "beetle.off");
  check_robust(beetle);
  DFM_DATA_OR_SKIP(camel, "camelhead.off");
  check_robust(camel);
}

TEST_CASE("two overlapping spheres: TetGen refuses, the robust volume is their union", "[volume][robust]") {
  TriMesh s = dfm::test::concat(icosphere(Eigen::Vector3d(0, 0, 0), 1.0, 3), icosphere(Eigen::Vector3d(1, 0, 0), 1.0, 3));
  Rig rig;
  rig.points.push_back({Eigen::Vector3d(-0.5, 0, 0), "left"});
  rig.points.push_back({Eigen::Vector3d(1.5, 0, 0), "right"});
  BindVolume v = build_bind_volume(s, rig);
  INFO(all_notes(v));
  REQUIRE(note_contains(v, "TetGen failed"));
  check_volume(v, rig, s.num_vertices());
  // Union of two unit balls 1 apart: 2 (4/3 pi) - pi (4 + 1)(2 - 1)^2 / 12.
  const double expect = 8.0 * M_PI / 3.0 - 5.0 * M_PI / 12.0;
  REQUIRE(tet_mesh_volume(v.tets) == Approx(expect).epsilon(0.05));
  VolumeOptions never;
  never.robust = VolumeOptions::Robust::Never;
  REQUIRE_THROWS_AS(build_bind_volume(s, rig, never), Error);
}

TEST_CASE("a quad mesh (triangulated on reading) binds like any closed surface", "[volume]") {
  const std::string path = (std::filesystem::temp_directory_path() / "dfm_volume_quad_cube.obj").string();
  {
    std::ofstream f(path);
    f << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
         "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
  }
  TriMesh m = read_surface(path);
  std::filesystem::remove(path);
  REQUIRE(m.num_faces() == 12);
  Rig rig;
  rig.points.push_back({Eigen::Vector3d(0.5, 0.5, 0.5), "centre"});
  rig.regions.push_back({{0, 1, 2, 3}, "floor"});
  BindVolume v = build_bind_volume(m, rig);
  INFO(all_notes(v));
  check_volume(v, rig, 8);
  REQUIRE_FALSE(note_contains(v, "robust"));
  REQUIRE(tet_mesh_volume(v.tets) == Approx(1.0).epsilon(1e-12));
  for (int u = 0; u < 4; ++u) {  // the region's vertices are its own
    int row = -1;
    for (int i = 0; i < v.b.size(); ++i)
      if (v.b(i) == u) row = i;
    REQUIRE(row >= 0);
    REQUIRE(v.bc(row, 1) == 1.0);
  }
}

TEST_CASE("many disconnected pieces: handle-less pieces follow their nearest handle", "[volume]") {
  TriMesh all;
  for (int i = 0; i < 8; ++i) {
    TriMesh s = icosphere(Eigen::Vector3d(3.0 * i, 0, 0), 1.0, 2);
    all = i == 0 ? s : dfm::test::concat(all, s);
  }
  Rig rig;
  rig.points.push_back({Eigen::Vector3d(0, 0, 0), "first"});
  rig.points.push_back({Eigen::Vector3d(21, 0, 0), "last"});
  for (auto mode : {VolumeOptions::Robust::Auto, VolumeOptions::Robust::Always}) {
    VolumeOptions opts;
    opts.robust = mode;
    BindVolume v = build_bind_volume(all, rig, opts);
    INFO(all_notes(v));
    check_volume(v, rig, all.num_vertices());
    REQUIRE(note_contains(v, "6 of 8 pieces of the volume have no handle"));
    // Every vertex of a piece without a handle is constrained (so no weight is undetermined).
    Eigen::VectorXi comp;
    REQUIRE(tet_vertex_components(v.tets, comp) == 8);
    std::vector<int> constrained(8, 0), size(8, 0);
    for (int i = 0; i < comp.size(); ++i) ++size[comp(i)];
    for (int i = 0; i < v.b.size(); ++i) ++constrained[comp(v.b(i))];
    int full = 0;
    for (int c = 0; c < 8; ++c) full += constrained[c] == size[c];
    REQUIRE(full == 6);
    if (mode == VolumeOptions::Robust::Auto)
      REQUIRE(tet_mesh_volume(v.tets) == Approx(8 * enclosed_volume(icosphere({0, 0, 0}, 1, 2).V, icosphere({0, 0, 0}, 1, 2).F)).epsilon(1e-9));
  }
}

TEST_CASE("robust volume of a closed surface approximates its volume", "[volume][robust][data]") {
  DFM_DATA_OR_SKIP(path, "decimated-knight.off");
  TriMesh m = read_surface(path);
  Rig rig;
  rig.points.push_back({m.V.row(10).transpose(), "a"});
  VolumeOptions opts;
  opts.robust = VolumeOptions::Robust::Always;
  BindVolume v = build_bind_volume(m, rig, opts);
  INFO(all_notes(v));
  check_volume(v, rig, m.num_vertices());
  check_point_handle(v, 0, rig.points[0].position);
  REQUIRE(tet_mesh_volume(v.tets) == Approx(std::abs(enclosed_volume(m.V, m.F))).epsilon(0.1));
}
