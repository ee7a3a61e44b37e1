// Red-green refinement of triangle lists and space-time edits that refine what they stretch (Southern
// 2008, 4.5.1; issue 35): core/mesh/red_green_refine.h, core/anim/manifold_refine.h.
#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "core/anim/manifold.h"
#include "core/anim/manifold_frame.h"
#include "core/anim/manifold_refine.h"
#include "core/mesh/red_green_refine.h"
#include "core/util/error.h"
#include "tests/transition_test_meshes.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;

namespace {

// A still sphere (radius 1, at the origin) at times 0, 1, ..., 4, joined by the prism build.
AnimationManifold still_sphere(int levels) {
  const TriMesh s = dfm::test::icosphere(Eigen::Vector3d::Zero(), 1.0, levels);
  return build_manifold(std::vector<Eigen::MatrixXd>(5, s.V), s.F, {0, 1, 2, 3, 4});
}

double area(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  double a = 0;
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d p = V.row(F(f, 0)), q = V.row(F(f, 1)), r = V.row(F(f, 2));
    a += 0.5 * (q - p).cross(r - p).norm();
  }
  return a;
}

// Every directed edge once and its reverse once: closed, consistently oriented, no hanging vertex.
bool conforming(const Eigen::MatrixXi& F) {
  std::map<std::pair<int, int>, int> directed;
  for (int f = 0; f < F.rows(); ++f)
    for (int j = 0; j < 3; ++j) ++directed[{F(f, j), F(f, (j + 1) % 3)}];
  for (const auto& [e, n] : directed)
    if (n != 1 || !directed.count({e.second, e.first})) return false;
  return true;
}

// The farthest a vertex of a lies from the surface b, and the other way (brute force).
double two_sided_distance(const TriMesh& a, const TriMesh& b) {
  auto one_way = [](const TriMesh& x, const TriMesh& y) {
    double worst = 0;
    for (int i = 0; i < x.V.rows(); ++i) {
      double best = 1e300;
      for (int f = 0; f < y.F.rows(); ++f)
        best = std::min(best, dfm::test::point_triangle_distance(x.V.row(i).transpose(), y.V.row(y.F(f, 0)).transpose(),
                                                                  y.V.row(y.F(f, 1)).transpose(), y.V.row(y.F(f, 2)).transpose()));
      worst = std::max(worst, best);
    }
    return worst;
  };
  return std::max(one_way(a, b), one_way(b, a));
}

struct Spike {
  EditRegionSpec region;
  EditHandleSpec handle;
  ManifoldDrag drag;
  Spike() {
    region.center = Eigen::Vector3d(0, 1, 0);
    region.radius = 0.6;
    region.t0 = 1;
    region.t1 = 3;
    handle.point = Eigen::Vector3d(0, 1, 0);
    handle.time = 2;
    drag.translation = Eigen::Vector3d(0, 1.2, 0);
  }
};

}  // namespace

TEST_CASE("red-green refinement: marked triangles 1:4, closed and conforming, the surface unchanged", "[manifold_refine]") {
  const TriMesh s = dfm::test::icosphere(Eigen::Vector3d::Zero(), 1.0, 2);
  const int n = static_cast<int>(s.V.rows());
  const RedGreenRefinement none = red_green_refine(s.F, n, std::vector<char>(s.F.rows(), 0));
  CHECK(none.F == s.F);
  CHECK(none.middles.empty());
  // One red triangle: its 3 edges split, each of its 3 neighbours bisected.
  std::vector<char> one(s.F.rows(), 0);
  one[7] = 1;
  const RedGreenRefinement r1 = red_green_refine(s.F, n, one);
  CHECK(r1.middles.size() == 3);
  CHECK(r1.F.rows() == s.F.rows() + 3 + 3);
  CHECK(conforming(r1.F));
  std::mt19937 rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<char> red(s.F.rows(), 0);
    for (char& c : red) c = rng() % 7 == 0;
    const RedGreenRefinement r = red_green_refine(s.F, n, red);
    INFO("trial " << trial);
    CHECK(conforming(r.F));
    // Every marked triangle's edges are split; each middle is the midpoint of a triangle edge.
    std::map<std::pair<int, int>, int> mid;
    for (size_t i = 0; i < r.middles.size(); ++i) mid[{r.middles[i][0], r.middles[i][1]}] = n + static_cast<int>(i);
    for (int f = 0; f < s.F.rows(); ++f)
      if (red[f])
        for (int j = 0; j < 3; ++j) CHECK(mid.count({std::min(s.F(f, j), s.F(f, (j + 1) % 3)), std::max(s.F(f, j), s.F(f, (j + 1) % 3))}));
    const Eigen::MatrixXd V = append_middles(s.V, r.middles);
    CHECK(V.rows() == n + static_cast<Eigen::Index>(r.middles.size()));
    CHECK(V.topRows(n) == s.V);
    CHECK(area(V, r.F) == Approx(area(s.V, s.F)).epsilon(1e-12));
    // Euler characteristic of the closed surface stays 2.
    CHECK(V.rows() - static_cast<Eigen::Index>(r.F.rows()) * 3 / 2 + r.F.rows() == 2);
  }
  CHECK_THROWS_AS(red_green_refine(s.F, n, std::vector<char>(3, 1)), Error);
  CHECK_THROWS_AS(red_green_refine(s.F, n - 1, one), Error);
}

TEST_CASE("a pulled spike refined (4.5.1 on the layer mesh): closer to the same pull on a finer sphere, prisms kept",
          "[manifold_refine]") {
  const Spike spike;
  const ManifoldEditOptions options;
  RefineOptions none;
  none.max_rounds = 0;
  const AnimationManifold m = still_sphere(3);  // 642 vertices a layer
  RefineStats plain_stats, stats;
  const AnimationManifold plain = edit_refined(m, spike.region, spike.handle, options, spike.drag, none, &plain_stats);
  const AnimationManifold refined = edit_refined(m, spike.region, spike.handle, options, spike.drag, {}, &stats);
  // The reference: the same pull on a sphere subdivided once more from the start.
  const AnimationManifold fine = edit_refined(still_sphere(4), spike.region, spike.handle, options, spike.drag, none);
  INFO(stats.added << " vertices added a layer in " << stats.rounds << " rounds; longest region edge " << plain_stats.longest
                   << " -> " << stats.longest << " mean lengths");
  CHECK(plain_stats.added == 0);
  CHECK(plain_stats.longest > 2);  // the pull stretched edges past the tolerance
  CHECK(stats.rounds == 1);
  CHECK(stats.added > 0);
  CHECK(stats.longest < plain_stats.longest);
  REQUIRE_NOTHROW(validate_manifold(refined, "refined"));
  // Every slab is still a prism slab: frames between layers are the layers' interpolation.
  REQUIRE(refined.prism_slabs.size() == static_cast<size_t>(refined.num_slabs()));
  for (const PrismSlab& p : refined.prism_slabs) CHECK(p.is_prism());
  const int n = m.prism_slabs.front().count, rn = refined.prism_slabs.front().count;
  CHECK(rn == n + stats.added);
  // Each new vertex sits at the middle of a layer edge (layer 0, unedited) and is numbered between that
  // edge's ends, so the prism staircase gives it time edges to both neighbouring layers.
  {
    const Eigen::MatrixXi& F = refined.layer_faces[refined.prism_slabs.front().faces];
    std::vector<std::vector<int>> ring(static_cast<size_t>(rn));
    for (int f = 0; f < F.rows(); ++f)
      for (int j = 0; j < 3; ++j) ring[F(f, j)].push_back(F(f, (j + 1) % 3));
    std::vector<char> original(static_cast<size_t>(rn), 0);
    for (int v : stats.layer_index) original[v] = 1;
    int between = 0, middles = 0;
    for (int v = 0; v < rn; ++v) {
      if (original[v]) continue;
      ++middles;
      bool found = false;
      for (int a : ring[v])
        for (int b : ring[v])
          found = found || (a < v && v < b && refined.V.row(v) == 0.5 * (refined.V.row(a) + refined.V.row(b)));
      between += found;
    }
    CHECK(middles == stats.added);
    CHECK(between == middles);
  }
  // The handle lands where it is dragged.
  CHECK(manifold_frame(refined, 2.0).mesh.V.col(1).maxCoeff() == Approx(2.2).epsilon(1e-12));
  // Outside the window the surface is the original's: its vertices bit for bit, the new ones at middles.
  REQUIRE(stats.layer_index.size() == static_cast<size_t>(n));
  for (int layer : {0, 4}) {
    for (int v = 0; v < n; ++v) CHECK(refined.V.row(layer * rn + stats.layer_index[v]) == m.V.row(layer * n + v));
    const TriMesh a = manifold_frame(m, layer).mesh, b = manifold_frame(refined, layer).mesh;
    CHECK(area(b.V, b.F) == Approx(area(a.V, a.F)).epsilon(1e-12));
  }
  // Inside, the frames lie closer to the finer sphere's.
  for (double t : {1.5, 2.0, 2.5}) {
    const TriMesh r = manifold_frame(fine, t).mesh, a = manifold_frame(plain, t).mesh, b = manifold_frame(refined, t).mesh;
    const double diag = (r.V.colwise().maxCoeff() - r.V.colwise().minCoeff()).norm();
    const double da = two_sided_distance(a, r) / diag, db = two_sided_distance(b, r) / diag;
    INFO("t = " << t << ": farthest from the finer sphere's pull " << da << " -> " << db << " of the diagonal, " << a.F.rows()
                << " -> " << b.F.rows() << " triangles");
    CHECK(db < 0.6 * da);
    CHECK(b.F.rows() > a.F.rows());
    CHECK(dfm::test::euler_characteristic(b.F) == 2);
    CHECK(conforming(b.F));
  }
  // Refused, m unchanged: a manifold not all prisms of one mesh, and bad options.
  AnimationManifold mixed = m;
  mixed.prism_slabs[1] = PrismSlab{};
  CHECK_THROWS_AS(edit_refined(mixed, spike.region, spike.handle, options, spike.drag), Error);
  RefineOptions bad;
  bad.stretch = 1;
  CHECK_THROWS_AS(edit_refined(m, spike.region, spike.handle, options, spike.drag, bad), Error);
}
