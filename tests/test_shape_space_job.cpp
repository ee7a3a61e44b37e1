// The Shape space panel's worker (app/editor/shape_space_job): a newer request supersedes an older
// one (a waiting one never runs, a running one's result is dropped), a cancelled request yields
// nothing, and an ARAP synthesis (Alexa 2002, 5.5.1, Eq. 5.31's chain) run on the worker over a shared,
// cached ShapeSpace equals the synchronous synthesis of a fresh space bit for bit. The panel's cursor
// (app/editor/shape_space_cursor): the linear blend (Eq. 5.36, written here) stands in while ARAP
// runs, a shape for an older cursor never shows, dragging and Cancel drop the request.
#include <atomic>
#include <chrono>
#include <future>
#include <memory>
#include <thread>

#include <catch2/catch.hpp>
#include <Eigen/Geometry>

#include "app/editor/shape_space_cursor.h"
#include "app/editor/shape_space_job.h"
#include "core/anim/shape_space.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;
using dfm::editor::CursorShape;
using dfm::editor::ShapeSpaceJob;

namespace {

// Spins (briefly sleeping) until flag is set; false after 5 s.
bool wait_for(const std::atomic<bool>& flag) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (!flag.load()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

// A request that records that it ran, blocks until `gate` opens, and returns a 1x1 matrix holding v.
struct Gated {
  std::promise<void> open;
  std::shared_future<void> gate{open.get_future().share()};
  std::atomic<bool> started{false}, finished{false};
  ShapeSpaceJob::Synthesize fn(double v) {
    return [this, v] {
      started = true;
      gate.wait();
      finished = true;
      return Eigen::MatrixXd::Constant(1, 1, v);
    };
  }
};

// A bar: the level-1 icosphere stretched 3x along x (closed, 42 vertices: TetGen takes milliseconds).
TriMesh bar() {
  TriMesh m = test::icosphere(Eigen::Vector3d::Zero(), 0.3, 1);
  m.V.col(0) *= 3.0;
  return m;
}

// Three bases of one connectivity: the bar, the bar bent (its right half turned 40 degrees about z)
// and the bar twisted about x.
std::vector<TriMesh> bent_bars() {
  const TriMesh b0 = bar();
  TriMesh b1 = b0, b2 = b0;
  for (int i = 0; i < b0.V.rows(); ++i) {
    const Eigen::Vector3d p = b0.V.row(i).transpose();
    if (p.x() > 0) b1.V.row(i) = (Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) * p).transpose();
    b2.V.row(i) = (Eigen::AngleAxisd(0.8 * p.x(), Eigen::Vector3d::UnitX()) * p).transpose();
  }
  return {b0, b1, b2};
}

// Eq. 5.36: sum_i x_i B_i.
Eigen::MatrixXd affine_combination(const std::vector<TriMesh>& B, const Eigen::VectorXd& x) {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(B[0].V.rows(), 3);
  for (size_t i = 0; i < B.size(); ++i) out += x(i) * B[i].V;
  return out;
}

Eigen::VectorXd coords(double a, double b, double c) { return Eigen::Vector3d(a, b, c); }

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && (a.array() == b.array()).all();
}

}  // namespace

TEST_CASE("shape space job: a newer request supersedes an older one", "[editor][shape_space]") {
  ShapeSpaceJob job;
  Gated a, c;
  std::atomic<bool> b_ran{false};
  const std::uint64_t ia = job.post(a.fn(1.0));
  REQUIRE(wait_for(a.started));  // a runs on the worker
  CHECK(job.running());
  const std::uint64_t ib = job.post([&] {
    b_ran = true;
    return Eigen::MatrixXd::Constant(1, 1, 2.0);
  });
  const std::uint64_t ic = job.post(c.fn(3.0));  // b was still waiting: it never runs
  CHECK(ia < ib);
  CHECK(ib < ic);
  CHECK(job.wanted() == ic);
  CHECK_FALSE(job.take());
  a.open.set_value();  // a ends while c is wanted: its result is dropped
  REQUIRE(wait_for(c.started));
  CHECK(a.finished.load());
  CHECK_FALSE(job.take());
  CHECK(job.waiting());
  c.open.set_value();
  REQUIRE(job.wait_idle(5.0));
  CHECK_FALSE(b_ran.load());
  const auto r = job.take();
  REQUIRE(r);
  CHECK(r->id == ic);
  CHECK(r->error.empty());
  REQUIRE(r->V.size() == 1);
  CHECK(r->V(0, 0) == 3.0);
  CHECK_FALSE(job.waiting());  // taken once
  CHECK_FALSE(job.take());
}

TEST_CASE("shape space job: a cancelled request yields nothing", "[editor][shape_space]") {
  ShapeSpaceJob job;
  SECTION("cancelled while it runs") {
    Gated a;
    job.post(a.fn(1.0));
    REQUIRE(wait_for(a.started));
    job.cancel();
    CHECK_FALSE(job.waiting());
    CHECK(job.elapsed_seconds() == 0.0);
    a.open.set_value();
    REQUIRE(job.wait_idle(5.0));
    CHECK(a.finished.load());
    CHECK_FALSE(job.take());
  }
  SECTION("cancelled while it waits: it never runs") {
    Gated a;
    std::atomic<bool> b_ran{false};
    job.post(a.fn(1.0));
    REQUIRE(wait_for(a.started));
    job.post([&] {
      b_ran = true;
      return Eigen::MatrixXd();
    });
    job.cancel();
    a.open.set_value();
    REQUIRE(job.wait_idle(5.0));
    CHECK_FALSE(b_ran.load());
    CHECK_FALSE(job.take());
  }
  SECTION("cancelled after it finished, before it was taken") {
    job.post([] { return Eigen::MatrixXd::Constant(1, 1, 4.0); });
    REQUIRE(job.wait_idle(5.0));
    job.cancel();
    CHECK_FALSE(job.take());
  }
  // A later request still runs after a cancel.
  const std::uint64_t id = job.post([] { return Eigen::MatrixXd::Constant(2, 3, 5.0); });
  REQUIRE(job.wait_idle(5.0));
  const auto r = job.take();
  REQUIRE(r);
  CHECK(r->id == id);
  CHECK(r->V.rows() == 2);
}

TEST_CASE("shape space job: errors come back as text; the destructor waits for a running request",
          "[editor][shape_space]") {
  Gated a;
  std::thread opener;
  {
    ShapeSpaceJob job;
    job.post([] () -> Eigen::MatrixXd { throw std::runtime_error("TetGen refused base 1"); });
    REQUIRE(job.wait_idle(5.0));
    const auto r = job.take();
    REQUIRE(r);
    CHECK(r->error == "TetGen refused base 1");
    CHECK(r->V.size() == 0);
    job.post(a.fn(1.0));
    REQUIRE(wait_for(a.started));
    opener = std::thread([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      a.open.set_value();
    });
  }  // ~ShapeSpaceJob joins: the running request has ended
  CHECK(a.finished.load());
  opener.join();
}

// Eq. 5.31's chain as rigid as possible over the three bars, at weights with all three nonzero (two
// ARAP steps, the second carrying a synthesized target through a base's tets) and with two.
TEST_CASE("shape space job: ARAP on the worker equals core's synchronous synthesis bit for bit",
          "[editor][shape_space]") {
  const std::vector<TriMesh> bases = bent_bars();
  const TriMesh& b0 = bases[0];
  const Eigen::VectorXd x1 = coords(0.3, 0.4, 0.3), x2 = coords(0.0, 0.6, 0.4);
  // References: a fresh space each, synthesized on this thread.
  const Eigen::MatrixXd ref1 = ShapeSpace(bases, {}, ShapeMorph::Arap).synthesize(x1);
  const Eigen::MatrixXd ref2 = ShapeSpace(bases, {}, ShapeMorph::Arap).synthesize(x2);
  REQUIRE(ref1.rows() == b0.V.rows());
  REQUIRE((ref1 - b0.V).norm() > 0.1);  // not a base
  REQUIRE((ref1 - ref2).norm() > 0.1);

  // One shared space across requests, as the panel keeps it: its cache serves the second request.
  auto space = std::make_shared<ShapeSpace>(bases, std::vector<std::string>{}, ShapeMorph::Arap);
  ShapeSpaceJob job;
  const std::thread::id ui = std::this_thread::get_id();
  std::atomic<bool> off_thread{true};
  auto request = [&](const Eigen::VectorXd& x) {
    return [space, x, ui, &off_thread] {
      off_thread = off_thread && std::this_thread::get_id() != ui;
      return space->synthesize(x);
    };
  };
  job.post(request(x1));
  REQUIRE(job.wait_idle(30.0));
  const auto r1 = job.take();
  REQUIRE(r1);
  INFO(r1->error);
  CHECK(same_bits(r1->V, ref1));
  job.post(request(x2));
  REQUIRE(job.wait_idle(30.0));
  const auto r2 = job.take();
  REQUIRE(r2);
  CHECK(same_bits(r2->V, ref2));
  CHECK(off_thread.load());
  // Coordinates that do not sum to 1: core's message comes back.
  Eigen::VectorXd bad(3);
  bad << 0.5, 0.5, 0.5;
  job.post(request(bad));
  REQUIRE(job.wait_idle(30.0));
  const auto r3 = job.take();
  REQUIRE(r3);
  CHECK(r3->error.find("sum to") != std::string::npos);
}

TEST_CASE("shape space cursor: the linear blend stands in while ARAP runs; an older cursor's shape never shows",
          "[editor][shape_space]") {
  const std::vector<TriMesh> bases = bent_bars();
  const Eigen::VectorXd x1 = coords(0.3, 0.4, 0.3), x2 = coords(0.2, 0.2, 0.6);
  const Eigen::MatrixXd ref1 = ShapeSpace(bases, {}, ShapeMorph::Arap).synthesize(x1);
  const Eigen::MatrixXd ref2 = ShapeSpace(bases, {}, ShapeMorph::Arap).synthesize(x2);
  REQUIRE((ref2 - affine_combination(bases, x2)).norm() > 1e-3);  // ARAP is not the stand-in
  auto space = std::make_shared<ShapeSpace>(bases, std::vector<std::string>{}, ShapeMorph::Arap);
  CursorShape c;

  // Dragging: the linear blend at once, nothing asked of the worker.
  CHECK(c.update(space, x1, true));
  CHECK_FALSE(c.waiting());
  CHECK_FALSE(c.is_final());
  CHECK(c.vertices().isApprox(affine_combination(bases, x1), 1e-12));
  // Released: ARAP asked for, the stand-in stays.
  CHECK_FALSE(c.update(space, x1, false));
  CHECK(c.waiting());
  // x1's result is ready on the worker when the cursor has moved on to x2: it is dropped, x2's
  // stand-in shows, and "Key this shape" (final_at) waits for x2's own.
  REQUIRE(c.wait_idle(30.0));
  CHECK(c.update(space, x2, false));
  CHECK(c.weights() == x2);
  CHECK_FALSE(c.is_final());
  CHECK_FALSE(c.final_at(x1));
  CHECK(c.vertices().isApprox(affine_combination(bases, x2), 1e-12));
  CHECK(c.waiting());
  REQUIRE(c.wait_idle(30.0));
  CHECK(c.update(space, x2, false));
  CHECK(c.final_at(x2));
  CHECK(same_bits(c.vertices(), ref2));
  CHECK_FALSE(c.waiting());
  CHECK(c.error().empty());
  // Nothing new at the same cursor; back at x1 the cached space gives core's x1 shape.
  CHECK_FALSE(c.update(space, x2, false));
  CHECK_FALSE(c.waiting());
  c.update(space, x1, false);
  REQUIRE(c.wait_idle(30.0));
  c.update(space, x1, false);
  CHECK(c.final_at(x1));
  CHECK(same_bits(c.vertices(), ref1));
}

TEST_CASE("shape space cursor: dragging and Cancel drop the request; retry asks again", "[editor][shape_space]") {
  const std::vector<TriMesh> bases = bent_bars();
  const Eigen::VectorXd x1 = coords(0.3, 0.4, 0.3), x2 = coords(0.5, 0.25, 0.25);
  const Eigen::MatrixXd ref2 = ShapeSpace(bases, {}, ShapeMorph::Arap).synthesize(x2);
  auto space = std::make_shared<ShapeSpace>(bases, std::vector<std::string>{}, ShapeMorph::Arap);
  CursorShape c;
  c.update(space, x1, false);
  CHECK(c.waiting());
  c.update(space, x2, true);  // the cursor moves again: x1 is no longer wanted
  CHECK_FALSE(c.waiting());
  REQUIRE(c.wait_idle(30.0));
  c.update(space, x2, true);
  CHECK_FALSE(c.is_final());
  CHECK(c.vertices().isApprox(affine_combination(bases, x2), 1e-12));

  c.update(space, x2, false);
  CHECK(c.waiting());
  c.cancel();
  CHECK_FALSE(c.waiting());
  CHECK(c.cancelled());
  REQUIRE(c.wait_idle(30.0));
  c.update(space, x2, false);  // not asked for again by itself
  CHECK_FALSE(c.waiting());
  CHECK_FALSE(c.is_final());
  c.retry();
  c.update(space, x2, false);
  CHECK(c.waiting());
  REQUIRE(c.wait_idle(30.0));
  c.update(space, x2, false);
  CHECK(c.final_at(x2));
  CHECK(same_bits(c.vertices(), ref2));

  // Another space (new bases): starts afresh; a linear space's shape is final at once.
  auto linear = std::make_shared<ShapeSpace>(bases, std::vector<std::string>{}, ShapeMorph::Linear);
  CHECK(c.update(linear, x2, true));
  CHECK(c.final_at(x2));
  CHECK_FALSE(c.waiting());
  CHECK(c.vertices().isApprox(affine_combination(bases, x2), 1e-12));
  CHECK(c.update(nullptr, x2, false));  // no space: nothing shown
  CHECK(c.vertices().rows() == 0);
  CHECK_FALSE(c.update(nullptr, x2, false));
  CHECK_FALSE(CursorShape().update(nullptr, Eigen::VectorXd(), false));
}
