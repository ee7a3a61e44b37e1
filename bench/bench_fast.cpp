// FAST (Jacobson 2013 ch. 7) precompute, switch and iteration times against Table 7.1, on
//  * armadillo.obj with 10 point handles (farthest-point surface vertices, BBW bind), the spokes-and-rims
//    energy on the surface and the tet energy on the bind's volume;
//  * hand.mesh with its 20 bones (BBW bind on the tet mesh), the tet energy.
// Next to the static iteration, the same drag with dynamics (7.7): one time step per call, its
// right-hand side (a Mt Y) set per step, 1 or 4 iterations per step.
// Per iteration the figure is the mean over a simulated drag (the target moves every iteration); the
// baseline in the same process is one CPU LBS of the display mesh with every weight (what posing costs).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "core/bind/bind.h"
#include "core/mesh/io.h"
#include "core/pose/fast_dynamics.h"
#include "core/pose/fast_model.h"
#include "core/pose/fast_rig.h"
#include "core/pose/fast_solver.h"
#include "core/rig/rig_io.h"
#include "core/skin/skin.h"
#include "core/bind/numeric_setup.h"

using Clock = std::chrono::steady_clock;

static double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct Case {
  std::string name;
  Eigen::MatrixXd V;           // energy mesh
  Eigen::MatrixXi elements;
  Eigen::MatrixXd W;
  Eigen::MatrixXd display_V;   // what is drawn (LBS baseline)
  Eigen::MatrixXd display_W;
  dfm::Rig rig;
  std::vector<int> free_a, free_b;  // two constraint sets, for the switch
  int dragged = 0;                  // a position-constrained handle whose target moves
};

static void run_case(const Case& c) {
  auto t0 = Clock::now();
  const dfm::FastModel model = dfm::fast_model(c.V, c.elements, c.W);
  const double precompute = seconds_since(t0);
  std::printf("%s: %d energy vertices, %d %s, %d handles, r = %d\n", c.name.c_str(), static_cast<int>(c.V.rows()),
              static_cast<int>(c.elements.rows()), c.elements.cols() == 4 ? "tets" : "triangles", model.handles,
              model.clusters);
  std::printf("  precompute %.3f s (k-means %.3f s, reduction %.3f s)    Table 7.1 armadillo: 8.365 s\n", precompute,
              model.cluster_seconds, model.assembly_seconds);
  std::vector<dfm::FastConstraint> ca = dfm::default_fast_constraints(c.rig, c.free_a);
  std::vector<dfm::FastConstraint> cb = dfm::default_fast_constraints(c.rig, c.free_b);
  for (auto* set : {&ca, &cb}) {
    (*set)[c.dragged].state = dfm::HandleConstraint::Position;
    (*set)[c.dragged].anchor = dfm::handle_anchor(c.rig, c.dragged);
  }
  double switch_s = 0;
  const int switches = 10;
  for (int s = 0; s < switches; ++s) switch_s += dfm::FastSolver(model, s % 2 ? cb : ca).switch_seconds();
  dfm::FastSolver solver(model, ca);
  std::printf("  switch %.2f ms (mean of %d)                          Table 7.1 armadillo: 15 ms\n",
              1e3 * switch_s / switches, switches);

  const double diag = (c.V.colwise().maxCoeff() - c.V.colwise().minCoeff()).norm();
  dfm::Pose pose = dfm::identity_pose(model.handles);
  // A drag: over `steps` calls the target slides 10% of the diagonal; each call runs `count` iterations
  // (count 8 in one call is how the editor runs a frame: rotation space in between). Seconds per iteration.
  auto drag = [&](int steps, int count) {
    double s = 0;
    for (int k = 0; k < steps; ++k) {
      pose.transforms[c.dragged] = Eigen::Translation3d(Eigen::Vector3d(0.1 * diag * k / steps, 0, 0));
      solver.set_targets(pose, dfm::fast_targets(ca, pose));
      t0 = Clock::now();
      if (count == 1) solver.iterate(pose, false);
      else solver.iterate(pose, count);
      s += seconds_since(t0);
    }
    return s / (static_cast<double>(steps) * count);
  };
  const int iterations = 5000, frames = iterations / 8;
  const double per_iteration_us = 1e6 * drag(iterations, 1);
  // The same with set_targets in the timed part, as a dynamics step has its right-hand side in it.
  double with_targets_s = 0;
  for (int k = 0; k < iterations; ++k) {
    pose.transforms[c.dragged] = Eigen::Translation3d(Eigen::Vector3d(0.1 * diag * k / iterations, 0, 0));
    const std::vector<Eigen::Vector3d> targets = dfm::fast_targets(ca, pose);
    t0 = Clock::now();
    solver.set_targets(pose, targets);
    solver.iterate(pose, false);
    with_targets_s += seconds_since(t0);
  }
  const double with_targets_us = 1e6 * with_targets_s / iterations;
  const double batched_us = 1e6 * drag(frames, 8);
  const dfm::SkinBinding binding = dfm::make_skin_binding(c.display_V, Eigen::MatrixXd(), c.display_W, c.rig, 0);
  double lbs_s = 1e300;
  for (int r = 0; r < 5; ++r) {
    t0 = Clock::now();
    const dfm::SkinResult res = dfm::skin(dfm::SkinMethod::LBS, binding, pose, {});
    lbs_s = std::min(lbs_s, seconds_since(t0));
  }
  std::printf("  one iteration %.2f us (mean of %d)                   Table 7.1 armadillo: 20 us\n", per_iteration_us,
              iterations);
  std::printf("  one iteration %.2f us in frames of 8 (mean of %d frames); ratio to single calls %.2f\n",
              batched_us, frames, batched_us / per_iteration_us);
  // Dynamics on the same constraints (7.7.2): the switch with the momentum term, then steps of the drag.
  t0 = Clock::now();
  const dfm::FastMass mass = dfm::fast_mass(c.V, c.elements, c.W);
  const double mass_s = seconds_since(t0);
  for (const int per_step : {1, 4}) {
    dfm::FastDynamicsOptions opts;
    opts.iterations = per_step;
    dfm::FastDynamics dyn(model, mass, ca, {}, opts, dfm::identity_pose(model.handles));
    dfm::Pose p = dfm::identity_pose(model.handles);
    const int steps = 5000 / per_step;
    double s = 0;
    for (int k = 0; k < steps; ++k) {
      p.transforms[c.dragged] = Eigen::Translation3d(Eigen::Vector3d(0.1 * diag * k / steps, 0, 0));
      const std::vector<Eigen::Vector3d> targets = dfm::fast_targets(ca, p);
      t0 = Clock::now();
      dyn.step(p, targets);
      s += seconds_since(t0);
    }
    if (per_step == 1)
      std::printf("  dynamics: mass W^T M W %.3f s, switch with momentum %.2f ms\n", mass_s,
                  1e3 * dyn.solver().switch_seconds());
    std::printf("  dynamics: one step of %d iteration%s %.2f us, %.2f us per iteration (mean of %d steps); "
                "static: set_targets + 1 iteration %.2f us\n",
                per_step, per_step > 1 ? "s" : "", 1e6 * s / steps, 1e6 * s / (steps * per_step), steps,
                with_targets_us);
  }
  std::printf("  CPU LBS of the %d display vertices (baseline): %.3f ms; iteration / LBS = %.4f\n",
              static_cast<int>(c.display_V.rows()), 1e3 * lbs_s, 1e-6 * per_iteration_us / lbs_s);
}

// The process-wide numeric settings (core/bind/numeric_setup.h): serial OpenMP regions here,
// setup_numerics() first thing in main.
DFM_RUN_OPENMP_REGIONS_SERIALLY()

int main(int argc, char** argv) {
  dfm::setup_numerics();  // before any bind (numeric_setup.h)
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  const std::string data = argc > 1 ? argv[1] : std::string(DFM_DATA_DIR);
  {
    const dfm::TriMesh mesh = dfm::read_surface(data + "/armadillo.obj");
    Case c;
    std::vector<double> dist(mesh.V.rows(), 1e300);
    int next = 0;
    for (int h = 0; h < 10; ++h) {
      c.rig.points.push_back({mesh.V.row(next).transpose(), "point " + std::to_string(h + 1)});
      for (int i = 0; i < mesh.V.rows(); ++i) dist[i] = std::min(dist[i], (mesh.V.row(i) - mesh.V.row(next)).norm());
      next = static_cast<int>(std::max_element(dist.begin(), dist.end()) - dist.begin());
    }
    const auto t0 = Clock::now();
    const dfm::BindResult bind = dfm::bind_surface(mesh, c.rig);
    std::printf("armadillo: bind %.1f s (not part of FAST)\n", seconds_since(t0));
    c.free_a = {7, 8, 9};
    c.free_b = {5, 6};
    c.dragged = 0;
    c.display_V = mesh.V;
    c.display_W = bind.weights;
    c.name = "armadillo, spokes and rims";
    c.V = mesh.V, c.elements = mesh.F, c.W = bind.weights;
    run_case(c);
    c.name = "armadillo, tets of the bind volume";
    c.V = bind.volume.tets.V, c.elements = bind.volume.tets.T, c.W = bind.tet_weights;
    run_case(c);
  }
  {
    const dfm::TetMesh tets = dfm::read_tet_mesh(data + "/hand.mesh");
    Case c;
    dfm::add_tgf_to_rig(c.rig, dfm::read_tgf(data + "/hand.tgf"), "hand.tgf");
    const dfm::BindResult bind = dfm::bind_tet_mesh(tets, c.rig);
    c.name = "hand, 20 bones, tets";
    c.V = tets.V, c.elements = tets.T, c.W = bind.weights;
    c.display_V = tets.V, c.display_W = bind.weights;
    c.free_a = {3, 4, 5, 6};
    c.free_b = {8, 9, 10};
    c.dragged = 7;  // its tip is dragged (IK)
    run_case(c);
  }
  return 0;
}
