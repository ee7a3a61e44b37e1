// `deform bind`: bounded biharmonic weights of a surface or tet mesh for its handles.
#include <algorithm>
#include <cstdio>
#include <iostream>

#include "app/cli/command.h"
#include "core/bind/bind.h"
#include "core/bind/bind_extrema.h"
#include "core/mesh/mesh_info.h"
#include "core/mesh/io.h"
#include "core/rig/rig_io.h"
#include "core/util/error.h"

namespace {

const char* kUsage =
    "usage: deform bind INPUT [--skeleton S.tgf] [--points P.txt] [--cage C.obj ...] [--tetgen SWITCHES]\n"
    "                   [--segmentation cut|threshold] [--exact-pou | --monotone] [--threads N] -o W.dmat [--tets OUT.mesh]\n"
    "                   [--endpoints E.dmat] [--additional K A.dmat]\n"
    "  INPUT              surface (.obj .off .ply .stl: tetrahedralized with TetGen) or tet mesh\n"
    "                     (.mesh .node/.ele: used as it is; it must contain every handle's geometry)\n"
    "  --skeleton S.tgf   bones (TGF edge order) and point handles (joints on no bone)\n"
    "  --points P.txt     point handles, one 'x y z' a line\n"
    "  --cage C.obj ...   cages (closed, open or partial); each cage vertex is a handle\n"
    "  --tetgen SWITCHES  TetGen switches (default pq1.414Y)\n"
    "  --segmentation M   robust volume (open or messy surfaces): 'cut' (default) keeps the tets a graph cut\n"
    "                     of the winding numbers chooses, 'threshold' those with winding number > 0.5\n"
    "  --exact-pou        enforce the partition of unity inside the optimization (all handles jointly)\n"
    "  --monotone         no local maxima or minima away from the handles (Jacobson 2013, ch. 5)\n"
    "  -o W.dmat          #input vertices x #handles; columns: points (P.txt, then TGF joints on no bone),\n"
    "                     bones, cage vertices\n"
    "  --tets OUT.mesh    also save the tet mesh the weights were solved on\n"
    "  --endpoints E.dmat also save the bones' STBS endpoint weights (#input vertices x #bones; Jacobson 2013,\n"
    "                     6.2.3: from joint weights solved on the same volume), for deform pose --endpoints\n"
    "  --additional K A.dmat  also solve K additional weight functions (Jacobson 2013, 7.3.3: abstract\n"
    "                     handles at farthest-point samples of the volume, 1 <= K <= 100) and save them\n"
    "                     (#input vertices x K), for deform pose --fast --additional";

// What the command line asks for.
struct Options {
  std::string input, skeleton, points, tetgen, segmentation, out, tets_out, endpoints_out, additional_out;
  int additional = 0;
  std::vector<std::string> cages;
  bool exact = false, monotone = false;
  int threads = 2;
};

Options parse_options(const dfm::cli::Args& args) {
  using dfm::cli::UsageError;
  Options o;
  dfm::cli::ArgReader r(args);
  while (!r.done()) {
    const std::string a = r.next();
    if (a == "--skeleton") o.skeleton = r.value(a);
    else if (a == "--points") o.points = r.value(a);
    else if (a == "--cage") {
      // One or more paths, up to the next flag.
      while (!r.done() && !r.peek().empty() && r.peek()[0] != '-') o.cages.push_back(r.next());
      if (o.cages.empty()) throw UsageError("--cage needs a file");
    } else if (a == "--tetgen") o.tetgen = r.value(a);
    else if (a == "--segmentation") o.segmentation = r.value(a);
    else if (a == "--exact-pou") o.exact = true;
    else if (a == "--monotone") o.monotone = true;
    else if (a == "--threads") o.threads = r.integer(a);
    else if (a == "-o" || a == "--output") o.out = r.value(a);
    else if (a == "--tets") o.tets_out = r.value(a);
    else if (a == "--endpoints") o.endpoints_out = r.value(a);
    else if (a == "--additional") o.additional = r.integer(a), o.additional_out = r.value(a);
    else if (!a.empty() && a[0] == '-') throw UsageError("unknown option " + a);
    else if (o.input.empty()) o.input = a;
    else throw UsageError("more than one input: " + o.input + ", " + a);
  }
  if (o.input.empty()) throw UsageError("no input mesh");
  if (o.out.empty()) throw UsageError("no output: give -o W.dmat");
  if (o.threads < 1) throw UsageError("--threads must be >= 1");
  if (!o.additional_out.empty() && (o.additional < 1 || o.additional > 100))
    throw UsageError("--additional K must be between 1 and 100, got " + std::to_string(o.additional));
  if (o.exact && o.monotone)
    throw UsageError("--monotone and --exact-pou do not combine (--monotone already sums to 1 exactly)");
  if (!o.segmentation.empty() && o.segmentation != "cut" && o.segmentation != "threshold")
    throw UsageError("--segmentation must be cut or threshold, not " + o.segmentation);
  return o;
}

dfm::Rig read_rig(const Options& o) {
  dfm::Rig rig;
  if (!o.points.empty()) dfm::add_points_file_to_rig(rig, o.points);
  if (!o.skeleton.empty()) dfm::add_tgf_to_rig(rig, dfm::read_tgf(o.skeleton), o.skeleton);
  for (const std::string& c : o.cages) {
    dfm::Cage cage;
    cage.mesh = dfm::read_surface(c);
    cage.name = c;
    rig.cages.push_back(std::move(cage));
  }
  if (dfm::num_handles(rig) == 0) throw dfm::cli::UsageError("no handles: give --skeleton, --points or --cage");
  return rig;
}

// The report's figures: sizes, stage times, the solver's and (when on) the monotone solve's.
void print_report(const dfm::BindResult& res, bool exact) {
  const dfm::BindReport& rep = res.report;
  for (const std::string& n : rep.notes) std::cout << "note: " << n << "\n";
  std::printf("tets: %d (%d vertices), handles: %d, input vertices: %d\n", rep.tets, rep.tet_vertices, rep.handles,
              static_cast<int>(res.weights.rows()));
  std::printf("times [s]: meshing %.3f, assembly %.3f, factorization %.3f, solve %.3f, total %.3f\n",
              rep.meshing_seconds, rep.assembly_seconds, rep.factorization_seconds, rep.solve_seconds,
              rep.total_seconds);
  if (rep.bbw.multilevel)
    std::printf("multilevel start for %d of %d handles: coarse level built and solved in %.3f s on a second thread\n",
                rep.bbw.multilevel_handles, rep.handles, rep.bbw.multilevel_seconds);
  std::printf("solver: %s, %d free-set solves (worst handle %d, fallback %d), KKT residual %.3g (weight units)\n",
              exact ? "exact partition of unity" : "per handle + row normalization", rep.bbw.iterations_total,
              rep.bbw.iterations_max, rep.bbw.fallback_iterations, rep.bbw.kkt_residual);
  if (rep.bbw.monotone)
    std::printf("monotone: %.3f s (%.3f s per handle; representative functions %.3f s), %d reduced solves (worst handle %d), "
                "%s (released multiplier %.3g), %d vertex sides bounded by the box\n",
                rep.bbw.monotone_seconds, rep.bbw.monotone_seconds / std::max(1, rep.handles),
                rep.bbw.monotone_representative_seconds, rep.bbw.monotone_iterations_total,
                rep.bbw.monotone_iterations_max, rep.bbw.monotone_optimal ? "optimal" : "feasible, not optimal",
                rep.bbw.monotone_dual_residual, rep.bbw.monotone_sides_without_neighbour);
  if (rep.bbw.monotone && rep.bbw.monotone_joint_iterations)
    std::printf("monotone row sums: %s (%.3f s, %d joint solves, max |row sum - 1| %.3g)\n",
                rep.bbw.monotone_joint ? "solved jointly, exact" : "joint solve infeasible, rows divided",
                rep.bbw.monotone_joint_seconds, rep.bbw.monotone_joint_iterations, rep.bbw.monotone_sum_residual);
}

int run(const dfm::cli::Args& args) {
  const Options o = parse_options(args);
  const dfm::Rig rig = read_rig(o);
  dfm::BindOptions opts;
  opts.bbw.exact_partition_of_unity = o.exact;
  opts.bbw.monotone = o.monotone;
  opts.bbw.threads = o.threads;
  if (!o.tetgen.empty()) opts.volume.tetgen_switches = o.tetgen;
  if (o.segmentation == "threshold") opts.volume.segmentation = dfm::VolumeOptions::Segmentation::Threshold;
  opts.additional_weights = o.additional;
  const bool tet_input = dfm::is_tet_mesh_path(o.input);
  dfm::TriMesh surface;
  dfm::TetMesh tets;
  if (tet_input) tets = dfm::read_tet_mesh(o.input);
  else surface = dfm::read_surface(o.input);
  const dfm::BindResult res = tet_input ? dfm::bind_tet_mesh(tets, rig, opts) : dfm::bind_surface(surface, rig, opts);
  print_report(res, o.exact);
  const dfm::BindExtrema ext =
      dfm::bind_local_extrema(res, tet_input ? dfm::tet_boundary_faces(tets.T) : surface.F);
  std::printf("local extrema away from the handles: tet graph %d maxima, %d minima; surface %d maxima, %d minima\n",
              ext.tet.maxima, ext.tet.minima, ext.surface.maxima, ext.surface.minima);
  std::printf("weights: min %.6g, max %.6g, max |row sum - 1| %.3g, exact zeros %.1f%%\n", res.report.min_weight,
              res.report.max_weight, res.report.max_row_sum_error, 100.0 * res.report.zero_fraction);
  dfm::write_dmat(o.out, res.weights);
  std::cout << "wrote " << o.out << " (" << res.weights.rows() << " x " << res.weights.cols() << ")\n";
  if (!o.tets_out.empty()) {
    dfm::write_tet_mesh(o.tets_out, res.volume.tets);
    std::cout << "wrote " << o.tets_out << "\n";
  }
  if (!o.endpoints_out.empty()) {
    if (res.endpoint_weights.cols() == 0) throw dfm::Error("--endpoints: the rig has no bones");
    dfm::write_dmat(o.endpoints_out, res.endpoint_weights);
    std::cout << "wrote " << o.endpoints_out << " (endpoint weights, " << res.endpoint_weights.rows() << " x "
              << res.endpoint_weights.cols() << ", " << res.report.endpoint_seconds << " s)\n";
  }
  if (!o.additional_out.empty()) {
    dfm::write_dmat(o.additional_out, res.additional_weights);
    std::cout << "wrote " << o.additional_out << " (additional weights, " << res.additional_weights.rows() << " x "
              << res.additional_weights.cols() << ", " << res.report.additional_seconds << " s)\n";
  }
  return 0;
}

dfm::cli::Register reg{"bind", "bounded biharmonic weights for points, bones and cages", kUsage, &run};

}  // namespace
