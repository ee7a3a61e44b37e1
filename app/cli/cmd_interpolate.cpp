// `deform interpolate`: the in-between of two keyed meshes of one connectivity at exactly T, as rigid
// as possible (Alexa 2002, 4.4, on tets), linear, or in Laplacian coordinates with per-vertex transition
// states (Alexa 2002, 4.3); no animation manifold.
#include <chrono>
#include <cstdio>

#include "app/cli/command.h"
#include "core/anim/arap_interpolation.h"
#include "core/mesh/io.h"
#include "core/sculpt/differential_blend.h"
#include "core/util/error.h"

namespace {

const char* kUsage =
    "usage: deform interpolate --keyframes K0 K1 [--method arap|linear|differential] [--states S.dmat] [--symmetric]\n"
    "                          --at T [--stats] -o OUT.obj|.ply|.off|.stl\n"
    "  --keyframes K0 K1  two surfaces with the same vertices and triangles (K0 closed for arap)\n"
    "  --method M         arap (default: K0's interior tetrahedralized, per-tet rotations and stretches\n"
    "                     interpolated, vertex paths by least squares; keys hit exactly), linear, or\n"
    "                     differential (Laplacian coordinates blended per vertex, positions by least squares)\n"
    "  --states S.dmat    differential: a #V x 1 column of transition-state offsets in (-1, 1); a vertex with\n"
    "                     offset o > 0 arrives early (its whole transition over T in [0, 1 - o]), o < 0 starts\n"
    "                     late (over [-o, 1]); T = 0 and 1 stay the keys. Without it every vertex is at T\n"
    "  --at T             0 gives K0, 1 gives K1; values outside [0, 1] extrapolate\n"
    "  --symmetric        arap with Eq. 4.28's symmetric energy (both keys' tets weigh alike; one\n"
    "                     factorization per time instead of per key pair)\n"
    "  --stats            print the tets and the time of each stage";

int run(const dfm::cli::Args& args) {
  std::vector<std::string> keys;
  std::string out, method = "arap", states_path;
  double at = 0;
  bool at_given = false, stats = false;
  dfm::ArapInterpolationOptions arap_opts;
  dfm::cli::ArgReader r(args);
  while (!r.done()) {
    const std::string f = r.next();
    if (f == "--keyframes") keys = r.values(f);
    else if (f == "--method") method = r.value(f);
    else if (f == "--at") at = r.number(f), at_given = true;
    else if (f == "--states") states_path = r.value(f);
    else if (f == "--stats") stats = true;
    else if (f == "--symmetric") arap_opts.symmetric = true;
    else if (f == "-o" || f == "--output") out = r.value(f);
    else throw dfm::cli::UsageError("unknown option " + f);
  }
  if (keys.size() != 2) throw dfm::cli::UsageError("--keyframes needs exactly two meshes");
  if (!at_given) throw dfm::cli::UsageError("--at T is required");
  if (out.empty()) throw dfm::cli::UsageError("-o OUT is required");
  if (method != "arap" && method != "linear" && method != "differential")
    throw dfm::cli::UsageError("--method must be arap, linear or differential");
  if (!states_path.empty() && method != "differential") throw dfm::cli::UsageError("--states goes with --method differential");
  if (arap_opts.symmetric && method != "arap") throw dfm::cli::UsageError("--symmetric goes with --method arap");
  const dfm::TriMesh k0 = dfm::read_surface(keys[0]), k1 = dfm::read_surface(keys[1]);
  if (k0.V.rows() != k1.V.rows() || k0.F != k1.F)
    throw dfm::Error(keys[1] + ": its vertices or triangles differ from " + keys[0] +
                     "'s (interpolation needs one connectivity; `deform manifold` joins different meshes)");
  const auto t0 = std::chrono::steady_clock::now();
  dfm::TriMesh result{Eigen::MatrixXd(), k0.F, {}};
  if (method == "linear") {
    result.V = dfm::linear_interpolation(k0.V, k1.V, at);
  } else if (method == "differential") {
    Eigen::VectorXd states = Eigen::VectorXd::Constant(k0.V.rows(), at);
    if (!states_path.empty()) {
      const Eigen::MatrixXd S = dfm::read_dmat(states_path);
      if (S.cols() != 1 || S.rows() != k0.V.rows())
        throw dfm::Error(states_path + ": transition-state offsets must be a " + std::to_string(k0.V.rows()) +
                         " x 1 column (one per vertex of " + keys[0] + "), found " + std::to_string(S.rows()) + " x " +
                         std::to_string(S.cols()));
      try {
        states = dfm::transition_states(S.col(0), at);
      } catch (const dfm::Error& e) {
        throw dfm::Error(states_path + ": " + e.what());
      }
    }
    const dfm::DifferentialBlend blend(k0.V, k1.V, k0.F);
    const auto t1 = std::chrono::steady_clock::now();
    result.V = blend.at(states);
    const double solve_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count();
    std::printf("interpolate: differential, factor %.3f s, solve %.2f ms\n", blend.factor_seconds(), solve_ms);
  } else {
    dfm::ArapInterpolation arap = [&] {
      try {
        return dfm::ArapInterpolation(k0, k1.V, arap_opts);
      } catch (const dfm::Error& e) {
        throw dfm::Error(keys[0] + ": " + e.what());
      }
    }();
    const auto t1 = std::chrono::steady_clock::now();
    result.V = arap.at(at);
    const double eval_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count();
    if (stats) {
      const dfm::ArapInterpolationStats& s = arap.stats();
      std::printf("interpolate: %d tets, %d tet vertices; tetrahedralize %.3f s, interior %.3f s, factor %.3f s, "
                  "one in-between %.2f ms\n",
                  s.tets, s.tet_vertices, s.tetrahedralize_seconds, s.interior_seconds, s.factor_seconds, eval_ms);
    }
  }
  dfm::write_surface(out, result);
  std::printf("interpolate: %s at t = %g in %.3f s; wrote %s\n", method.c_str(), at,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), out.c_str());
  return 0;
}

dfm::cli::Register reg{"interpolate", "the in-between of two same-connectivity meshes (ARAP or linear)", kUsage, &run};

}  // namespace
