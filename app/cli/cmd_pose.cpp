// `deform pose`: skins a mesh with its weights into a pose and saves the posed surface.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>

#include "app/cli/command.h"
#include "core/mesh/io.h"
#include "core/mesh/mesh_info.h"
#include "core/rig/pose_io.h"
#include "core/rig/pose_params.h"
#include "core/rig/rig_io.h"
#include "core/skin/skin.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "render/gl_context.h"
#include "render/skin_pass.h"

namespace {

const char* kUsage =
    "usage: deform pose INPUT --weights W.dmat [--skeleton S.tgf --pose Q.dmat] [--points-pose P.txt]\n"
    "                   [--method lbs|dqs|stbs] [-k 4|8] [--cpu] -o OUT.obj|.ply|.off|.stl\n"
    "  INPUT              surface (.obj .off .ply .stl) or tet mesh (.mesh .node/.ele: all its vertices\n"
    "                     are posed, its surface triangles saved)\n"
    "  --weights W.dmat   #V x #handles weights (handle order: point handles, then bones)\n"
    "  --skeleton S.tgf   bones and point handles (joints on no bone)\n"
    "  --pose Q.dmat      one rotation per bone relative to its parent, quaternions (x y z w)\n"
    "  --points-pose P.txt  one translation per point handle ('x y z' per line)\n"
    "  --method M         lbs (default), dqs or stbs\n"
    "  -k K               keep only the K = 4 or 8 largest weights per vertex (renormalized), as glTF\n"
    "                     does; default: every nonzero weight (exact, on the GPU too)\n"
    "  --cpu              skin on the CPU even when an OpenGL context is available\n"
    "Uses the GPU when an OpenGL 3.3 context can be created, the CPU otherwise, and says which. Prints\n"
    "with -k the largest vertex error the truncation causes on this pose (vs. all weights).";

struct Input {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
};

Input read_input(const std::string& path) {
  Input in;
  if (dfm::is_tet_mesh_path(path)) {
    dfm::TetMesh t = dfm::read_tet_mesh(path);
    in.V = t.V;
    in.F = t.T.rows() ? dfm::tet_boundary_faces(t.T) : t.F;
  } else {
    dfm::TriMesh m = dfm::read_surface(path);
    in.V = m.V;
    in.F = m.F;
  }
  return in;
}

int run(const dfm::cli::Args& args) {
  std::string input, out, weights, skeleton, pose_file, points_pose, method_name = "lbs";
  int k = 0;  // 0: every weight
  bool k_given = false, force_cpu = false;
  dfm::cli::ArgReader a(args);
  while (!a.done()) {
    const std::string f = a.next();
    if (f == "-o" || f == "--output") out = a.value(f);
    else if (f == "--weights") weights = a.value(f);
    else if (f == "--skeleton") skeleton = a.value(f);
    else if (f == "--pose") pose_file = a.value(f);
    else if (f == "--points-pose") points_pose = a.value(f);
    else if (f == "--method") method_name = a.value(f);
    else if (f == "-k") k = a.integer(f), k_given = true;
    else if (f == "--cpu") force_cpu = true;
    else if (!f.empty() && f[0] == '-') throw dfm::cli::UsageError("unknown option " + f);
    else if (input.empty()) input = f;
    else throw dfm::cli::UsageError("more than one INPUT: " + input + ", " + f);
  }
  if (input.empty()) throw dfm::cli::UsageError("INPUT is required");
  if (out.empty()) throw dfm::cli::UsageError("-o OUT is required");
  if (weights.empty()) throw dfm::cli::UsageError("--weights W.dmat is required");
  if (k_given && k != 4 && k != 8) throw dfm::cli::UsageError("-k must be 4 or 8");
  if (!pose_file.empty() && skeleton.empty()) throw dfm::cli::UsageError("--pose needs --skeleton");
  dfm::SkinMethod method;
  try {
    method = dfm::parse_skin_method(method_name);
  } catch (const dfm::Error& e) {
    throw dfm::cli::UsageError(e.what());
  }
  const std::string ext = dfm::file_extension(out);
  if (ext != "obj" && ext != "ply" && ext != "off" && ext != "stl")
    throw dfm::cli::UsageError("OUT must end in .obj, .ply, .off or .stl, got '" + out + "'");

  const Input in = read_input(input);
  dfm::Rig rig;
  if (!skeleton.empty()) dfm::add_tgf_to_rig(rig, dfm::read_tgf(skeleton), skeleton);
  const int nh = dfm::num_handles(rig);
  if (nh == 0) throw dfm::Error("pose: the rig has no handles (give --skeleton)");
  const Eigen::MatrixXd W = dfm::read_dmat(weights);
  if (W.rows() != in.V.rows() || W.cols() != nh)
    throw dfm::file_error(weights, 0, "is " + std::to_string(W.rows()) + " x " + std::to_string(W.cols()) +
                                          " but the mesh has " + std::to_string(in.V.rows()) + " vertices and the rig " +
                                          std::to_string(nh) + " handles");

  dfm::PoseParams params = dfm::rest_pose_params(rig);
  if (!pose_file.empty()) params.bone_rotation = dfm::read_bone_rotations(pose_file, rig.skeleton.num_bones());
  if (!points_pose.empty())
    params.point_translation = dfm::read_point_translations(points_pose, dfm::num_point_handles(rig));
  const dfm::Pose pose = dfm::evaluate_pose(rig, params);
  const auto stbs = dfm::stbs_handles(rig, params.bone_twist_stretch);

  const Eigen::MatrixXd N = dfm::vertex_normals(in.V, in.F);
  const dfm::SkinBinding kept = dfm::make_skin_binding(in.V, N, W, rig, k);

  dfm::SkinResult posed;
  std::string where;
  const auto t0 = std::chrono::steady_clock::now();
  if (!force_cpu && dfm::gl::display_available()) {
    try {
      dfm::gl::Context ctx;
      dfm::gl::SkinPass pass(kept);
      pass.set_pose(pose, stbs);
      pass.run(method);
      posed = pass.read_back_result();
      where = "GPU (" + ctx.renderer() + ")";
    } catch (const dfm::Error& e) {
      std::cerr << "pose: GPU skinning unavailable (" << e.what() << "); using the CPU\n";
    }
  }
  if (where.empty()) {
    posed = dfm::skin(method, kept, pose, stbs);
    where = force_cpu ? "CPU (--cpu)" : "CPU (no OpenGL context)";
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const double trunc =
      k > 0 ? dfm::truncation_error(method, dfm::make_skin_binding(in.V, Eigen::MatrixXd(), W, rig, 0), kept, pose, stbs)
            : 0.0;
  const double diag = (in.V.colwise().maxCoeff() - in.V.colwise().minCoeff()).norm();

  dfm::TriMesh result;
  result.V = posed.V;
  result.F = in.F;
  result.N = posed.N;
  dfm::write_surface(out, result);
  const dfm::SparseInfluences rows = dfm::sparse_influences(kept.influences);
  const std::string kept_text = k > 0 ? "k = " + std::to_string(k) : "all weights";
  std::printf("pose: %d vertices, %d triangles, %d handles, %s, %s (%.2f per vertex on average, %d at most), "
              "skinned on the %s in %.1f ms\n",
              static_cast<int>(in.V.rows()), static_cast<int>(in.F.rows()), nh, dfm::skin_method_name(method),
              kept_text.c_str(), in.V.rows() ? double(rows.num_entries()) / in.V.rows() : 0.0, rows.max_row,
              where.c_str(), ms);
  if (k > 0)
    std::printf("pose: largest truncation error of %d influences on this pose: %.3g (%.3g of the bbox diagonal)\n", k,
                trunc, diag > 0 ? trunc / diag : 0.0);
  std::printf("pose: wrote %s\n", out.c_str());
  return 0;
}

dfm::cli::Register reg{"pose", "skin a mesh into a pose (LBS, DQS, STBS) and save it", kUsage, &run};

}  // namespace
