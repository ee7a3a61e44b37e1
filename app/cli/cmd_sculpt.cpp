// `deform sculpt`: smooth region deformation (Jacobson 2013, ch. 3): the fixed vertices stay, the handle
// vertices move by DX DY DZ, the free vertices between minimize the Laplacian energy (order 2, C1 at the
// region boundaries) or the Laplacian gradient energy (order 3, C2).
#include <chrono>
#include <cmath>
#include <cstdio>

#include <Eigen/Geometry>

#include "app/cli/command.h"
#include "core/mesh/io.h"
#include "core/sculpt/variational_deform.h"
#include "core/util/error.h"

namespace {

const char* kUsage =
    "usage: deform sculpt INPUT --fixed F.txt --handle H.txt --move DX DY DZ [--rotate AX AY AZ DEG [--about X Y Z]]\n"
    "                     [--order 2|3] -o OUT.obj|.ply|.off|.stl\n"
    "  INPUT           a triangle surface\n"
    "  --fixed F.txt   vertices that stay (0-based indices, one a line; '#' comments allowed)\n"
    "  --handle H.txt  vertices that move by DX DY DZ; the free region is every other vertex\n"
    "  --rotate        the handle also turns by DEG degrees about the axis (AX, AY, AZ) through --about\n"
    "                  (default: the handle's centroid), before the move\n"
    "  --order 2|3     2 (default): biharmonic, C1 where the free region meets the others (the fixed\n"
    "                  region needs one ring of vertices around it); 3: triharmonic, C2 (two rings)";

int run(const dfm::cli::Args& args) {
  std::string input, fixed_path, handle_path, out;
  Eigen::RowVector3d d;
  bool moved = false, turned = false, about_given = false;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ(), about = Eigen::Vector3d::Zero();
  double degrees = 0;
  int order = 2;
  dfm::cli::ArgReader r(args);
  while (!r.done()) {
    const std::string f = r.next();
    if (f == "--fixed") fixed_path = r.value(f);
    else if (f == "--handle") handle_path = r.value(f);
    else if (f == "--move") {
      for (int k = 0; k < 3; ++k) d(k) = r.number(f);
      moved = true;
    }
    else if (f == "--rotate") {
      for (int k = 0; k < 3; ++k) axis(k) = r.number(f);
      degrees = r.number(f);
      turned = true;
    } else if (f == "--about") {
      for (int k = 0; k < 3; ++k) about(k) = r.number(f);
      about_given = true;
    }
    else if (f == "--order") order = r.integer(f);
    else if (f == "-o" || f == "--output") out = r.value(f);
    else if (f.size() > 1 && f[0] == '-')
      throw dfm::cli::UsageError("unknown option " + f);
    else if (input.empty()) input = f;
    else throw dfm::cli::UsageError("one INPUT only (got " + input + " and " + f + ")");
  }
  if (input.empty()) throw dfm::cli::UsageError("INPUT is required");
  if (fixed_path.empty() || handle_path.empty()) throw dfm::cli::UsageError("--fixed F.txt and --handle H.txt are required");
  if (!moved) throw dfm::cli::UsageError("--move DX DY DZ is required");
  if (order != 2 && order != 3) throw dfm::cli::UsageError("--order must be 2 or 3");
  if (turned && !(axis.norm() > 0)) throw dfm::cli::UsageError("--rotate needs a nonzero axis");
  if (about_given && !turned) throw dfm::cli::UsageError("--about goes with --rotate");
  if (out.empty()) throw dfm::cli::UsageError("-o OUT is required");
  const dfm::TriMesh mesh = dfm::read_surface(input);
  const std::vector<int> fixed = dfm::read_vertex_indices(fixed_path, mesh.num_vertices());
  const std::vector<int> handle = dfm::read_vertex_indices(handle_path, mesh.num_vertices());
  const auto t0 = std::chrono::steady_clock::now();
  dfm::VariationalDeform deform = [&] {
    try {
      return dfm::VariationalDeform(mesh.V, mesh.F, fixed, handle, {order});
    } catch (const dfm::Error& e) {
      throw dfm::Error(input + " with --fixed " + fixed_path + " --handle " + handle_path + ": " + e.what());
    }
  }();
  const double factor_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto t1 = std::chrono::steady_clock::now();
  // p' = R (p - c) + c + d, in the row-vector form p' = p T.topRows(3) + T.row(3).
  dfm::HandleTransform T = dfm::handle_translation(d);
  if (turned) {
    Eigen::Vector3d c = about;
    if (!about_given) {
      c.setZero();
      for (int v : deform.handle_vertices()) c += mesh.V.row(v).transpose();
      c /= static_cast<double>(deform.handle_vertices().size());
    }
    const Eigen::Matrix3d R = Eigen::AngleAxisd(degrees * M_PI / 180, axis.normalized()).toRotationMatrix();
    T.topRows(3) = R.transpose();
    T.row(3) = (c - R * c + d.transpose()).transpose();
  }
  const dfm::TriMesh result{deform.solve(T), mesh.F, {}};
  const double solve_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count();
  dfm::write_surface(out, result);
  std::printf("sculpt: %s, %zu handle, %zu free vertices; factor %.3f s, solve %.2f ms; wrote %s\n",
              order == 2 ? "biharmonic" : "triharmonic", deform.handle_vertices().size(), deform.free_vertices().size(),
              factor_s, solve_ms, out.c_str());
  return 0;
}

dfm::cli::Register reg{"sculpt", "smooth region deformation: fixed, handle and free vertices (bi- or triharmonic)",
                       kUsage, &run};

}  // namespace
