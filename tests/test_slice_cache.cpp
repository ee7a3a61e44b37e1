// app/editor/slice_cache: when the editor draws a time slice from a cached interval, builds one, or
// runs the general per-tetrahedron pass (no GL); app/editor/interval_prefetch: the next interval's
// topology built on a worker equals the one built in place.
#include <cmath>
#include <cstring>
#include <memory>

#include <catch2/catch.hpp>

#include "app/editor/interval_prefetch.h"
#include "app/editor/slice_cache.h"
#include "core/anim/manifold_normals.h"
#include "tests/interval_slice_test_manifolds.h"

using dfm::editor::IntervalCachePolicy;
using dfm::editor::IntervalPrefetch;
using dfm::editor::SliceDecision;
using dfm::editor::SliceRoute;

namespace {
const double kStep = 1.0 / 30.0;
}

TEST_CASE("slice cache: build once per interval, then draw from it", "[editor][interval]") {
  IntervalCachePolicy p(2);
  p.reset({0.0, 0.2, 0.4, 1.0});
  SliceDecision d = p.choose(true, 0.05, kStep);
  REQUIRE(d.route == SliceRoute::Build);
  REQUIRE(d.interval == 0);
  const int slot0 = d.slot;
  REQUIRE(p.slot_interval(slot0) == 0);
  for (double t = 0.05 + kStep; t < 0.2; t += kStep) {
    d = p.choose(true, t, kStep);
    REQUIRE(d.route == SliceRoute::Cached);
    REQUIRE(d.slot == slot0);
  }
  REQUIRE(p.builds() == 1);
  // Crossing the boundary builds the next interval, in the other slot.
  d = p.choose(true, 0.21, kStep);
  REQUIRE(d.route == SliceRoute::Build);
  REQUIRE(d.interval == 1);
  REQUIRE(d.slot != slot0);
  const int slot1 = d.slot;
  REQUIRE(p.builds() == 2);
  // Back into the first: still cached (a small cache of recent intervals).
  d = p.choose(true, 0.1, kStep);
  REQUIRE(d.route == SliceRoute::Cached);
  REQUIRE(d.slot == slot0);
  // A third interval evicts the least recently used one (interval 1, not the one just drawn).
  d = p.choose(true, 0.5, kStep);
  REQUIRE(d.route == SliceRoute::Build);
  REQUIRE(d.interval == 2);
  REQUIRE(d.slot == slot1);
  REQUIRE(p.slot_interval(slot0) == 0);
  d = p.choose(true, 0.3, kStep);
  REQUIRE(d.route == SliceRoute::Build);  // interval 1 was evicted: rebuilt
  REQUIRE(d.slot == slot0);               // ...over interval 0, now the least recent
  REQUIRE(p.builds() == 4);
}

TEST_CASE("slice cache: the general pass where the cache does not apply", "[editor][interval]") {
  IntervalCachePolicy p(4);
  p.reset({0.0, 0.2, 0.4, 1.0});
  // The x, y, z sweep.
  REQUIRE(p.choose(false, 0.1, 0.0).route == SliceRoute::General);
  // On a vertex time with no neighbouring interval cached, before the start and after the end.
  for (double t : {0.0, 0.2, 0.4, 1.0, -0.5, 1.5}) {
    const SliceDecision d = p.choose(true, t, kStep);
    REQUIRE(d.route == SliceRoute::General);
    REQUIRE(d.slot == -1);
  }
  REQUIRE(p.builds() == 0);
  // A vertex time next to a cached interval draws from it (its limit there).
  const SliceDecision built = p.choose(true, 0.3, kStep);  // interval 1, (0.2, 0.4)
  REQUIRE(built.route == SliceRoute::Build);
  for (double t : {0.2, 0.4}) {
    const SliceDecision d = p.choose(true, t, kStep);
    REQUIRE(d.route == SliceRoute::Cached);
    REQUIRE(d.interval == 1);
    REQUIRE(d.slot == built.slot);
  }
  REQUIRE(p.choose(true, 0.0, kStep).route == SliceRoute::General);  // interval 0 is not cached
  REQUIRE(p.choose(true, 1.5, kStep).route == SliceRoute::General);
  REQUIRE(p.builds() == 1);
  // No manifold (fewer than two vertex times).
  IntervalCachePolicy empty;
  REQUIRE(empty.choose(true, 0.5, 0.0).route == SliceRoute::General);
  empty.reset({1.0});
  REQUIRE(empty.choose(true, 1.0, 0.0).route == SliceRoute::General);
}

TEST_CASE("slice cache: an interval shorter than the frame step is not worth building", "[editor][interval]") {
  // A transition's many vertex times: intervals of 0.001 while playback steps 1/30 a frame.
  std::vector<double> times;
  for (int i = 0; i <= 1000; ++i) times.push_back(i * 0.001);
  times.push_back(2.0);  // and one long interval (1, 2)
  IntervalCachePolicy p(4);
  p.reset(times);
  for (double t = 0.0005; t < 1.0; t += kStep) REQUIRE(p.choose(true, t, kStep).route == SliceRoute::General);
  REQUIRE(p.builds() == 0);
  // Backwards steps count by their size.
  REQUIRE(p.choose(true, 0.5005, -kStep).route == SliceRoute::General);
  // A still frame (step 0, e.g. a scrub that stopped) or a small step does build the short interval...
  SliceDecision d = p.choose(true, 0.5005, 0.0);
  REQUIRE(d.route == SliceRoute::Build);
  REQUIRE(d.interval == 500);
  // ...and once built it is used whatever the step.
  REQUIRE(p.choose(true, 0.5006, kStep).route == SliceRoute::Cached);
  // The long interval is cached at playback speed.
  REQUIRE(p.choose(true, 1.2, kStep).route == SliceRoute::Build);
  REQUIRE(p.choose(true, 1.2 + kStep, kStep).route == SliceRoute::Cached);
  // A failed build is forgotten; a new manifold forgets everything.
  d = p.choose(true, 1.5, kStep);
  REQUIRE(d.route == SliceRoute::Cached);
  p.forget(d.slot);
  REQUIRE(p.choose(true, 1.5, kStep).route == SliceRoute::Build);
  p.reset(times);
  REQUIRE(p.builds() == 0);
  REQUIRE(p.choose(true, 1.5, kStep).route == SliceRoute::Build);
}

// Issue 38: between prism layers the frame is the layers' mesh, which only a built interval draws;
// building it is a copy, so it is built however short, and on a vertex time at its ends too.
TEST_CASE("slice cache: prism intervals are always built, on their ends too", "[editor][interval]") {
  IntervalCachePolicy p(4);
  // Interval 0 (0, 0.01) is a prism slab's and shorter than the frame step; interval 1 a transition's.
  p.reset({0.0, 0.01, 0.012, 1.0}, {true, false, true});
  SliceDecision d = p.choose(true, 0.005, kStep);
  REQUIRE(d.route == SliceRoute::Build);
  REQUIRE(d.interval == 0);
  REQUIRE(p.choose(true, 0.011, kStep).route == SliceRoute::General);  // the short transition interval
  // On the vertex time 1.0 (the end of prism interval 2, nothing cached there): built, not the general pass.
  d = p.choose(true, 1.0, kStep);
  REQUIRE(d.route == SliceRoute::Build);
  REQUIRE(d.interval == 2);
  REQUIRE(p.choose(true, 1.0, kStep).route == SliceRoute::Cached);
  REQUIRE(p.builds() == 2);
  // The flags come from the manifold: a prism build's intervals are all prism ones, the same
  // tetrahedra without the records none.
  const dfm::AnimationManifold m = dfm::test::deforming_sphere_manifold();
  const std::vector<double> times = {0.0, 1.0, 2.5};
  CHECK(dfm::editor::prism_intervals(m, times) == std::vector<bool>{true, true});
  CHECK(dfm::editor::prism_intervals(dfm::test::without_prism_records(m), times) == std::vector<bool>{false, false});
}

TEST_CASE("slice cache: the interval playback reaches next, and which are cached", "[editor][interval]") {
  IntervalCachePolicy p(2);
  p.reset({0.0, 0.2, 0.4, 1.0});  // intervals 0, 1, 2
  REQUIRE(p.next_interval(0, kStep) == 1);
  REQUIRE(p.next_interval(0, 0.0) == 1);    // a still frame looks forward
  REQUIRE(p.next_interval(2, kStep) == 0);  // a looping timeline wraps to the start
  REQUIRE(p.next_interval(0, -kStep) == 2);  // and backwards to the end
  REQUIRE(p.next_interval(1, -kStep) == 0);
  REQUIRE(p.worth_building(2, kStep));
  REQUIRE_FALSE(p.worth_building(0, 0.25));  // 0.2 long, left within one step of 0.25
  REQUIRE_FALSE(p.worth_building(3, kStep));  // no such interval
  REQUIRE_FALSE(p.cached(1));
  REQUIRE(p.choose(true, 0.3, kStep).route == SliceRoute::Build);
  REQUIRE(p.cached(1));
  REQUIRE_FALSE(p.cached(-1));
  p.reset({});
  REQUIRE(p.next_interval(0, kStep) == -1);
}

TEST_CASE("interval prefetch: the worker's topology is the one built in place", "[editor][interval]") {
  auto m = std::make_shared<const dfm::AnimationManifold>(dfm::test::deforming_sphere_manifold());
  auto n4 = std::make_shared<const Eigen::MatrixXd>(dfm::manifold_vertex_normals(*m));
  const std::vector<double> times = dfm::manifold_vertex_times(*m);
  REQUIRE(times.size() >= 3);
  IntervalPrefetch pf;
  REQUIRE_FALSE(pf.take(0));  // nothing asked for yet
  pf.reset(m, n4, times);
  pf.request(1);
  REQUIRE(pf.interval() == 1);
  REQUIRE_FALSE(pf.take(0));  // not the interval built
  std::optional<dfm::editor::PreparedInterval> got = pf.take(1);  // waits for the worker
  REQUIRE(got);
  const dfm::IntervalSlice ref = dfm::build_interval_slice(*m, *n4, times[1], times[2]);
  REQUIRE(got->topology.edges == ref.edges);
  REQUIRE(got->topology.F == ref.F);
  REQUIRE(got->topology.closed_outward == ref.closed_outward);
  const dfm::gl::IntervalRecords rec = dfm::gl::interval_records(ref, *m, *n4);
  REQUIRE(got->records.indices == rec.indices);
  REQUIRE(got->records.vertices.size() == rec.vertices.size());
  for (size_t v = 0; v < rec.vertices.size(); ++v)
    REQUIRE(std::memcmp(&got->records.vertices[v], &rec.vertices[v], sizeof(rec.vertices[v])) == 0);
  REQUIRE(pf.interval() == -1);  // taken
  REQUIRE_FALSE(pf.take(1));
  // A newer manifold drops the build (the old manifold stays alive for the worker meanwhile).
  pf.request(0);
  pf.reset(m, n4, times);
  REQUIRE_FALSE(pf.take(0));
  // A build that fails (a vertex time inside the interval) gives nothing; the caller's own build says why.
  pf.reset(m, n4, {times[0], times[2]});
  pf.request(0);
  REQUIRE_FALSE(pf.take(0));
  REQUIRE_THROWS(dfm::build_interval_slice(*m, *n4, times[0], times[2]));
}

TEST_CASE("slice cache: growing keeps the cached intervals", "[editor][interval]") {
  IntervalCachePolicy p(2);
  p.reset({0.0, 0.2, 0.4, 0.6, 1.0});
  const SliceDecision a = p.choose(true, 0.1, kStep), b = p.choose(true, 0.3, kStep);
  p.grow(1);  // never fewer
  REQUIRE(p.capacity() == 2);
  p.grow(4);
  REQUIRE(p.capacity() == 4);
  REQUIRE(p.slot_interval(a.slot) == 0);
  REQUIRE(p.slot_interval(b.slot) == 1);
  REQUIRE(p.choose(true, 0.5, kStep).route == SliceRoute::Build);  // into a new slot...
  REQUIRE(p.choose(true, 0.8, kStep).route == SliceRoute::Build);
  REQUIRE(p.choose(true, 0.15, kStep).route == SliceRoute::Cached);  // ...evicting nothing
  REQUIRE(p.choose(true, 0.35, kStep).route == SliceRoute::Cached);
  REQUIRE(p.builds() == 4);
}
