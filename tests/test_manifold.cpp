// Animation manifolds: build, the derived slice table, CPU slicing, the .tet4 file (core/anim).
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>

#include <unistd.h>

#include <catch2/catch.hpp>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include "core/anim/frame_sequence.h"
#include "core/anim/manifold.h"
#include "core/anim/manifold_frame.h"
#include "core/anim/manifold_io.h"
#include "core/anim/slice.h"
#include "core/anim/slice_table.h"
#include "core/anim/surface_checks.h"
#include "core/mesh/io.h"
#include "core/util/error.h"
#include "tests/test_support.h"

using namespace dfm;
namespace fs = std::filesystem;

namespace {

TriMesh unit_cube() {
  TriMesh m;
  m.V.resize(8, 3);
  m.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  m.F.resize(12, 3);
  m.F << 0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 3, 7, 6, 3, 6, 2, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5;
  return m;
}

Eigen::MatrixXd transformed(const Eigen::MatrixXd& V, const Eigen::Affine3d& a) {
  return ((a.linear() * V.transpose()).colwise() + a.translation()).transpose();
}

// <N, w> = det[w, e1, e2, e3]: the 4D normal of a tetrahedron, straight from the definition.
Eigen::Vector4d normal4(const AnimationManifold& M, int k) {
  Eigen::Matrix4d E;
  for (int c = 1; c < 4; ++c) E.col(c) = (M.V.row(M.T(k, c)) - M.V.row(M.T(k, 0))).transpose();
  Eigen::Vector4d N;
  for (int j = 0; j < 4; ++j) {
    E.col(0) = Eigen::Vector4d::Unit(j);
    N[j] = E.determinant();
  }
  return N;
}

double area(const TriMesh& m) {
  double a = 0;
  for (int f = 0; f < m.num_faces(); ++f) {
    const Eigen::Vector3d p0 = m.V.row(m.F(f, 0)), p1 = m.V.row(m.F(f, 1)), p2 = m.V.row(m.F(f, 2));
    a += 0.5 * (p1 - p0).cross(p2 - p0).norm();
  }
  return a;
}

// Same triangle up to a cyclic rotation of its corners (winding preserved).
bool same_cyclic(const Eigen::Vector3i& a, const Eigen::Vector3i& b) {
  for (int r = 0; r < 3; ++r)
    if (a[0] == b[r] && a[1] == b[(r + 1) % 3] && a[2] == b[(r + 2) % 3]) return true;
  return false;
}

// Checks every slice vertex is the linear interpolation of its manifold edge's endpoints.
void require_on_edges(const AnimationManifold& M, const ManifoldSlice& s, int axis, double c) {
  int keep[3], n = 0;
  for (int d = 0; d < 4; ++d)
    if (d != axis) keep[n++] = d;
  const double scale = M.V.cwiseAbs().maxCoeff();
  for (int v = 0; v < s.mesh.num_vertices(); ++v) {
    const auto [a, b] = s.edges[v];
    Eigen::Vector4d pa = M.V.row(a), pb = M.V.row(b), p;
    if (a == b) {
      REQUIRE(pa[axis] == c);
      p = pa;
    } else {
      REQUIRE((std::min(pa[axis], pb[axis]) <= c && c <= std::max(pa[axis], pb[axis])));
      const double lambda = (c - pa[axis]) / (pb[axis] - pa[axis]);
      p = (1 - lambda) * pa + lambda * pb;
    }
    for (int d = 0; d < 3; ++d) REQUIRE(std::abs(s.mesh.V(v, d) - p[keep[d]]) <= 1e-12 * scale);
  }
}

// A sweep slice (x, y or z) is oriented and closed except for its ends: its boundary edges all lie
// in the first or last time plane (display coordinate 2 is t). Returns its volume with those caps.
double sweep_volume(const AnimationManifold& M, const ManifoldSlice& s) {
  REQUIRE(is_oriented_manifold(s.mesh.F));
  const Eigen::MatrixXi E = boundary_edges(s.mesh.F);
  for (int e = 0; e < E.rows(); ++e)
    for (int j = 0; j < 2; ++j) {
      const double t = s.mesh.V(E(e, j), 2);
      REQUIRE((t == M.times.front() || t == M.times.back()));
    }
  const double v0 = flux_volume(s.mesh.V, s.mesh.F, 0), v1 = flux_volume(s.mesh.V, s.mesh.F, 1);
  REQUIRE(v0 == Approx(v1).epsilon(1e-9));  // two independent fluxes agree
  return v0;
}

}  // namespace

TEST_CASE("slice table: derived cases cut exactly the crossing edges, wound along grad f", "[manifold]") {
  const auto& table = slice_table();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int mask = 0; mask < 16; ++mask) {
    const int up = __builtin_popcount(mask);
    std::set<int> crossing, used;
    for (int e = 0; e < 6; ++e)
      if (((mask >> kSliceEdges[e][0]) & 1) != ((mask >> kSliceEdges[e][1]) & 1)) crossing.insert(e);
    const SliceCase& sc = table[mask];
    REQUIRE(sc.num_triangles == (up == 0 || up == 4 ? 0 : up == 2 ? 2 : 1));
    for (int t = 0; t < sc.num_triangles; ++t)
      for (int e : sc.triangles[t]) used.insert(e);
    REQUIRE(used == crossing);
    // Random positively oriented tetrahedra and values with this sign pattern: the triangles' vector
    // area equals the crossing polygon's, computed independently by sorting its points by angle.
    for (int trial = 0; trial < 20 && sc.num_triangles > 0; ++trial) {
      Eigen::Vector3d p[4];
      for (auto& q : p) q = Eigen::Vector3d(U(rng), U(rng), U(rng));
      if ((p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]) < 0) std::swap(p[2], p[3]);
      double f[4];
      for (int i = 0; i < 4; ++i) f[i] = ((mask >> i) & 1) ? 0.05 + std::abs(U(rng)) : -0.05 - std::abs(U(rng));
      Eigen::Matrix3d E;
      for (int c = 0; c < 3; ++c) E.col(c) = p[c + 1] - p[0];
      const Eigen::Vector3d grad = E.transpose().inverse() * Eigen::Vector3d(f[1] - f[0], f[2] - f[0], f[3] - f[0]);
      auto point = [&](int e) {
        const int a = kSliceEdges[e][0], b = kSliceEdges[e][1];
        return Eigen::Vector3d(p[a] + f[a] / (f[a] - f[b]) * (p[b] - p[a]));
      };
      Eigen::Vector3d tri_area = Eigen::Vector3d::Zero();
      for (int t = 0; t < sc.num_triangles; ++t) {
        const auto& tr = sc.triangles[t];
        const Eigen::Vector3d n = 0.5 * (point(tr[1]) - point(tr[0])).cross(point(tr[2]) - point(tr[0]));
        REQUIRE(n.dot(grad) > 0);
        tri_area += n;
      }
      std::vector<Eigen::Vector3d> poly;
      for (int e : crossing) poly.push_back(point(e));
      Eigen::Vector3d ctr = Eigen::Vector3d::Zero();
      for (auto& q : poly) ctr += q / poly.size();
      const Eigen::Vector3d ax = grad.normalized(), u = (poly[0] - ctr).normalized(), w = ax.cross(u);
      std::sort(poly.begin(), poly.end(), [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
        return std::atan2((a - ctr).dot(w), (a - ctr).dot(u)) < std::atan2((b - ctr).dot(w), (b - ctr).dot(u));
      });
      Eigen::Vector3d poly_area = Eigen::Vector3d::Zero();
      for (size_t i = 0; i < poly.size(); ++i) poly_area += 0.5 * poly[i].cross(poly[(i + 1) % poly.size()]);
      REQUIRE((tri_area - poly_area).norm() <= 1e-12);
    }
  }
}

TEST_CASE("manifold build: 3 l (m-1) tets, interior faces shared twice with opposite orientation", "[manifold]") {
  const TriMesh cube = unit_cube();
  REQUIRE(is_closed_and_oriented(cube.F));
  REQUIRE(enclosed_volume(cube.V, cube.F) == Approx(1.0));
  const Eigen::Affine3d move(Eigen::Translation3d(0.3, -0.2, 0.5) * Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY()));
  const std::vector<Eigen::MatrixXd> layers = {cube.V, transformed(cube.V, move), transformed(cube.V, move * move),
                                               cube.V};
  const AnimationManifold M = build_manifold(layers, cube.F, {0.0, 0.5, 2.0, 2.5});
  const int l = cube.num_faces(), m = 4, n = cube.num_vertices();
  REQUIRE(M.num_tets() == 3 * l * (m - 1));
  REQUIRE(M.num_vertices() == n * m);
  REQUIRE(M.slab_offsets == std::vector<int>{0, 3 * l, 6 * l, 9 * l});
  REQUIRE_NOTHROW(validate_manifold(M));

  // Faces of a tetrahedron with their induced orientation; the key is the sorted triple and the
  // value the accumulated orientation signs and count.
  std::map<std::array<int, 3>, std::pair<int, int>> faces;
  static const int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  for (int k = 0; k < M.num_tets(); ++k) {
    for (auto& fc : kFace) {
      std::array<int, 3> f = {M.T(k, fc[0]), M.T(k, fc[1]), M.T(k, fc[2])};
      int parity = 0;  // bubble sort, counting swaps
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 2 - i; ++j)
          if (f[j] > f[j + 1]) std::swap(f[j], f[j + 1]), parity ^= 1;
      auto& e = faces[f];
      e.first += parity ? -1 : 1;
      e.second += 1;
    }
  }
  std::set<std::array<int, 3>> boundary;
  for (auto& [f, e] : faces) {
    REQUIRE(e.second <= 2);
    if (e.second == 2)
      REQUIRE(e.first == 0);  // opposite orientations: consistently oriented
    else
      boundary.insert(f);
  }
  std::set<std::array<int, 3>> expected;
  for (int f = 0; f < l; ++f)
    for (int layer : {0, m - 1}) {
      std::array<int, 3> t = {cube.F(f, 0) + layer * n, cube.F(f, 1) + layer * n, cube.F(f, 2) + layer * n};
      std::sort(t.begin(), t.end());
      expected.insert(t);
    }
  REQUIRE(boundary == expected);

  // Static layers: every tetrahedron's 4D normal points out of the cube (and has no t part).
  const AnimationManifold S = build_manifold(std::vector<Eigen::MatrixXd>{cube.V, cube.V, cube.V}, cube.F, {0, 1, 2});
  for (int k = 0; k < S.num_tets(); ++k) {
    const Eigen::Vector4d N = normal4(S, k);
    Eigen::Vector3d ctr = Eigen::Vector3d::Zero();
    for (int c = 0; c < 4; ++c) ctr += S.V.row(S.T(k, c)).head<3>().transpose() / 4;
    REQUIRE(N.head<3>().dot(ctr - Eigen::Vector3d(0.5, 0.5, 0.5)) > 0);
    REQUIRE(N[3] == 0.0);
  }

  // Shared quads get the same diagonal: the cube's 18 edges each have one diagonal per slab.
  REQUIRE_THROWS_AS(build_manifold(std::vector<Eigen::MatrixXd>{cube.V}, cube.F, {0}), Error);
  REQUIRE_THROWS_AS(build_manifold(layers, cube.F, {0, 1, 1, 2}), Error);
  Eigen::MatrixXi bad = cube.F;
  bad(3, 1) = 99;
  REQUIRE_THROWS_AS(build_manifold(layers, bad, {0, 1, 2, 3}), Error);
}

TEST_CASE("slices of a moving cube: exact volumes on every axis, keys reproduced", "[manifold]") {
  const TriMesh cube = unit_cube();
  // The cube slides +1 in x from t = 0 to t = 1, then stretches x by 2 until t = 3.
  Eigen::MatrixXd V1 = cube.V, V2 = cube.V;
  V1.col(0).array() += 1.0;
  V2.col(0) = 2.0 * cube.V.col(0);
  V2.col(0).array() += 1.0;
  const AnimationManifold M = build_manifold(std::vector<Eigen::MatrixXd>{cube.V, V1, V2}, cube.F, {0, 1, 3});

  for (double t : {0.1, 0.5, 0.99, 1.5, 2.9}) {
    const ManifoldSlice s = slice_manifold(M, SliceAxis::T, t);
    REQUIRE(is_closed_and_oriented(s.mesh.F));
    const double sx = t <= 1 ? 1.0 : 1.0 + (t - 1) / 2;
    REQUIRE(enclosed_volume(s.mesh.V, s.mesh.F) == Approx(sx).epsilon(1e-12));
    require_on_edges(M, s, 3, t);
  }
  // Sweep views: the solid {(y, z, t) : x = c inside the cube at time t} has a known volume.
  // x = 1.5: inside for t in [0.5, 3] -> unit square x 2.5. x = 0.5: t in [0, 0.5] -> 0.5.
  struct Case {
    SliceAxis axis;
    double at, volume;
  };
  for (const Case& c : {Case{SliceAxis::X, 1.5, 2.5}, Case{SliceAxis::X, 0.5, 0.5}, Case{SliceAxis::Y, 0.3, 0.0},
                        Case{SliceAxis::Z, 0.7, 0.0}}) {
    const ManifoldSlice s = slice_manifold(M, c.axis, c.at);
    INFO("axis " << slice_axis_name(c.axis) << " at " << c.at);
    // y and z sections: the cube's x-extent (width 1, 1, then 1..2 over t in [1,3]) integrated over t:
    // 1 + 1 + (1+2)/2*2 = 4.
    const double expect = c.volume > 0 ? c.volume : 4.0;
    REQUIRE(sweep_volume(M, s) == Approx(expect).epsilon(1e-12));
    require_on_edges(M, s, static_cast<int>(c.axis), c.at);
  }

  // Slices at the layer times are the layers exactly: same vertex order, same bits.
  const std::vector<Eigen::MatrixXd> layers = {cube.V, V1, V2};
  for (int i = 0; i < 3; ++i) {
    const ManifoldSlice s = slice_manifold(M, SliceAxis::T, M.times[i]);
    REQUIRE(s.mesh.V == layers[i]);
    REQUIRE(s.mesh.num_faces() == cube.num_faces());
    for (int f = 0; f < cube.num_faces(); ++f) {
      bool found = false;
      for (int g = 0; g < s.mesh.num_faces() && !found; ++g)
        found = same_cyclic(cube.F.row(f).transpose(), s.mesh.F.row(g).transpose());
      REQUIRE(found);
    }
  }
  // Outside the animation: nothing.
  REQUIRE(slice_manifold(M, SliceAxis::T, 3.5).mesh.num_faces() == 0);
  REQUIRE(slice_manifold(M, SliceAxis::T, -0.5).mesh.num_faces() == 0);
  REQUIRE(slice_tet_range(M, SliceAxis::T, 0.5) == std::pair<int, int>{0, 36});
  REQUIRE(slice_tet_range(M, SliceAxis::T, 1.0) == std::pair<int, int>{0, 72});
  REQUIRE(slice_tet_range(M, SliceAxis::X, 1.0) == std::pair<int, int>{0, 72});
  REQUIRE(parse_slice_axis("X") == SliceAxis::X);
  REQUIRE_THROWS_AS(parse_slice_axis("w"), Error);
}

TEST_CASE("arm: identical keys slice to the keyframe, moving keys to closed positive solids", "[manifold]") {
  DFM_DATA_OR_SKIP(path, "arm.obj");
  const TriMesh arm = read_surface(path);
  REQUIRE(is_closed_and_oriented(arm.F));
  const double vol = enclosed_volume(arm.V, arm.F);
  REQUIRE(vol > 0);

  SECTION("identical keyframes") {
    const AnimationManifold M =
        build_manifold(std::vector<Eigen::MatrixXd>{arm.V, arm.V, arm.V}, arm.F, {0.0, 1.0, 2.0});
    const int n = arm.num_vertices();
    std::set<std::pair<int, int>> mesh_edges;
    for (int f = 0; f < arm.num_faces(); ++f)
      for (int j = 0; j < 3; ++j) {
        const int a = arm.F(f, j), b = arm.F(f, (j + 1) % 3);
        mesh_edges.insert({std::min(a, b), std::max(a, b)});
      }
    for (double t : {0.25, 0.5, 1.0 - 1e-9, 1.7}) {
      const ManifoldSlice s = slice_manifold(M, SliceAxis::T, t);
      REQUIRE(is_closed_and_oriented(s.mesh.F));
      REQUIRE(enclosed_volume(s.mesh.V, s.mesh.F) == Approx(vol).epsilon(1e-12));
      REQUIRE(area(s.mesh) == Approx(area(arm)).epsilon(1e-12));
      // Hausdorff 0: every slice vertex lies on a keyframe vertex or keyframe edge segment; with
      // the same area and closedness the slice covers the keyframe.
      for (int v = 0; v < s.mesh.num_vertices(); ++v) {
        const int a = s.edges[v][0] % n, b = s.edges[v][1] % n;
        const Eigen::Vector3d p = s.mesh.V.row(v);
        if (a == b) {
          REQUIRE(p == arm.V.row(a).transpose());
          continue;
        }
        REQUIRE(mesh_edges.count({std::min(a, b), std::max(a, b)}) == 1);
        const Eigen::Vector3d pa = arm.V.row(a), pb = arm.V.row(b);
        const double u = (p - pa).dot(pb - pa) / (pb - pa).squaredNorm();
        REQUIRE((u >= -1e-12 && u <= 1 + 1e-12));
        REQUIRE((pa + u * (pb - pa) - p).norm() <= 1e-12 * (pb - pa).norm());
      }
    }
  }

  SECTION("moving keyframes: rigid turn, then a stretch") {
    const Eigen::Vector3d ctr = arm.V.colwise().mean();
    const Eigen::Affine3d turn(Eigen::Translation3d(ctr + Eigen::Vector3d(0.1, 0.05, 0)) *
                               Eigen::AngleAxisd(0.8, Eigen::Vector3d(0.2, 0.3, 1).normalized()) *
                               Eigen::Translation3d(-ctr));
    Eigen::Affine3d stretch = Eigen::Affine3d::Identity();
    stretch.linear() = Eigen::Vector3d(1.3, 0.8, 1.1).asDiagonal();
    const std::vector<Eigen::MatrixXd> keys = {arm.V, transformed(arm.V, turn), transformed(arm.V, stretch * turn)};
    const AnimationManifold M = build_manifold(keys, arm.F, {0.0, 1.0, 2.5});
    for (double t : {0.05, 0.3, 0.5, 0.77, 1.2, 1.9, 2.45}) {
      const ManifoldSlice s = slice_manifold(M, SliceAxis::T, t);
      INFO("t = " << t);
      REQUIRE(is_closed_and_oriented(s.mesh.F));
      REQUIRE(enclosed_volume(s.mesh.V, s.mesh.F) > 0.5 * vol);
      require_on_edges(M, s, 3, t);
    }
    for (int i = 0; i < 3; ++i) {
      const ManifoldSlice s = slice_manifold(M, SliceAxis::T, M.times[i]);
      REQUIRE(s.mesh.V == keys[i]);
      REQUIRE(s.mesh.num_faces() == arm.num_faces());
      for (int f = 0; f < arm.num_faces(); f += 97) {
        bool found = false;
        for (int g = 0; g < s.mesh.num_faces() && !found; ++g)
          found = same_cyclic(arm.F.row(f).transpose(), s.mesh.F.row(g).transpose());
        REQUIRE(found);
      }
    }
    // Sweep views through the middle of the arm's bounding box on each spatial axis.
    for (int axis = 0; axis < 3; ++axis) {
      const double c = 0.5 * (arm.V.col(axis).minCoeff() + arm.V.col(axis).maxCoeff()) + 1e-4;
      const ManifoldSlice s = slice_manifold(M, static_cast<SliceAxis>(axis), c);
      INFO("axis " << axis);
      REQUIRE(s.mesh.num_faces() > 0);
      REQUIRE(sweep_volume(M, s) > 0);
      require_on_edges(M, s, axis, c);
    }
  }
}

TEST_CASE("welded_slice_vertex_count: the slice's own vertex count, without building it", "[manifold]") {
  const TriMesh cube = unit_cube();
  Eigen::MatrixXd V1 = cube.V, V2 = cube.V;
  V1.col(0).array() += 1.0;
  V2.col(0) = 2.0 * cube.V.col(0);
  const AnimationManifold M = build_manifold(std::vector<Eigen::MatrixXd>{cube.V, V1, V2}, cube.F, {0, 1, 3});
  // At a layer's time the slice is the layer: the cube's 8 corners.
  for (double t : {0.0, 1.0, 3.0}) REQUIRE(welded_slice_vertex_count(M, SliceAxis::T, t) == 8);
  REQUIRE(welded_slice_vertex_count(M, SliceAxis::T, 3.5) == 0);  // outside the animation
  for (SliceAxis axis : {SliceAxis::T, SliceAxis::X, SliceAxis::Y, SliceAxis::Z})
    for (double c : {0.1, 0.5, 0.99, 1.5, 2.9}) {
      const ManifoldSlice s = slice_manifold(M, axis, c);
      INFO("axis " << slice_axis_name(axis) << " at " << c);
      REQUIRE(welded_slice_vertex_count(M, axis, c) == s.mesh.num_vertices());
      // Welded: no two of the slice's vertices lie on one manifold edge.
      std::set<std::array<int, 2>> edges(s.edges.begin(), s.edges.end());
      REQUIRE(static_cast<int>(edges.size()) == s.mesh.num_vertices());
    }
}

TEST_CASE("tet4 files round-trip exactly and reject malformed input with a line number", "[manifold]") {
  const TriMesh cube = unit_cube();
  Eigen::MatrixXd V1 = cube.V * 1.1;
  V1.col(2).array() += 0.1;
  const AnimationManifold M =
      build_manifold(std::vector<Eigen::MatrixXd>{cube.V, V1, cube.V / 3.0}, cube.F, {0.1, 0.7, 1.0 / 3 + 1});
  const fs::path dir = fs::temp_directory_path() / "dfm_test_manifold";
  fs::create_directories(dir);
  const std::string p = (dir / "m.tet4").string();
  write_manifold(p, M);
  const AnimationManifold R = read_manifold(p);
  REQUIRE(R.V == M.V);
  REQUIRE(R.T == M.T);
  REQUIRE(R.times == M.times);
  REQUIRE(R.slab_offsets == M.slab_offsets);
  // The prism build's layers (version 2's closing sections) come back too.
  REQUIRE(R.layer_faces.size() == 1);
  REQUIRE(R.layer_faces[0] == cube.F);
  REQUIRE(R.prism_slabs.size() == 2);
  CHECK(R.prism_slabs[1].lower == 8);
  CHECK(R.prism_slabs[1].upper == 16);
  CHECK(R.prism_slabs[1].count == 8);

  std::ifstream in(p);
  std::vector<std::string> lines;
  for (std::string s; std::getline(in, s);) lines.push_back(s);
  auto write_with = [&](int line, const std::string& text) {
    std::vector<std::string> l = lines;
    if (line < 0)
      l.resize(l.size() + line);
    else
      l[line] = text;
    const std::string q = (dir / "bad.tet4").string();
    std::ofstream out(q);
    for (auto& s : l) out << s << "\n";
    return q;
  };
  // lines: 0 header, 1 comment, 2 vertices, 3 tets, 4 layers, 5..7 layer, 8.. vertices, then tets,
  // then the surfaces and prisms sections.
  int last_tet = 0;
  for (int i = 0; i < static_cast<int>(lines.size()); ++i)
    if (lines[i].rfind("t ", 0) == 0) last_tet = i;
  int last = 0;  // the last slab's prism line (a "keys 0" line follows: a prism build has no key layer)
  for (int i = 0; i < static_cast<int>(lines.size()); ++i)
    if (lines[i].rfind("prism ", 0) == 0) last = i;
  REQUIRE(lines.back() == "keys 0");
  REQUIRE_THROWS_WITH(read_manifold(write_with(0, "tet5 1")), Catch::Contains("bad.tet4:1") && Catch::Contains("tet4"));
  REQUIRE_THROWS_WITH(read_manifold(write_with(6, "layer 0.05 36")), Catch::Contains("increasing"));
  REQUIRE_THROWS_WITH(read_manifold(write_with(9, "v 1 2 zz 0.1")), Catch::Contains("bad.tet4:10"));
  REQUIRE_THROWS_WITH(read_manifold(write_with(last_tet, "t 0 1 2 999")), Catch::Contains("outside"));
  REQUIRE_THROWS_WITH(read_manifold(write_with(-3, "")), Catch::Contains("end of file"));
  // A prism slab whose layer is not at its times, or whose triangle list does not exist.
  REQUIRE_THROWS_WITH(read_manifold(write_with(last, "prism 0 0 16 8")),
                      Catch::Contains("prism slab 1") && Catch::Contains("times"));
  REQUIRE_THROWS_WITH(read_manifold(write_with(last, "prism 3 8 16 8")), Catch::Contains("bad.tet4:" + std::to_string(last + 1)));
  // Version 1 (no closing sections) still reads, without prism slabs.
  {
    std::vector<std::string> v1(lines.begin(), lines.begin() + last_tet + 1);
    v1[0] = "tet4 1";
    const std::string q = (dir / "v1.tet4").string();
    std::ofstream out(q);
    for (auto& l : v1) out << l << "\n";
    out.close();
    const AnimationManifold R1 = read_manifold(q);
    CHECK(R1.T == M.T);
    CHECK(R1.prism_slabs.empty());
  }
  // A vertex moved outside its slab's time span.
  REQUIRE_THROWS_WITH(read_manifold(write_with(8, "v 0 0 0 5")), Catch::Contains("slab"));
  REQUIRE_THROWS_AS(read_manifold((dir / "missing.tet4").string()), Error);
  fs::remove_all(dir);
}

TEST_CASE("frame sequences: one naming rule, frames evenly over the animation, both ends included", "[manifold]") {
  CHECK(frame_naming("out/walk").stem == "out/walk");
  CHECK(frame_naming("out/walk").ext == ".obj");
  CHECK(frame_naming("out/walk.ply").stem == "out/walk");
  CHECK(frame_naming("out/walk.ply").ext == ".ply");
  CHECK(frame_naming("walk.stl").ext == ".stl");
  CHECK(frame_naming(".obj").stem == ".obj");  // nothing before the extension: a stem, not a format
  CHECK(frame_path(frame_naming("a/f.off"), 7) == "a/f0007.off");
  CHECK(frame_time(1.0, 3.0, 0, 5) == 1.0);
  CHECK(frame_time(1.0, 3.0, 4, 5) == 3.0);
  CHECK(frame_time(1.0, 3.0, 1, 5) == 1.5);
  CHECK(frame_time(1.0, 3.0, 0, 1) == 1.0);

  // The cube slides +1 in x over [0, 2]: frame i of 5 is the cube moved by t / 2.
  const TriMesh cube = unit_cube();
  Eigen::MatrixXd V1 = cube.V;
  V1.col(0).array() += 1.0;
  const AnimationManifold M = build_manifold(std::vector<Eigen::MatrixXd>{cube.V, V1}, cube.F, {0, 2});
  const fs::path dir = fs::temp_directory_path() / ("dfm_frames_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::vector<std::string> paths = write_frame_sequence(M, (dir / "f.off").string(), 5);
  REQUIRE(paths.size() == 5);
  for (int i = 0; i < 5; ++i) {
    REQUIRE(paths[i] == (dir / ("f000" + std::to_string(i) + ".off")).string());
    const TriMesh m = read_surface(paths[i]);
    CHECK(m.V.col(0).minCoeff() == Approx(0.25 * i).margin(1e-12));
    CHECK(m.V.col(0).maxCoeff() == Approx(1 + 0.25 * i).margin(1e-12));
    CHECK(enclosed_volume(m.V, m.F) == Approx(1.0).epsilon(1e-12));
  }
  CHECK_THROWS_WITH(write_frame_sequence(M, (dir / "g").string(), 0), Catch::Contains("at least one frame"));
  CHECK_THROWS_WITH(write_frame_sequence(M, (dir / "missing" / "g").string(), 2), Catch::Contains("missing"));
  fs::remove_all(dir);
}

TEST_CASE("frames between prism layers are the layers' mesh, each vertex on its own time edge", "[manifold]") {
  // A cube whose corners move differently: each by its own vector between layers (not a rigid move),
  // so the prisms' exact slice kinks on the side diagonals while the frame stays the cube's mesh.
  const TriMesh cube = unit_cube();
  Eigen::MatrixXd V1 = cube.V, V2 = cube.V;
  for (int v = 0; v < 8; ++v) {
    V1.row(v) += Eigen::RowVector3d(0.02 * v, -0.01 * (v % 3), 0.3);
    V2.row(v) = 1.5 * V1.row(v);
  }
  const std::vector<double> times = {0.0, 1.0, 3.0};
  const AnimationManifold M = build_manifold(std::vector<Eigen::MatrixXd>{cube.V, V1, V2}, cube.F, times);
  REQUIRE(M.prism_slabs.size() == 2);
  CHECK(prism_slab_at(M, -0.1) == -1);
  CHECK(prism_slab_at(M, 0.0) == 0);
  CHECK(prism_slab_at(M, 1.0) == 0);  // shared by two slabs: the earlier
  CHECK(prism_slab_at(M, 2.0) == 1);
  CHECK(prism_slab_at(M, 3.5) == -1);

  for (double t : {0.25, 0.5, 1.0, 2.2, 3.0}) {
    const ManifoldSlice f = manifold_frame(M, t);
    REQUIRE(f.mesh.F == cube.F);
    REQUIRE(f.mesh.num_vertices() == 8);
    // The reference: vertex v on the segment between its copies in the layers around t.
    const Eigen::MatrixXd& A = t <= 1.0 ? cube.V : V1;
    const Eigen::MatrixXd& B = t <= 1.0 ? V1 : V2;
    const double u = t <= 1.0 ? t : (t - 1.0) / 2.0;
    CHECK((f.mesh.V - (A + u * (B - A))).cwiseAbs().maxCoeff() < 1e-14);
    for (int v = 0; v < 8; ++v) {
      CHECK(f.mesh.N.row(v).norm() == Approx(1.0).epsilon(1e-12));
      // Edges name the vertex's own copies: (lower, upper), or the vertex itself on a layer.
      const int slab = t <= 1.0 ? 0 : 1;
      if (t == times[slab + 1]) {
        CHECK(f.edges[v][0] == (slab + 1) * 8 + v);
        CHECK(f.edges[v][1] == f.edges[v][0]);
      } else {
        CHECK(f.edges[v][0] == slab * 8 + v);
        CHECK(f.edges[v][1] == (slab + 1) * 8 + v);
      }
    }
    // The exact slice of the prisms has more vertices (the kinks) and encloses another volume.
    if (t != 1.0 && t != 3.0) CHECK(slice_manifold(M, SliceAxis::T, t).mesh.num_vertices() > 8);
  }
  // At a layer time the frame is that layer, bit for bit, outward normals included.
  const ManifoldSlice key = manifold_frame(M, 1.0);
  CHECK(key.mesh.V == V1);
  for (int f = 0; f < key.mesh.num_faces(); ++f) {
    const Eigen::Vector3d a = key.mesh.V.row(key.mesh.F(f, 0)), b = key.mesh.V.row(key.mesh.F(f, 1)),
                          c = key.mesh.V.row(key.mesh.F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    for (int j = 0; j < 3; ++j) CHECK(key.mesh.N.row(key.mesh.F(f, j)).dot(n) > 0);
  }
  // Without prism records (a manifold made otherwise) the frame is the exact slice.
  AnimationManifold plain = M;
  plain.prism_slabs.clear();
  plain.layer_faces.clear();
  CHECK(manifold_frame(plain, 0.5).mesh.V == slice_manifold(M, SliceAxis::T, 0.5).mesh.V);
  CHECK_THROWS_WITH(prism_frame(plain, 0, 0.5), Catch::Contains("prism build"));
  CHECK_THROWS_WITH(prism_frame(M, 1, 0.5), Catch::Contains("outside"));
}
