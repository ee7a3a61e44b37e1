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
    "  --tets OUT.mesh    also save the tet mesh the weights were solved on";

int run(const dfm::cli::Args& args) {
  using dfm::cli::UsageError;
  std::string input, skeleton, points, tetgen, segmentation, out, tets_out;
  std::vector<std::string> cages;
  bool exact = false, monotone = false;
  int threads = 2;
  dfm::cli::ArgReader r(args);
  while (!r.done()) {
    const std::string a = r.next();
    if (a == "--skeleton") skeleton = r.value(a);
    else if (a == "--points") points = r.value(a);
    else if (a == "--cage") {
      // One or more paths, up to the next flag.
      while (!r.done() && !r.peek().empty() && r.peek()[0] != '-') cages.push_back(r.next());
      if (cages.empty()) throw UsageError("--cage needs a file");
    } else if (a == "--tetgen") tetgen = r.value(a);
    else if (a == "--segmentation") segmentation = r.value(a);
    else if (a == "--exact-pou") exact = true;
    else if (a == "--monotone") monotone = true;
    else if (a == "--threads") threads = r.integer(a);
    else if (a == "-o" || a == "--output") out = r.value(a);
    else if (a == "--tets") tets_out = r.value(a);
    else if (!a.empty() && a[0] == '-') throw UsageError("unknown option " + a);
    else if (input.empty()) input = a;
    else throw UsageError("more than one input: " + input + ", " + a);
  }
  if (input.empty()) throw UsageError("no input mesh");
  if (out.empty()) throw UsageError("no output: give -o W.dmat");
  if (threads < 1) throw UsageError("--threads must be >= 1");
  if (exact && monotone)
    throw UsageError("--monotone and --exact-pou do not combine (--monotone already sums to 1 exactly)");
  if (!segmentation.empty() && segmentation != "cut" && segmentation != "threshold")
    throw UsageError("--segmentation must be cut or threshold, not " + segmentation);

  dfm::Rig rig;
  if (!points.empty()) dfm::add_points_file_to_rig(rig, points);
  if (!skeleton.empty()) dfm::add_tgf_to_rig(rig, dfm::read_tgf(skeleton), skeleton);
  for (const std::string& c : cages) {
    dfm::Cage cage;
    cage.mesh = dfm::read_surface(c);
    cage.name = c;
    rig.cages.push_back(std::move(cage));
  }
  if (dfm::num_handles(rig) == 0) throw UsageError("no handles: give --skeleton, --points or --cage");

  dfm::BindOptions opts;
  opts.bbw.exact_partition_of_unity = exact;
  opts.bbw.monotone = monotone;
  opts.bbw.threads = threads;
  if (!tetgen.empty()) opts.volume.tetgen_switches = tetgen;
  if (segmentation == "threshold") opts.volume.segmentation = dfm::VolumeOptions::Segmentation::Threshold;
  const bool tet_input = dfm::is_tet_mesh_path(input);
  dfm::TriMesh surface;
  dfm::TetMesh tets;
  if (tet_input) tets = dfm::read_tet_mesh(input);
  else surface = dfm::read_surface(input);
  const dfm::BindResult res = tet_input ? dfm::bind_tet_mesh(tets, rig, opts) : dfm::bind_surface(surface, rig, opts);

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
  const dfm::BindExtrema ext =
      dfm::bind_local_extrema(res, tet_input ? dfm::tet_boundary_faces(tets.T) : surface.F);
  std::printf("local extrema away from the handles: tet graph %d maxima, %d minima; surface %d maxima, %d minima\n",
              ext.tet.maxima, ext.tet.minima, ext.surface.maxima, ext.surface.minima);
  std::printf("weights: min %.6g, max %.6g, max |row sum - 1| %.3g, exact zeros %.1f%%\n", rep.min_weight,
              rep.max_weight, rep.max_row_sum_error, 100.0 * rep.zero_fraction);
  dfm::write_dmat(out, res.weights);
  std::cout << "wrote " << out << " (" << res.weights.rows() << " x " << res.weights.cols() << ")\n";
  if (!tets_out.empty()) {
    dfm::write_tet_mesh(tets_out, res.volume.tets);
    std::cout << "wrote " << tets_out << "\n";
  }
  return 0;
}

dfm::cli::Register reg{"bind", "bounded biharmonic weights for points, bones and cages", kUsage, &run};

}  // namespace
