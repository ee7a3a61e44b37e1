// Monotone weights (Jacobson 2013, ch. 5) against the default bounded biharmonic weights, same mesh, same
// process: hand.mesh + hand.tgf (tet input, 20 bones) and arm.obj + arm.tgf (TetGen pq1.414Y, 4 bones).
// Prints the per-function solve time of each (Table 5.1 reports 6.0 s per function for the Beetle,
// 38,656 triangles, k = 2, on a 2012 i7 with MOSEK), the monotone stage's share, and the spurious local
// maxima/minima on the tet edge graph and on the surface.
//   bench_monotone [hand|arm|all] [--threads N] [--unnormalized]
//     --unnormalized: count extrema on each handle's own minimizer, before the rows are normalized
// Monotone runs twice: rows divided by their sums (mono/div) and solved jointly with exact sums (mono/sums).
#include <sys/resource.h>

#include <cstdio>
#include <cstring>
#include <string>

#include "core/bind/bind.h"
#include "core/bind/bind_extrema.h"
#include "core/mesh/io.h"
#include "core/mesh/mesh_info.h"
#include "core/rig/rig_io.h"

namespace {

double cpu_seconds() {  // the machine may be shared: CPU time says what the bind itself cost
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

void run(const char* name, const dfm::TetMesh* tets, const dfm::TriMesh* surface, const dfm::Rig& rig, int threads,
         bool unnormalized) {
  const Eigen::MatrixXi F = tets ? dfm::tet_boundary_faces(tets->T) : surface->F;
  std::printf("%s: %d surface triangles, %d handles, %d threads\n", name, static_cast<int>(F.rows()),
              dfm::num_handles(rig), threads);
  double bbw_per_function = 0;
  for (int mode = 0; mode < 3; ++mode) {  // default, monotone divided by row sums, monotone with exact sums
    const bool monotone = mode > 0;
    dfm::BindOptions o;
    o.bbw.threads = threads;
    o.bbw.monotone = monotone;
    o.bbw.monotone_exact_sums = mode == 2;
    o.bbw.normalize_rows = !unnormalized;
    const double cpu0 = cpu_seconds();
    const dfm::BindResult r = tets ? dfm::bind_tet_mesh(*tets, rig, o) : dfm::bind_surface(*surface, rig, o);
    const dfm::BindReport& p = r.report;
    const double cpu = cpu_seconds() - cpu0;
    const dfm::BindExtrema e = dfm::bind_local_extrema(r, F);
    const double solve = p.assembly_seconds + p.factorization_seconds + p.solve_seconds;
    const double per_function = solve / p.handles;
    if (!monotone) bbw_per_function = per_function;
    const char* label = mode == 0 ? "default" : mode == 1 ? "mono/div" : "mono/sums";
    std::printf("  %-9s %d tets %d tet vertices: weights %.3f s = %.3f s per function", label, p.tets, p.tet_vertices,
                solve, per_function);
    if (monotone)
      std::printf(" (x%.2f; monotone stage %.3f s per function, %d reduced solves, worst handle %d, %s, released "
                  "multiplier %.3g)",
                  per_function / bbw_per_function, p.bbw.monotone_seconds / p.handles, p.bbw.monotone_iterations_total,
                  p.bbw.monotone_iterations_max, p.bbw.monotone_optimal ? "optimal" : "feasible",
                  p.bbw.monotone_dual_residual);
    if (mode == 2)
      std::printf("\n            joint solve %.3f s = %.3f s per function, %d reduced solves, %s, max |row sum - 1| %.2g",
                  p.bbw.monotone_joint_seconds, p.bbw.monotone_joint_seconds / p.handles,
                  p.bbw.monotone_joint_iterations, p.bbw.monotone_joint ? "feasible" : "INFEASIBLE (rows divided)",
                  p.bbw.monotone_sum_residual);
    std::printf("\n            whole bind %.3f s wall, %.3f s CPU (meshing included)", p.total_seconds, cpu);
    std::printf("\n            local maxima/minima away from handles: tet graph %d/%d, surface %d/%d; exact zeros %.1f%%\n",
                e.tet.maxima, e.tet.minima, e.surface.maxima, e.surface.minima, 100 * p.zero_fraction);
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string which = "all";
  int threads = 2;
  bool unnormalized = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--unnormalized")) unnormalized = true;
    else which = argv[i];
  }
  const std::string d = DFM_DATA_DIR;
  try {
    if (which == "hand" || which == "all") {
      const dfm::TetMesh tets = dfm::read_tet_mesh(d + "/hand.mesh");
      dfm::Rig rig;
      dfm::add_tgf_to_rig(rig, dfm::read_tgf(d + "/hand.tgf"), d + "/hand.tgf");
      run("hand.mesh", &tets, nullptr, rig, threads, unnormalized);
    }
    if (which == "arm" || which == "all") {
      const dfm::TriMesh arm = dfm::read_surface(d + "/arm.obj");
      dfm::Rig rig;
      dfm::add_tgf_to_rig(rig, dfm::read_tgf(d + "/arm.tgf"), d + "/arm.tgf");
      run("arm.obj", nullptr, &arm, rig, threads, unnormalized);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_monotone: %s\n", e.what());
    return 1;
  }
  return 0;
}
