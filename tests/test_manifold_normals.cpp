// Smooth normals of animation manifolds (core/anim/manifold_normals) and of their CPU slices.
#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include <catch2/catch.hpp>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include "core/anim/manifold.h"
#include "core/anim/manifold_normals.h"
#include "core/anim/slice.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;

namespace {

// <N, w> = det[w, e1, e2, e3], straight from the definition (4x4 determinants, no cofactors).
Eigen::Vector4d normal_by_det(const Eigen::Vector4d p[4]) {
  Eigen::Matrix4d E;
  for (int c = 1; c < 4; ++c) E.col(c) = p[c] - p[0];
  Eigen::Vector4d N;
  for (int j = 0; j < 4; ++j) {
    E.col(0) = Eigen::Vector4d::Unit(j);
    N[j] = E.determinant();
  }
  return N;
}

AnimationManifold one_tet(const Eigen::Vector4d p[4]) {
  AnimationManifold M;
  M.V.resize(4, 4);
  for (int i = 0; i < 4; ++i) M.V.row(i) = p[i].transpose();
  M.T.resize(1, 4);
  M.T << 0, 1, 2, 3;
  return M;
}

// An icosphere with its vertices pushed radially at random, so area weights matter.
TriMesh lumpy_sphere() {
  TriMesh m = test::icosphere(Eigen::Vector3d(0.2, -0.1, 0.3), 1.0, 2);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(0.8, 1.2);
  const Eigen::RowVector3d c(0.2, -0.1, 0.3);
  for (int v = 0; v < m.num_vertices(); ++v) m.V.row(v) = c + U(rng) * (m.V.row(v) - c);
  return m;
}

int up_endpoint(const AnimationManifold& M, const std::array<int, 2>& e, int axis, double c) {
  return M.V(e[0], axis) - c < 0.0 ? e[1] : e[0];
}

}  // namespace

TEST_CASE("tetrahedron normals: the generalized cross product, its length and sign", "[manifold][normals]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int trial = 0; trial < 50; ++trial) {
    Eigen::Vector4d p[4];
    for (auto& q : p) q = Eigen::Vector4d(U(rng), U(rng), U(rng), U(rng));
    const Eigen::Vector4d N = tet_normal4(one_tet(p), 0), ref = normal_by_det(p);
    REQUIRE((N - ref).norm() <= 1e-12);
    // Orthogonal to the tetrahedron, length 6 x its 3-volume (Gram determinant), det[N, e1, e2, e3] > 0.
    Eigen::Matrix<double, 4, 3> E;
    for (int c = 0; c < 3; ++c) E.col(c) = p[c + 1] - p[0];
    REQUIRE((E.transpose() * N).norm() <= 1e-12);
    REQUIRE(N.norm() == Approx(std::sqrt((E.transpose() * E).determinant())).epsilon(1e-10));
    Eigen::Matrix4d W;
    W << N, E;
    REQUIRE(W.determinant() == Approx(N.squaredNorm()).epsilon(1e-10));

    // Lying in the hyperplane x = 0 (or t = 0): the normal is along e_x (e_t), signed by the orientation
    // of the other three coordinates, with length 6 x the 3D volume there.
    for (int axis : {0, 3}) {
      Eigen::Vector4d f[4];
      for (int i = 0; i < 4; ++i) (f[i] = p[i])[axis] = 0.0;
      const Eigen::Vector4d n = tet_normal4(one_tet(f), 0);
      Eigen::Matrix3d D;
      for (int c = 0, r = 0; r < 4; ++r)
        if (r != axis) D.row(c++) = (Eigen::Vector3d(f[1][r], f[2][r], f[3][r]) - Eigen::Vector3d::Constant(f[0][r])).transpose();
      const double sign = axis == 0 ? 1.0 : -1.0;  // moving row 3 to the top takes 3 swaps
      REQUIRE(n[axis] == Approx(sign * D.determinant()).epsilon(1e-12));
      REQUIRE(n.norm() == Approx(std::abs(D.determinant())).epsilon(1e-12));
    }
  }
}

TEST_CASE("tetrahedron normals follow manifold.h: prisms of an outward triangle face out", "[manifold][normals]") {
  // Every vertex numbering of the triangle (0,0,0) (1,0,0) (0,1,0), wound so that +z is outward: the
  // staircase split depends on the index order, the normal's direction must not.
  std::array<int, 3> perm = {0, 1, 2};
  do {
    Eigen::MatrixXd V(3, 3);
    V.row(perm[0]) << 0, 0, 0;
    V.row(perm[1]) << 1, 0, 0;
    V.row(perm[2]) << 0, 1, 0;
    Eigen::MatrixXi F(1, 3);
    F << perm[0], perm[1], perm[2];
    for (double speed : {0.0, 0.5, -2.0}) {
      // The upper layer moves along the outward normal: the solid is z <= speed t, normal (0, 0, 1, -speed).
      Eigen::MatrixXd V1 = V;
      V1.col(2).array() += speed;
      const AnimationManifold M = build_manifold(std::vector<Eigen::MatrixXd>{V, V1}, F, {0.0, 1.0});
      const Eigen::Vector4d expect = Eigen::Vector4d(0, 0, 1, -speed).normalized();
      double volume = 0;
      for (int k = 0; k < M.num_tets(); ++k) {
        const Eigen::Vector4d N = tet_normal4(M, k);
        INFO("F = " << F << ", speed " << speed << ", tet " << k);
        REQUIRE(N[2] > 0);  // the xyz part points outward
        REQUIRE((N.normalized() - expect).norm() <= 1e-12);
        volume += N.norm() / 6;
      }
      // 3 tetrahedra fill the prism, whose 3-volume is the triangle's area in the tilted hyperplane x height.
      REQUIRE(volume == Approx(0.5 * std::sqrt(1 + speed * speed)).epsilon(1e-12));
      const Eigen::MatrixXd N4 = manifold_vertex_normals(M);
      for (int v = 0; v < 6; ++v) REQUIRE((N4.row(v).transpose() - expect).norm() <= 1e-12);
      // Slice along t: drop t and renormalise -> +z; along z: (0, 0, -speed) normalised, i.e. the t axis.
      REQUIRE((slice_normal3(N4.row(0).transpose(), SliceAxis::T) - Eigen::Vector3d(0, 0, 1)).norm() <= 1e-12);
      const Eigen::Vector3d nz = slice_normal3(N4.row(0).transpose(), SliceAxis::Z);
      if (speed == 0.0)
        REQUIRE(nz == Eigen::Vector3d::Zero());  // nothing left after dropping z
      else
        REQUIRE((nz - Eigen::Vector3d(0, 0, speed > 0 ? -1 : 1)).norm() <= 1e-12);
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
}

TEST_CASE("vertex normals: Eq. 2.3 against layer normals of static manifolds", "[manifold][normals]") {
  const TriMesh s = lumpy_sphere();
  const int n = s.num_vertices();
  const Eigen::MatrixXd layer_n = test::area_weighted_normals(s.V, s.F);
  // Equal time steps: an inner layer vertex meets 4 of the 6 staircase tetrahedra of each incident
  // prism pair whatever its rank in the triangle, so Eq. 2.3 is the layer's area-weighted normal.
  const AnimationManifold M = build_manifold(std::vector<Eigen::MatrixXd>(4, s.V), s.F, {0, 1, 2, 3});
  const Eigen::MatrixXd N4 = manifold_vertex_normals(M);
  REQUIRE(N4.rows() == 4 * n);
  for (int layer : {1, 2})
    for (int v = 0; v < n; ++v) {
      const Eigen::Vector4d N = N4.row(layer * n + v).transpose();
      REQUIRE(std::abs(N[3]) <= 1e-15);
      REQUIRE((N.head<3>() - layer_n.row(v).transpose()).norm() <= 1e-12);
    }
  // The first and last layer are key planes: a vertex there sums only the tetrahedra with a face in
  // the plane, one per incident triangle (its prism's bottom or top), so it too gets the layer's
  // area-weighted normal, whatever the vertex's rank in the triangle.
  for (int v = 0; v < n; ++v) {
    REQUIRE((N4.row(v).head<3>() - layer_n.row(v)).norm() <= 1e-12);
    REQUIRE((N4.row(3 * n + v).head<3>() - layer_n.row(v)).norm() <= 1e-12);
  }
}

TEST_CASE("slice normals of identical layers are the layer's normals, interpolated on the cut edge", "[manifold][normals]") {
  const TriMesh s = lumpy_sphere();
  const int n = s.num_vertices();
  const Eigen::MatrixXd layer_n = test::area_weighted_normals(s.V, s.F);
  const AnimationManifold M = build_manifold(std::vector<Eigen::MatrixXd>(4, s.V), s.F, {0, 1, 2, 3});
  for (double t : {1.0, 1.37, 1.5, 2.0 - 1e-7, 2.0}) {
    INFO("t = " << t);
    const ManifoldSlice sl = slice_manifold(M, SliceAxis::T, t);
    REQUIRE(sl.mesh.N.rows() == sl.mesh.num_vertices());
    int on_vertical = 0;
    for (int v = 0; v < sl.mesh.num_vertices(); ++v) {
      const auto e = sl.edges[v];
      Eigen::Vector3d expect;
      if (e[0] % n == e[1] % n) {  // a layer vertex, or the vertical edge over it
        expect = layer_n.row(e[0] % n).transpose();
        ++on_vertical;
      } else {  // a prism diagonal q -- p': the layer normals interpolated with the time parameter
        const int up = up_endpoint(M, e, 3, t), dn = up == e[0] ? e[1] : e[0];
        const double mu = (M.V(up, 3) - t) / (M.V(up, 3) - M.V(dn, 3));
        const Eigen::Vector3d nu = layer_n.row(up % n), nd = layer_n.row(dn % n);
        expect = (nu + mu * (nd - nu)).normalized();
      }
      REQUIRE((sl.mesh.N.row(v).transpose() - expect).norm() <= 1e-9);
    }
    REQUIRE(on_vertical == n);
  }
}

TEST_CASE("slice normals: unit, outward on a moving convex shape, same with precomputed normals", "[manifold][normals]") {
  struct Case {
    SliceAxis axis;
    double at;
  };
  auto check = [](const AnimationManifold& M, const std::vector<Case>& cases) {
    const Eigen::MatrixXd N4 = manifold_vertex_normals(M);
    for (int v = 0; v < M.num_vertices(); ++v) REQUIRE(N4.row(v).norm() == Approx(1.0).epsilon(1e-14));
    for (const Case& c : cases) {
      INFO("axis " << slice_axis_name(c.axis) << " at " << c.at);
      const ManifoldSlice sl = slice_manifold(M, c.axis, c.at);
      REQUIRE(sl.mesh.num_faces() > 0);
      const Eigen::RowVector3d centroid = sl.mesh.V.colwise().mean();
      for (int v = 0; v < sl.mesh.num_vertices(); ++v) {
        REQUIRE(sl.mesh.N.row(v).norm() == Approx(1.0).epsilon(1e-12));
        REQUIRE(sl.mesh.N.row(v).dot(sl.mesh.V.row(v) - centroid) > 0);
      }
      // Precomputed normals: the same slice, bit for bit (for t only the neighbouring slabs are summed).
      const ManifoldSlice pre = slice_manifold(M, c.axis, c.at, &N4);
      REQUIRE(pre.mesh.V == sl.mesh.V);
      REQUIRE(pre.mesh.F == sl.mesh.F);
      REQUIRE(pre.mesh.N == sl.mesh.N);
    }
  };
  const TriMesh s = test::icosphere(Eigen::Vector3d::Zero(), 1.0, 2);
  const Eigen::RowVector3d velocity(0.7, -0.4, 0.2);
  const std::vector<double> times = {0.0, 1.0, 1.8, 3.0};
  // A sphere moving at constant velocity with a concave radius 1, 1.6, 1.9, 2: the space-time solid
  // |p - c(t)| <= r(t) is convex, so every slice of it, on t or on x, y, z, is.
  std::vector<Eigen::MatrixXd> grow;
  for (int i = 0; i < 4; ++i) {
    const double r[] = {1.0, 1.6, 1.9, 2.0};
    grow.push_back((r[i] * s.V).rowwise() + times[i] * velocity);
  }
  check(build_manifold(grow, s.F, times), {{SliceAxis::T, 0.0}, {SliceAxis::T, 0.3}, {SliceAxis::T, 1.0},
                                           {SliceAxis::T, 2.5}, {SliceAxis::T, 3.0}, {SliceAxis::X, 0.1},
                                           {SliceAxis::Y, -0.2}, {SliceAxis::Z, 0.05}, {SliceAxis::X, 2.1}});
  // Turning as well: t slices are affine images of the sphere (convex), sweeps are not checked.
  std::vector<Eigen::MatrixXd> turn = grow;
  for (int i = 1; i < 4; ++i)
    turn[i] = turn[i] * Eigen::AngleAxisd(0.5 * i, Eigen::Vector3d(1, 2, 0.5).normalized()).toRotationMatrix();
  check(build_manifold(turn, s.F, times), {{SliceAxis::T, 0.2}, {SliceAxis::T, 1.0}, {SliceAxis::T, 1.3},
                                           {SliceAxis::T, 2.2}, {SliceAxis::T, 3.0}});

  const AnimationManifold M = build_manifold(grow, s.F, times);
  const Eigen::MatrixXd wrong = Eigen::MatrixXd::Zero(3, 4);
  REQUIRE_THROWS(slice_manifold(M, SliceAxis::T, 0.5, &wrong));
}
