// core/anim/interval_slice: one interval's slice topology, evaluated at any time inside it, equals the
// CPU slicer there (same vertices in the same order, same triangles, same normals).
#include <algorithm>
#include <cmath>

#include <catch2/catch.hpp>

#include "core/anim/interval_slice.h"
#include "core/anim/manifold_normals.h"
#include "core/anim/slice.h"
#include "core/util/error.h"
#include "tests/interval_slice_test_manifolds.h"

using namespace dfm;

namespace {

// Times strictly inside (lo, hi): near both ends, the middle, and between.
std::vector<double> times_inside(double lo, double hi) {
  const double w = hi - lo;
  return {lo + 1e-9 * w, lo + 0.013 * w, lo + 0.25 * w, lo + 0.5 * w, lo + 0.77 * w, hi - 1e-9 * w};
}

// The interval's evaluation equals slice_manifold at t, and the slice is not empty.
void require_equal_to_cpu_slice(const IntervalSlice& s, const AnimationManifold& M, const Eigen::MatrixXd& N4,
                                double t) {
  INFO("t = " << t << " in (" << s.t_lo << ", " << s.t_hi << ")");
  const ManifoldSlice cpu = slice_manifold(M, SliceAxis::T, t, &N4);
  const TriMesh mine = evaluate_interval_slice(s, M, N4, t);
  REQUIRE(cpu.mesh.num_faces() > 0);
  REQUIRE(mine.num_vertices() == cpu.mesh.num_vertices());
  REQUIRE(mine.num_faces() == cpu.mesh.num_faces());
  REQUIRE(mine.F == cpu.mesh.F);
  const double scale = std::max(1.0, cpu.mesh.V.cwiseAbs().maxCoeff());
  REQUIRE((mine.V - cpu.mesh.V).cwiseAbs().maxCoeff() <= 1e-12 * scale);
  REQUIRE((mine.N - cpu.mesh.N).cwiseAbs().maxCoeff() <= 1e-12);
  for (int v = 0; v < s.num_vertices(); ++v) {
    const int a = std::min(s.edges[v][0], s.edges[v][1]), b = std::max(s.edges[v][0], s.edges[v][1]);
    REQUIRE(cpu.edges[v] == std::array<int, 2>{a, b});
  }
}

}  // namespace

TEST_CASE("vertex times and the open interval holding a time", "[manifold][interval]") {
  const AnimationManifold M = test::deforming_sphere_manifold();
  const std::vector<double> times = manifold_vertex_times(M);
  REQUIRE(times == std::vector<double>{0.0, 1.0, 2.5});
  REQUIRE(open_interval_of(times, -0.1) == -1);
  REQUIRE(open_interval_of(times, 0.0) == -1);  // on a vertex time: another topology
  REQUIRE(open_interval_of(times, 0.5) == 0);
  REQUIRE(open_interval_of(times, 1.0) == -1);
  REQUIRE(open_interval_of(times, std::nextafter(1.0, 2.0)) == 1);
  REQUIRE(open_interval_of(times, std::nextafter(1.0, 0.0)) == 0);
  REQUIRE(open_interval_of(times, 2.4) == 1);
  REQUIRE(open_interval_of(times, 2.5) == -1);
  REQUIRE(open_interval_of(times, 3.0) == -1);
  REQUIRE(open_interval_of({}, 0.0) == -1);
}

TEST_CASE("an interval's topology gives the CPU slice at every time inside it (prism manifold)", "[manifold][interval]") {
  const AnimationManifold M = test::without_prism_records(test::deforming_sphere_manifold());
  const Eigen::MatrixXd N4 = manifold_vertex_normals(M);
  const std::vector<double> times = manifold_vertex_times(M);
  for (size_t i = 0; i + 1 < times.size(); ++i) {
    const IntervalSlice s = build_interval_slice(M, N4, times[i], times[i + 1]);
    REQUIRE(s.num_faces() > 0);
    for (int v = 0; v < s.num_vertices(); ++v) REQUIRE(M.V(s.edges[v][0], 3) > M.V(s.edges[v][1], 3));
    REQUIRE(s.closed_outward);  // the slice of a closed sphere's manifold: the viewport may cull back faces
    for (double t : times_inside(times[i], times[i + 1])) require_equal_to_cpu_slice(s, M, N4, t);
    // Not beyond the ends.
    REQUIRE_THROWS_AS(evaluate_interval_slice(s, M, N4, times[i] - 0.01), Error);
    REQUIRE_THROWS_AS(evaluate_interval_slice(s, M, N4, times[i + 1] + 0.01), Error);
  }
  // Two intervals have different topologies: one does not stand for the other.
  const IntervalSlice a = build_interval_slice(M, N4, times[0], times[1]);
  const IntervalSlice b = build_interval_slice(M, N4, times[1], times[2]);
  REQUIRE(a.edges != b.edges);
  // An interval with a vertex time inside is refused.
  REQUIRE_THROWS_AS(build_interval_slice(M, N4, times[0], times[2]), Error);
  REQUIRE_THROWS_AS(build_interval_slice(M, N4, 1.0, 1.0), Error);
  // An open surface's manifold (the sphere less one triangle) slices open: never culled.
  const TriMesh sphere = test::icosphere(Eigen::Vector3d::Zero(), 1.0, 1);
  const Eigen::MatrixXi open_F = sphere.F.topRows(sphere.F.rows() - 1);
  const AnimationManifold open =
      test::without_prism_records(build_manifold({sphere.V, 1.1 * sphere.V}, open_F, {0.0, 1.0}));
  const IntervalSlice o = build_interval_slice(open, manifold_vertex_normals(open), 0.0, 1.0);
  REQUIRE(o.num_faces() > 0);
  REQUIRE_FALSE(o.closed_outward);
}

// At a vertex time slice_manifold has another topology; the neighbouring intervals' limits there are
// the same surface: the same points (each limit vertex is a CPU vertex and back), the same area and
// the same enclosed volume, the extra triangles collapsed to zero area.
TEST_CASE("an interval's limit at its ends is the CPU slice's surface", "[manifold][interval]") {
  const AnimationManifold M = test::without_prism_records(test::deforming_sphere_manifold());
  const Eigen::MatrixXd N4 = manifold_vertex_normals(M);
  const std::vector<double> times = manifold_vertex_times(M);
  auto area = [](const TriMesh& m) {
    double a = 0;
    for (int f = 0; f < m.F.rows(); ++f)
      a += 0.5 * Eigen::RowVector3d(m.V.row(m.F(f, 1)) - m.V.row(m.F(f, 0)))
                     .cross(Eigen::RowVector3d(m.V.row(m.F(f, 2)) - m.V.row(m.F(f, 0))))
                     .norm();
    return a;
  };
  auto nearest = [](const Eigen::MatrixXd& P, const Eigen::RowVector3d& q) {
    return (P.rowwise() - q).rowwise().norm().minCoeff();
  };
  for (size_t k = 0; k < times.size(); ++k) {
    const TriMesh cpu = slice_manifold(M, SliceAxis::T, times[k], &N4).mesh;
    REQUIRE(cpu.num_faces() > 0);
    for (int side : {-1, 0}) {  // interval k - 1 ends at times[k], interval k starts there
      const int i = static_cast<int>(k) + side;
      if (i < 0 || i + 1 >= static_cast<int>(times.size())) continue;
      INFO("vertex time " << times[k] << ", interval " << i);
      const IntervalSlice s = build_interval_slice(M, N4, times[i], times[i + 1]);
      REQUIRE(s.reaches(times[k]));
      REQUIRE_FALSE(s.contains(times[k]));
      const TriMesh lim = evaluate_interval_slice(s, M, N4, times[k]);
      for (int v = 0; v < lim.num_vertices(); ++v) REQUIRE(nearest(cpu.V, lim.V.row(v)) < 1e-12);
      for (int v = 0; v < cpu.num_vertices(); ++v) REQUIRE(nearest(lim.V, cpu.V.row(v)) < 1e-12);
      REQUIRE(area(lim) == Approx(area(cpu)).epsilon(1e-12));
      REQUIRE(test::enclosed_volume(lim.V, lim.F) == Approx(test::enclosed_volume(cpu.V, cpu.F)).epsilon(1e-12));
      REQUIRE(lim.num_faces() > cpu.num_faces());  // collapsed triangles remain in the limit
    }
  }
}

// Issue 38: between prism layers the interval's topology is the layers' mesh, so playback draws the
// artist's triangles: each vertex on the segment between its own two copies (written out here), the
// layers' triangles, the layers themselves at the ends, and a closed mesh stays closed.
TEST_CASE("a prism slab's interval is its layers' mesh, vertex for vertex", "[manifold][interval]") {
  const AnimationManifold M = test::deforming_sphere_manifold();
  const Eigen::MatrixXd N4 = manifold_vertex_normals(M);
  const std::vector<double> times = manifold_vertex_times(M);
  REQUIRE(times.size() == 3);
  const int n = M.prism_slabs[0].count;
  const Eigen::MatrixXi& F = M.layer_faces[0];
  for (int i = 0; i < 2; ++i) {
    const IntervalSlice s = build_interval_slice(M, N4, times[i], times[i + 1]);
    REQUIRE(s.num_vertices() == n);
    REQUIRE(s.F == F);
    REQUIRE(s.closed_outward);
    const Eigen::MatrixXd lo = M.V.block(i * n, 0, n, 3), hi = M.V.block((i + 1) * n, 0, n, 3);
    for (double t : times_inside(times[i], times[i + 1])) {
      const TriMesh f = evaluate_interval_slice(s, M, N4, t);
      const double u = (t - times[i]) / (times[i + 1] - times[i]);
      REQUIRE((f.V - (lo + u * (hi - lo))).cwiseAbs().maxCoeff() < 1e-12);
      for (int v = 0; v < n; ++v) REQUIRE(f.N.row(v).norm() == Approx(1.0).epsilon(1e-12));
    }
    REQUIRE((evaluate_interval_slice(s, M, N4, times[i]).V - lo).cwiseAbs().maxCoeff() < 1e-14);
    REQUIRE(evaluate_interval_slice(s, M, N4, times[i + 1]).V == hi);
    // The exact slice of the prisms has the kinks: more vertices than the mesh.
    REQUIRE(slice_manifold(M, SliceAxis::T, 0.5 * (times[i] + times[i + 1]), &N4).mesh.num_vertices() > n);
  }
}

TEST_CASE("intervals of a transition (many vertex times) give its CPU slices", "[manifold][interval][transition]") {
  const AnimationManifold M = test::sphere_to_box_transition();
  const Eigen::MatrixXd N4 = manifold_vertex_normals(M);
  const std::vector<double> times = manifold_vertex_times(M);
  INFO(times.size() << " distinct vertex times, " << M.num_layers() << " layers");
  REQUIRE(static_cast<int>(times.size()) > 3 * M.num_layers());  // far more than the layers
  const int n = static_cast<int>(times.size()) - 1;
  std::vector<int> picks = {0, 1, n / 7, n / 3, n / 2, (2 * n) / 3, n - 2, n - 1};
  int checked = 0;
  for (int i : picks) {
    const IntervalSlice s = build_interval_slice(M, N4, times[i], times[i + 1]);
    for (double t : {times[i] + 0.1 * (times[i + 1] - times[i]), times[i] + 0.5 * (times[i + 1] - times[i]),
                     times[i] + 0.9 * (times[i + 1] - times[i])}) {
      if (!(times[i] < t && t < times[i + 1])) continue;  // an interval too short for these fractions
      require_equal_to_cpu_slice(s, M, N4, t);
      ++checked;
    }
  }
  REQUIRE(checked >= 12);
}
