// GPU slicing (render/slice_pass, shaders/slice.*.glsl) against the CPU slicer (core/anim/slice).
#include <algorithm>
#include <cmath>

#include <catch2/catch.hpp>
#include <Eigen/Geometry>

#include "core/anim/manifold.h"
#include "core/anim/manifold_normals.h"
#include "core/anim/slice.h"
#include "core/util/error.h"
#include "core/mesh/io.h"
#include "render/gl_context.h"
#include "render/slice_pass.h"
#include "tests/test_support.h"

using namespace dfm;

namespace {

Eigen::MatrixXd transformed(const Eigen::MatrixXd& V, const Eigen::Affine3d& a) {
  return ((a.linear() * V.transpose()).colwise() + a.translation()).transpose();
}

// Every GPU triangle matches a distinct CPU triangle (same corners in the same cyclic order) within
// tol, and the counts agree. Of the candidates the closest is taken: near a vertex just off the plane
// several slice points lie within tol of each other. Each GPU corner's smooth normal is unit and the
// CPU's at that vertex within ntol. With `facing`, every GPU corner normal also faces the side of the
// CPU triangle (true on fold-free slices such as the keyframes; mid-slab slices of a fast motion fold).
void require_same_triangles(const ManifoldSlice& cpu, const std::vector<gl::PosNormal>& gpu, double tol,
                            bool facing, double ntol = 1e-4) {
  const int nf = cpu.mesh.num_faces();
  REQUIRE(static_cast<int>(gpu.size()) == 3 * nf);
  std::vector<std::pair<double, int>> by_x(nf);
  for (int f = 0; f < nf; ++f) {
    double cx = 0;
    for (int j = 0; j < 3; ++j) cx += cpu.mesh.V(cpu.mesh.F(f, j), 0) / 3;
    by_x[f] = {cx, f};
  }
  std::sort(by_x.begin(), by_x.end());
  std::vector<char> used(nf, 0);
  int unmatched = 0, facing_away = 0;
  double worst_normal = 0, worst_length = 0;
  for (size_t g = 0; g < gpu.size(); g += 3) {
    Eigen::Vector3d q[3], n[3];
    for (int j = 0; j < 3; ++j) {
      q[j] = Eigen::Vector3d(gpu[g + j].position[0], gpu[g + j].position[1], gpu[g + j].position[2]);
      n[j] = Eigen::Vector3d(gpu[g + j].normal[0], gpu[g + j].normal[1], gpu[g + j].normal[2]);
    }
    const double cx = (q[0].x() + q[1].x() + q[2].x()) / 3;
    int best_f = -1, best_r = 0;
    double best = tol;
    for (auto it = std::lower_bound(by_x.begin(), by_x.end(), std::make_pair(cx - tol, -1));
         it != by_x.end() && it->first <= cx + tol; ++it) {
      const int f = it->second;
      if (used[f]) continue;
      for (int r = 0; r < 3; ++r) {
        double d = 0;
        for (int j = 0; j < 3; ++j)
          d = std::max(d, (cpu.mesh.V.row(cpu.mesh.F(f, (j + r) % 3)).transpose() - q[j]).norm());
        if (d <= best) best = d, best_f = f, best_r = r;
      }
    }
    if (best_f < 0) {
      ++unmatched;
      continue;
    }
    used[best_f] = 1;
    const Eigen::Vector3d p0 = cpu.mesh.V.row(cpu.mesh.F(best_f, 0)), p1 = cpu.mesh.V.row(cpu.mesh.F(best_f, 1)),
                          p2 = cpu.mesh.V.row(cpu.mesh.F(best_f, 2));
    const Eigen::Vector3d fn = (p1 - p0).cross(p2 - p0);
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d cn = cpu.mesh.N.row(cpu.mesh.F(best_f, (j + best_r) % 3)).transpose();
      worst_normal = std::max(worst_normal, (cn - n[j]).norm());
      worst_length = std::max(worst_length, std::abs(n[j].norm() - 1));
      facing_away += fn.dot(n[j]) <= 0;
    }
  }
  REQUIRE(unmatched == 0);
  INFO("largest GPU - CPU normal difference " << worst_normal);
  REQUIRE(worst_normal <= ntol);
  REQUIRE(worst_length <= 1e-6);
  if (facing) REQUIRE(facing_away == 0);
}

}  // namespace

TEST_CASE("GPU slices equal the CPU slices on every axis", "[gl][manifold]") {
  DFM_DATA_OR_SKIP(path, "arm.obj");
  const TriMesh arm = read_surface(path);
  const Eigen::Vector3d ctr = arm.V.colwise().mean();
  const Eigen::Affine3d turn(Eigen::Translation3d(ctr + Eigen::Vector3d(0.1, 0.05, 0)) *
                             Eigen::AngleAxisd(0.8, Eigen::Vector3d(0.2, 0.3, 1).normalized()) *
                             Eigen::Translation3d(-ctr));
  Eigen::Affine3d stretch = Eigen::Affine3d::Identity();
  stretch.linear() = Eigen::Vector3d(1.3, 0.8, 1.1).asDiagonal();
  const std::vector<Eigen::MatrixXd> keys = {arm.V, transformed(arm.V, turn), transformed(arm.V, stretch * turn)};
  const AnimationManifold M = build_manifold(keys, arm.F, {0.0, 1.0, 2.5});
  Eigen::Vector4d lo = M.V.colwise().minCoeff(), hi = M.V.colwise().maxCoeff();
  const double tol = 1e-5 * (hi - lo).head<3>().norm();

  gl::Context ctx;
  INFO(ctx.renderer());
  gl::SlicePass pass;
  pass.upload(M);
  struct Case {
    SliceAxis axis;
    double at;
  };
  std::vector<Case> cases = {{SliceAxis::T, 0.0},  {SliceAxis::T, 0.37}, {SliceAxis::T, 1.0},
                             {SliceAxis::T, 1.8},  {SliceAxis::T, 2.5},  {SliceAxis::T, 3.0}};
  for (int axis = 0; axis < 3; ++axis)
    cases.push_back({static_cast<SliceAxis>(axis), lo[axis] + 0.43 * (hi[axis] - lo[axis])});
  for (const Case& c : cases) {
    INFO("axis " << slice_axis_name(c.axis) << " at " << c.at);
    const ManifoldSlice cpu = slice_manifold(M, c.axis, c.at);
    const int n = pass.slice(c.axis, c.at);
    REQUIRE(n == cpu.mesh.num_faces());
    const auto range = slice_tet_range(M, c.axis, c.at);
    REQUIRE(pass.last_tets_drawn() == range.second - range.first);
    if (c.axis == SliceAxis::T && c.at != 1.0) REQUIRE(pass.last_tets_drawn() < M.num_tets());  // one slab
    const bool key_time = c.axis == SliceAxis::T && std::find(M.times.begin(), M.times.end(), c.at) != M.times.end();
    require_same_triangles(cpu, pass.read_back(), tol, key_time);
  }
  // At a key time the GPU gives the keyframe's triangles (no collapsed ones).
  REQUIRE(pass.slice(SliceAxis::T, 1.0) == arm.num_faces());

  // New positions for the same tetrahedra and times (a space-time drag frame): the slices follow them.
  AnimationManifold moved = M;
  for (int v = 0; v < moved.num_vertices(); ++v)
    moved.V.row(v).head<3>() += Eigen::RowVector3d(0.05, -0.02, 0.03) * std::sin(3 * moved.V(v, 0) + moved.V(v, 3));
  pass.upload_vertices(moved, manifold_vertex_normals(moved));
  for (const Case& c : {Case{SliceAxis::T, 0.37}, Case{SliceAxis::T, 1.8}, Case{SliceAxis::X, lo[0] + 0.5 * (hi[0] - lo[0])}}) {
    INFO("moved, axis " << slice_axis_name(c.axis) << " at " << c.at);
    const ManifoldSlice cpu = slice_manifold(moved, c.axis, c.at);
    REQUIRE(pass.slice(c.axis, c.at) == cpu.mesh.num_faces());
    require_same_triangles(cpu, pass.read_back(), tol, false);
  }
  AnimationManifold fewer = M;
  fewer.V.conservativeResize(M.num_vertices() - 1, 4);
  REQUIRE_THROWS_AS(pass.upload_vertices(fewer, manifold_vertex_normals(M)), Error);
}
