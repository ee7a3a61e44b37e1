// Mesh checks against hand-built cases and independent identities (volume of a tet mesh = volume
// enclosed by its boundary).
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <map>

#include "core/mesh/io.h"
#include "core/mesh/mesh_info.h"
#include "tests/test_support.h"

using namespace dfm;

// Unit cube [0,1]^3, 12 outward triangles.
static TriMesh cube(Eigen::Vector3d offset = Eigen::Vector3d::Zero()) {
  TriMesh m;
  m.V.resize(8, 3);
  for (int i = 0; i < 8; ++i) m.V.row(i) << (i & 1), (i >> 1) & 1, (i >> 2) & 1;
  m.V.rowwise() += offset.transpose();
  m.F.resize(12, 3);
  m.F << 0, 2, 1, 1, 2, 3,  // z = 0 (normal -z)
      4, 5, 6, 5, 7, 6,     // z = 1
      0, 1, 4, 1, 5, 4,     // y = 0
      2, 6, 3, 3, 6, 7,     // y = 1
      0, 4, 2, 2, 4, 6,     // x = 0
      1, 3, 5, 3, 7, 5;     // x = 1
  return m;
}

static TriMesh join(const TriMesh& a, const TriMesh& b) {
  TriMesh m;
  m.V.resize(a.V.rows() + b.V.rows(), 3);
  m.V << a.V, b.V;
  m.F.resize(a.F.rows() + b.F.rows(), 3);
  m.F << a.F, (b.F.array() + a.V.rows()).matrix();
  return m;
}

TEST_CASE("closed cube: volume 1, no boundary, one component", "[mesh_info]") {
  TriMesh c = cube(Eigen::Vector3d(5, -3, 2));  // volume must not depend on the position
  REQUIRE(is_closed(c.F));
  REQUIRE(boundary_edge_count(c.F) == 0);
  REQUIRE(non_manifold_edge_count(c.F) == 0);
  REQUIRE(inconsistent_edge_count(c.F) == 0);
  REQUIRE(connected_component_count(c.F) == 1);
  REQUIRE(signed_volume(c.V, c.F) == Approx(1.0));
  BoundingBox b = bounding_box(c.V);
  REQUIRE(b.min == Eigen::Vector3d(5, -3, 2));
  REQUIRE(b.max == Eigen::Vector3d(6, -2, 3));
  // Inside out: negative volume.
  TriMesh f = c;
  f.F.col(1).swap(f.F.col(2));
  REQUIRE(signed_volume(f.V, f.F) == Approx(-1.0));
  REQUIRE(is_closed(f.F));
  // Back faces may be culled only when closed and outward.
  REQUIRE(is_closed_outward(c.V, c.F));
  REQUIRE_FALSE(is_closed_outward(f.V, f.F));
}

TEST_CASE("open, multi-piece, non-manifold and inconsistent meshes", "[mesh_info]") {
  TriMesh open = cube();
  open.F.conservativeResize(10, 3);  // drop the x = 1 side: a square hole
  REQUIRE(boundary_edge_count(open.F) == 4);
  REQUIRE_FALSE(is_closed(open.F));
  REQUIRE(signed_volume(open.V, open.F) > 0);  // the open box still reads as positive...
  REQUIRE_FALSE(is_closed_outward(open.V, open.F));  // ...but its inside shows through the hole

  TriMesh two = join(cube(), cube(Eigen::Vector3d(3, 0, 0)));
  REQUIRE(connected_component_count(two.F) == 2);
  Eigen::VectorXi comp = face_components(two.F);
  REQUIRE(comp.head(12).minCoeff() == comp.head(12).maxCoeff());
  REQUIRE(comp(0) != comp(12));
  REQUIRE(signed_volume(two.V, two.F) == Approx(2.0));

  // Three triangles on one edge (0,1): one non-manifold edge, 6 boundary edges.
  Eigen::MatrixXi fan(3, 3);
  fan << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  REQUIRE(non_manifold_edge_count(fan) == 1);
  REQUIRE(boundary_edge_count(fan) == 6);
  REQUIRE_FALSE(is_closed(fan));

  // One face flipped: its three edges are traversed twice in the same direction.
  TriMesh bad = cube();
  std::swap(bad.F(0, 1), bad.F(0, 2));
  REQUIRE(inconsistent_edge_count(bad.F) == 3);
  REQUIRE_FALSE(is_closed(bad.F));
  REQUIRE(is_closed(Eigen::MatrixXi()) == false);

  // Every face doubled (two sheets on one surface): each edge has four faces.
  Eigen::MatrixXi doubled(24, 3);
  doubled << cube().F, cube().F;
  REQUIRE(non_manifold_edge_count(doubled) == 18);
  REQUIRE_FALSE(is_closed(doubled));
  // A closed cube plus a face with a repeated vertex, and the two sides of one triangle (a closed,
  // flat pair): is_closed agrees with the edge counts.
  TriMesh degenerate = cube();
  degenerate.F.conservativeResize(13, 3);
  degenerate.F.row(12) << 0, 0, 1;
  REQUIRE_FALSE(is_closed(degenerate.F));
  Eigen::MatrixXi pair(2, 3);
  pair << 0, 1, 2, 0, 2, 1;
  REQUIRE(is_closed(pair));
  REQUIRE(boundary_edge_count(pair) + non_manifold_edge_count(pair) + inconsistent_edge_count(pair) == 0);
}

TEST_CASE("duplicate vertices, degenerate faces, unreferenced vertices", "[mesh_info]") {
  Eigen::MatrixXd V(5, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 0, 0, 1, 1e-9, 0, 2, 0, 0;
  REQUIRE(duplicate_vertex_count(V) == 1);         // exact copy of vertex 0
  REQUIRE(duplicate_vertex_count(V, 1e-6) == 2);   // and vertex 3 near vertex 1
  REQUIRE(duplicate_vertex_count(V, 1e-12) == 1);
  Eigen::MatrixXi F(3, 3);
  F << 0, 1, 3, 0, 0, 1, 0, 1, 4;  // sliver, repeated index, collinear
  REQUIRE(degenerate_face_count(V, F, 1e-14) == 2);
  REQUIRE(degenerate_face_count(V, F, 1e-6) == 3);
  REQUIRE(unreferenced_vertex_count(5, F) == 1);  // vertex 2
  // Fuzz regression: coordinates far beyond tol * 2^63 once overflowed the grid cell cast.
  Eigen::MatrixXd H(3, 3);
  H << 2e37, 0, 0, 2e37, 0, 0, -3e38, 1, 1;
  REQUIRE(duplicate_vertex_count(H, 1e-3) == 1);
}

TEST_CASE("tet boundary: one tet, and hand.mesh volume = volume inside its boundary", "[mesh_info]") {
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  Eigen::MatrixXi T(1, 4);
  T << 0, 1, 2, 3;
  Eigen::MatrixXi B = tet_boundary_faces(T);
  REQUIRE(B.rows() == 4);
  REQUIRE(is_closed(B));
  REQUIRE(signed_volume(V, B) == Approx(1.0 / 6));
  REQUIRE(tet_mesh_volume(V, T) == Approx(1.0 / 6));

  DFM_DATA_OR_SKIP(path, "hand.mesh");
  TetMesh m = read_tet_mesh(path);
  REQUIRE(non_positive_tet_count(m.V, m.T) == 0);
  Eigen::MatrixXi HB = tet_boundary_faces(m.T);
  {  // Against a plain reference: faces seen once, in the order of their sorted vertex triples.
    static const int face[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    std::map<std::array<int, 3>, std::pair<int, std::array<int, 3>>> seen;
    for (int t = 0; t < m.T.rows(); ++t)
      for (auto& fc : face) {
        std::array<int, 3> f = {m.T(t, fc[0]), m.T(t, fc[1]), m.T(t, fc[2])}, k = f;
        std::sort(k.begin(), k.end());
        auto& e = seen[k];
        ++e.first;
        e.second = f;
      }
    int row = 0;
    for (const auto& [k, e] : seen)
      if (e.first == 1) {
        REQUIRE(row < HB.rows());
        REQUIRE(HB.row(row) == Eigen::RowVector3i(e.second[0], e.second[1], e.second[2]));
        ++row;
      }
    REQUIRE(row == HB.rows());
  }
  REQUIRE(is_closed(HB));
  REQUIRE(connected_component_count(HB) == 1);
  REQUIRE(signed_volume(m.V, HB) == Approx(tet_mesh_volume(m.V, m.T)).epsilon(1e-9));
}

TEST_CASE("shared data: closed and open surfaces as the README says", "[mesh_info][data]") {
  for (const char* name : {"decimated-knight.off", "arm.obj", "bunny.off"}) {
    DFM_DATA_OR_SKIP(path, name);
    TriMesh m = read_surface(path);
    INFO(name);
    REQUIRE(boundary_edge_count(m.F) == 0);
    REQUIRE(signed_volume(m.V, m.F) > 0);
  }
  for (const char* name : {"camelhead.off", "beetle.off"}) {
    DFM_DATA_OR_SKIP(path, name);
    TriMesh m = read_surface(path);
    INFO(name);
    REQUIRE(boundary_edge_count(m.F) > 0);
    REQUIRE_FALSE(is_closed(m.F));
  }
}
