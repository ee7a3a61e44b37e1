// Bind benchmark: hand.mesh + hand.tgf (tet input, 20 bones) and armadillo.obj + 10 point handles at
// surface vertices (TetGen pq1.414Y). Prints per-stage wall times, CPU time (the machine may be shared),
// solver iterations, KKT residual, peak RSS, and the ratio of the bounded solve to the bound-free
// biharmonic solve (the baseline measured in the same run: one factorization + solve for all handles;
// on armadillo the coarse level replaces that factorization, so the stage is the ordering instead).
//   bench_bind [hand|armadillo|all] [--reference|--baseline]
//     --reference (hand): also solve to 1e-10 and print the largest weight difference of the 1e-6 run
//     --baseline (armadillo): bind again started from the bound-free solution (no coarse level) and
//                             print the ratios and the largest weight difference
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <utility>

#include "core/bind/bind.h"
#include "core/mesh/io.h"
#include "core/rig/rig_io.h"
#include "core/bind/numeric_setup.h"

namespace {

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;  // KiB on Linux
}

// Progress on stderr (stage changes and every 5%), so a long run shows how far it got.
dfm::BindOptions with_progress(dfm::BindOptions o = {}) {
  const auto t0 = std::chrono::steady_clock::now();
  auto last = std::make_shared<std::pair<std::string, double>>("", -1.0);
  o.progress = [t0, last](const std::string& stage, double f) {
    if (stage == last->first && f < last->second + 0.05) return;
    *last = {stage, f};
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "  [%7.2f s, CPU %7.2f s, RSS %5.0f MB] %s %.0f%%\n", t, cpu_seconds(), peak_rss_mb(),
                 stage.c_str(), 100 * f);
  };
  return o;
}

void print(const char* name, const dfm::BindResult& r, double cpu) {
  const dfm::BindReport& p = r.report;
  std::printf("%s: %d tets, %d tet vertices, %d handles\n", name, p.tets, p.tet_vertices, p.handles);
  std::printf("  wall [s]: meshing %.3f  assembly %.3f  %s %.3f  bounded solve %.3f  endpoint weights %.3f  total %.3f\n",
              p.meshing_seconds, p.assembly_seconds,
              p.bbw.multilevel ? "ordering" : "factorization+bound-free solve",
              p.factorization_seconds, p.solve_seconds, p.endpoint_seconds, p.total_seconds);
  std::printf("  whole solve (assembly + factorization + bounded solve): %.3f s wall; process CPU %.3f s\n",
              p.assembly_seconds + p.factorization_seconds + p.solve_seconds, cpu);
  std::printf("  solver: %d free-set solves (worst handle %d, fallback %d), KKT residual %.2e, factor nnz %ld\n",
              p.bbw.iterations_total, p.bbw.iterations_max, p.bbw.fallback_iterations, p.bbw.kkt_residual,
              p.bbw.factor_nonzeros);
  if (p.bbw.multilevel)
    std::printf("  multilevel start for %d of %d handles: coarse level built and solved in %.3f s (on a second thread, "
                "alongside assembly, ordering and the first fine solves)\n",
                p.bbw.multilevel_handles, p.handles, p.bbw.multilevel_seconds);
  std::printf("  weights: min %.3g max %.3g max|rowsum-1| %.2e exact zeros %.1f%%\n", p.min_weight, p.max_weight,
              p.max_row_sum_error, 100 * p.zero_fraction);
  if (!p.bbw.multilevel)  // with a coarse level the stage is the ordering: see --baseline instead
    std::printf("  ratio bounded solve / bound-free baseline (factorization + solve): %.1fx\n",
                p.solve_seconds / std::max(p.factorization_seconds, 1e-9));
  std::printf("  peak RSS %.0f MB\n", peak_rss_mb());
}

void hand(bool reference) {
  const std::string dir = DFM_DATA_DIR;
  const dfm::TetMesh tets = dfm::read_tet_mesh(dir + "/hand.mesh");
  dfm::Rig rig;
  dfm::add_tgf_to_rig(rig, dfm::read_tgf(dir + "/hand.tgf"), "hand.tgf");
  const double c0 = cpu_seconds();
  const dfm::BindResult r = dfm::bind_tet_mesh(tets, rig);
  print("hand", r, cpu_seconds() - c0);
  if (reference) {
    dfm::BindOptions o;
    o.bbw.qp.tolerance = 1e-10;
    const double c1 = cpu_seconds();
    const dfm::BindResult ref = dfm::bind_tet_mesh(tets, rig, o);
    print("hand (reference, tolerance 1e-10)", ref, cpu_seconds() - c1);
    std::printf("  max |w(1e-6) - w(1e-10)| = %.2e\n", (r.weights - ref.weights).cwiseAbs().maxCoeff());
  }
}

void armadillo(bool baseline) {
  const std::string dir = DFM_DATA_DIR;
  const dfm::TriMesh surf = dfm::read_surface(dir + "/armadillo.obj");
  dfm::Rig rig;
  for (int k = 0; k < 10; ++k) {
    const int v = static_cast<int>((static_cast<long>(k) * surf.num_vertices()) / 10);
    rig.points.push_back({surf.V.row(v).transpose(), "v" + std::to_string(v)});
  }
  const double c0 = cpu_seconds();
  const dfm::BindResult r = dfm::bind_surface(surf, rig, with_progress());
  print("armadillo + 10 points", r, cpu_seconds() - c0);
  if (baseline) {
    // The same bind started from the bound-free solution (no coarse level), in this process.
    dfm::BindOptions o = with_progress();
    o.bbw.multilevel_min_vertices = 0;
    const double c1 = cpu_seconds();
    const dfm::BindResult b = dfm::bind_surface(surf, rig, o);
    print("armadillo + 10 points, bound-free start (no coarse level)", b, cpu_seconds() - c1);
    std::printf("  multilevel / bound-free start: total %.2fx, bounded solve %.2fx; max |w - w_bound_free_start| = %.2e\n",
                r.report.total_seconds / b.report.total_seconds, r.report.solve_seconds / b.report.solve_seconds,
                (r.weights - b.weights).cwiseAbs().maxCoeff());
  }
}

}  // namespace

// The process-wide numeric settings (core/bind/numeric_setup.h): serial OpenMP regions here,
// setup_numerics() first thing in main.
DFM_RUN_OPENMP_REGIONS_SERIALLY()

int main(int argc, char** argv) {
  dfm::setup_numerics();  // before any bind (numeric_setup.h)
  const std::string which = argc > 1 ? argv[1] : "hand";
  const bool reference = argc > 2 && std::strcmp(argv[2], "--reference") == 0;
  const bool baseline = argc > 2 && std::strcmp(argv[2], "--baseline") == 0;
  try {
    if (which == "hand" || which == "all") hand(reference);
    if (which == "armadillo" || which == "all") armadillo(baseline);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_bind: %s\n", e.what());
    return 1;
  }
  return 0;
}
