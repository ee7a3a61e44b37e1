// `deform pose`: skins a mesh with its weights into a pose and saves the posed surface.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>

#include "app/cli/command.h"
#include "core/anim/frame_sequence.h"
#include "core/mesh/io.h"
#include "core/mesh/mesh_info.h"
#include "core/pose/fast_dynamics.h"
#include "core/pose/fast_model.h"
#include "core/pose/fast_rig.h"
#include "core/pose/fast_solver.h"
#include "core/rig/additional_handles.h"
#include "core/rig/pose_io.h"
#include "core/rig/pose_params.h"
#include "core/rig/rig_io.h"
#include "core/scene/document.h"
#include "core/scene/script.h"
#include "core/skin/skin.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "render/gl_context.h"
#include "render/skin_pass.h"

namespace {

const char* kUsage =
    "usage: deform pose SCENE.scene.json --at T [--method lbs|dqs|stbs|stbs-dqs] -o OUT.obj|.ply|.off|.stl\n"
    "       deform pose INPUT --weights W.dmat [--skeleton S.tgf --pose Q.dmat [--twist-stretch TS.dmat]\n"
    "                   [--endpoints E.dmat]] [--points P.txt] [--points-pose T.txt]\n"
    "                   [--fast [--free H,H,...] [--iterations N] [--additional A.dmat]]\n"
    "                   [--method lbs|dqs|stbs|stbs-dqs] [-k 4|8] [--cpu] -o OUT.obj|.ply|.off|.stl\n"
    "       deform pose INPUT --weights W.dmat ... --fast --dynamics --frames N --dt H [--damping D] [--density R]\n"
    "                   --sequence PREFIX [-o LAST.obj]\n"
    "  SCENE --at T       a bound scene (deform import's, the editor's) at time T of its animation in seconds,\n"
    "                     as the editor shows it (its method unless --method)\n"
    "  INPUT              surface (.obj .off .ply .stl) or tet mesh (.mesh .node/.ele: all its vertices\n"
    "                     are posed, its surface triangles saved)\n"
    "  --weights W.dmat   #V x #handles weights (handle order: point handles, then bones)\n"
    "  --points P.txt     point handles, one 'x y z' a line (before the TGF's, as `deform bind` orders them)\n"
    "  --skeleton S.tgf   bones and point handles (joints on no bone)\n"
    "  --pose Q.dmat      one rotation per bone relative to its parent, quaternions (x y z w)\n"
    "  --twist-stretch TS.dmat  one row per bone: twist in degrees at its second joint, stretch factor,\n"
    "                     optionally the twist in degrees at its first joint (Jacobson 2013 ch. 6;\n"
    "                     --method stbs spreads them along each bone, Eq. 6.5)\n"
    "  --endpoints E.dmat #V x #bones STBS endpoint weights (deform bind --endpoints); without, STBS projects\n"
    "                     each vertex onto the bone and says so\n"
    "  --points-pose P.txt  one translation per point handle ('x y z' per line)\n"
    "  --fast             solve the transforms nobody set (FAST, Jacobson 2013 ch. 7): handles in --free\n"
    "                     entirely, other point handles keep their --points-pose position (rotation solved),\n"
    "                     bones keep their --pose; energy: spokes and rims on a surface INPUT, tets on a\n"
    "                     tet-mesh INPUT. Prints 'fast: iteration I energy E' per iteration\n"
    "  --free H,H,...     handles solved entirely: 0-based indices or names ('point 2', 'bone 3')\n"
    "  --iterations N     local-global iterations (default 20; with --dynamics per time step, default 4)\n"
    "  --additional A.dmat  additional weights (deform bind --additional): one more handle per column, always\n"
    "                     free, whose transforms FAST solves and the skin adds (Jacobson 2013, 7.3.3), so two\n"
    "                     constrained handles no longer pinch what lies between them\n"
    "  --dynamics         FAST with dynamics (Jacobson 2013, 7.7): from rest, the constraints jump to their\n"
    "                     --pose / --points-pose at step 0 (a step input) and the solved handles follow with\n"
    "                     mass and damping; N steps of H seconds, frame i (the state after step i + 1) saved\n"
    "                     as PREFIX0000.obj, ... (PREFIX ending in .ply, .off or .stl picks that format).\n"
    "                     Prints 'dynamics: frame I kinetic K' per frame\n"
    "  --damping D        mass-proportional damping in 1/s (default 4: a step settles in about 2 s)\n"
    "  --density R        mass per unit area (tets: volume) with the bounding box diagonal as the unit\n"
    "                     (default 1; heavier is slower)\n"
    "  --method M         lbs (default), dqs, stbs (stretchable, twistable bones over LBS) or stbs-dqs (over DQS)\n"
    "  -k K               keep only the K = 4 or 8 largest weights per vertex (renormalized), as glTF\n"
    "                     does; default: every nonzero weight (exact, on the GPU too)\n"
    "  --cpu              skin on the CPU even when an OpenGL context is available\n"
    "Uses the GPU when an OpenGL 3.3 context can be created, the CPU otherwise, and says which. Prints\n"
    "with -k the largest vertex error the truncation causes on this pose (vs. all weights).";

struct Input {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  Eigen::MatrixXi T;  // tets, for a tet-mesh INPUT
};

Input read_input(const std::string& path) {
  Input in;
  if (dfm::is_tet_mesh_path(path)) {
    dfm::TetMesh t = dfm::read_tet_mesh(path);
    in.V = t.V;
    in.T = t.T;
    in.F = t.T.rows() ? dfm::tet_boundary_faces(t.T) : t.F;
  } else {
    dfm::TriMesh m = dfm::read_surface(path);
    in.V = m.V;
    in.F = m.F;
  }
  return in;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// FAST from the pose the files give: its fixed handles and position targets, free handles warm-started
// at that pose; prints the stages and one line per iteration.
// The rig's FAST constraints (default_fast_constraints) and one free one per additional handle.
std::vector<dfm::FastConstraint> fast_constraints(const dfm::Rig& rig, const std::vector<int>& free, int additional) {
  std::vector<dfm::FastConstraint> c = dfm::default_fast_constraints(rig, free);
  c.resize(c.size() + additional, {dfm::HandleConstraint::Free, Eigen::Vector3d::Zero()});
  return c;
}

// W: the rig's weights and the additional ones ([W | A]); pose: one transform per column (the additional
// handles' zero: additional_handles.h).
void solve_fast(const Input& in, const Eigen::MatrixXd& W, const dfm::Rig& rig, const std::vector<int>& free,
                int iterations, dfm::Pose& pose) {
  const dfm::FastModel model = dfm::fast_model(in.V, in.T.rows() ? in.T : in.F, W);
  const std::vector<dfm::FastConstraint> constraints =
      fast_constraints(rig, free, static_cast<int>(W.cols()) - dfm::num_handles(rig));
  dfm::FastSolver solver(model, constraints, dfm::fast_joints(rig));  // solved bones stay on their joints
  solver.set_targets(pose, dfm::fast_targets(constraints, pose));
  std::printf("fast: %s energy, %d handles (%d free), %d rotation clusters; precompute %.3f s (clusters %.3f s, "
              "reduction %.3f s), switch %.2f ms\n",
              in.T.rows() ? "tet" : "spokes-and-rims", model.handles, static_cast<int>(free.size()), model.clusters,
              model.cluster_seconds + model.assembly_seconds, model.cluster_seconds, model.assembly_seconds,
              1e3 * solver.switch_seconds());
  double iterating = 0;
  for (int i = 1; i <= iterations; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    solver.iterate(pose, false);
    iterating += seconds_since(t0);
    std::printf("fast: iteration %d energy %.9g\n", i, dfm::fast_energy(model, pose));
  }
  std::printf("fast: %d iterations, %.2f us per iteration\n", iterations, 1e6 * iterating / iterations);
}

// What the command line asks for.
struct Options {
  std::string input, out, weights, skeleton, pose_file, twist_stretch, endpoints, points, points_pose, free_list,
      additional;
  dfm::SkinMethod method = dfm::SkinMethod::LBS;
  int k = 0;  // 0: every weight
  int iterations = 20;
  bool iterations_given = false;
  bool force_cpu = false, fast = false;
  bool dynamics = false;
  int frames = 0;
  double dt = 0, damping = dfm::FastDynamicsOptions().damping, density = 1;
  bool dt_given = false, damping_given = false, density_given = false;
  std::string sequence;
  bool method_given = false;
  double at = 0;  // a scene's time
  bool scene = false, at_given = false;
};

Options parse_options(const dfm::cli::Args& args) {
  using dfm::cli::UsageError;
  Options o;
  std::string method_name = "lbs";
  bool k_given = false;
  dfm::cli::ArgReader a(args);
  while (!a.done()) {
    const std::string f = a.next();
    if (f == "-o" || f == "--output") o.out = a.value(f);
    else if (f == "--weights") o.weights = a.value(f);
    else if (f == "--skeleton") o.skeleton = a.value(f);
    else if (f == "--pose") o.pose_file = a.value(f);
    else if (f == "--twist-stretch") o.twist_stretch = a.value(f);
    else if (f == "--endpoints") o.endpoints = a.value(f);
    else if (f == "--points-pose") o.points_pose = a.value(f);
    else if (f == "--points") o.points = a.value(f);
    else if (f == "--fast") o.fast = true;
    else if (f == "--free") o.free_list = a.value(f);
    else if (f == "--additional") o.additional = a.value(f);
    else if (f == "--iterations") o.iterations = a.integer(f), o.iterations_given = true;
    else if (f == "--dynamics") o.dynamics = true;
    else if (f == "--frames") o.frames = a.integer(f);
    else if (f == "--dt") o.dt = a.number(f), o.dt_given = true;
    else if (f == "--damping") o.damping = a.number(f), o.damping_given = true;
    else if (f == "--density") o.density = a.number(f), o.density_given = true;
    else if (f == "--sequence") o.sequence = a.value(f);
    else if (f == "--method") method_name = a.value(f), o.method_given = true;
    else if (f == "--at") o.at = a.number(f), o.at_given = true;
    else if (f == "-k") o.k = a.integer(f), k_given = true;
    else if (f == "--cpu") o.force_cpu = true;
    else if (!f.empty() && f[0] == '-') throw UsageError("unknown option " + f);
    else if (o.input.empty()) o.input = f;
    else throw UsageError("more than one INPUT: " + o.input + ", " + f);
  }
  if (o.input.empty()) throw UsageError("INPUT is required");
  if (o.dynamics) {
    if (!o.fast) throw UsageError("--dynamics needs --fast");
    if (o.frames < 1) throw UsageError("--dynamics needs --frames N with N >= 1");
    if (!o.dt_given || !(o.dt > 0)) throw UsageError("--dynamics needs --dt H with H > 0 seconds");
    if (!(o.damping >= 0)) throw UsageError("--damping must be >= 0");
    if (!(o.density > 0)) throw UsageError("--density must be > 0");
    if (o.sequence.empty()) throw UsageError("--dynamics needs --sequence PREFIX");
    if (!o.iterations_given) o.iterations = dfm::FastDynamicsOptions().iterations;
  } else if (o.frames || o.dt_given || o.damping_given || o.density_given || !o.sequence.empty()) {
    throw UsageError("--frames, --dt, --damping, --density and --sequence go with --dynamics");
  }
  if (o.out.empty() && !o.dynamics) throw UsageError("-o OUT is required");
  o.scene = o.input.size() > 11 && o.input.compare(o.input.size() - 11, 11, ".scene.json") == 0;
  if (o.scene != o.at_given) throw UsageError(o.scene ? "a scene needs --at T" : "--at T takes a SCENE.scene.json");
  if (o.scene && (!o.weights.empty() || !o.skeleton.empty() || !o.points.empty() || o.fast))
    throw UsageError("a scene brings its own weights and rig: give only --at, --method and -o");
  if (!o.scene && o.weights.empty()) throw UsageError("--weights W.dmat is required");
  if (k_given && o.k != 4 && o.k != 8) throw UsageError("-k must be 4 or 8");
  if (!o.pose_file.empty() && o.skeleton.empty()) throw UsageError("--pose needs --skeleton");
  if (!o.twist_stretch.empty() && o.skeleton.empty()) throw UsageError("--twist-stretch needs --skeleton");
  if (!o.fast && (!o.free_list.empty())) throw UsageError("--free needs --fast");
  if (!o.fast && !o.additional.empty())
    throw UsageError("--additional needs --fast (only FAST sets the additional handles' transforms)");
  if (o.iterations < 1) throw UsageError("--iterations must be >= 1");
  try {
    o.method = dfm::parse_skin_method(method_name);
  } catch (const dfm::Error& e) {
    throw UsageError(e.what());
  }
  const std::string ext = dfm::file_extension(o.out);
  if (!o.out.empty() && ext != "obj" && ext != "ply" && ext != "off" && ext != "stl")
    throw UsageError("OUT must end in .obj, .ply, .off or .stl, got '" + o.out + "'");
  return o;
}

// The rig from --points and --skeleton, and the weights checked against it and the mesh.
dfm::Rig read_rig(const Options& o, const Input& in, Eigen::MatrixXd& W) {
  dfm::Rig rig;
  if (!o.points.empty()) dfm::add_points_file_to_rig(rig, o.points);
  if (!o.skeleton.empty()) dfm::add_tgf_to_rig(rig, dfm::read_tgf(o.skeleton), o.skeleton);
  const int nh = dfm::num_handles(rig);
  if (nh == 0) throw dfm::Error("pose: the rig has no handles (give --skeleton or --points)");
  W = dfm::read_dmat(o.weights);
  if (W.rows() != in.V.rows() || W.cols() != nh)
    throw dfm::file_error(o.weights, 0, "is " + std::to_string(W.rows()) + " x " + std::to_string(W.cols()) +
                                            " but the mesh has " + std::to_string(in.V.rows()) + " vertices and the rig " +
                                            std::to_string(nh) + " handles");
  return rig;
}

// --additional's weights (#V x a), or none.
Eigen::MatrixXd read_additional(const Options& o, const Input& in) {
  if (o.additional.empty()) return {};
  const Eigen::MatrixXd A = dfm::read_dmat(o.additional);
  if (A.rows() != in.V.rows() || A.cols() < 1 || !A.allFinite())
    throw dfm::file_error(o.additional, 0, "is " + std::to_string(A.rows()) + " x " + std::to_string(A.cols()) +
                                               " but additional weights need one finite row per mesh vertex (" +
                                               std::to_string(in.V.rows()) + ") and at least one column");
  return A;
}

// The pose files' parameters, and with --fast the free handles solved (and the additional ones, A's
// columns: the pose then holds their transforms past the rig's).
dfm::Pose posed_handles(const Options& o, const Input& in, const Eigen::MatrixXd& W, const Eigen::MatrixXd& A,
                        const dfm::Rig& rig, dfm::PoseParams& params) {
  params = dfm::rest_pose_params(rig);
  if (!o.pose_file.empty()) params.bone_rotation = dfm::read_bone_rotations(o.pose_file, rig.skeleton.num_bones());
  if (!o.twist_stretch.empty())
    params.bone_twist_stretch = dfm::read_bone_twist_stretch(o.twist_stretch, rig.skeleton.num_bones());
  if (!o.points_pose.empty())
    params.point_translation = dfm::read_point_translations(o.points_pose, dfm::num_point_handles(rig));
  dfm::Pose pose = dfm::evaluate_pose(rig, params);
  if (!o.fast) return pose;
  if (o.method != dfm::SkinMethod::LBS) throw dfm::cli::UsageError("--fast solves for linear blend skinning: use --method lbs");
  const std::vector<int> free = dfm::parse_handle_list(rig, o.free_list);
  const int na = static_cast<int>(A.cols());
  pose.transforms.resize(pose.transforms.size() + na, dfm::zero_transform());
  solve_fast(in, dfm::with_additional_weights(W, A), rig, free, o.iterations, pose);
  // The solved transforms through evaluate_pose: a pinned bone below a solved one follows it.
  const std::vector<dfm::FastConstraint> states = fast_constraints(rig, free, na);
  for (int h = 0; h < static_cast<int>(states.size()); ++h)
    if (states[h].state != dfm::HandleConstraint::Fixed) params.solved[h] = pose.transforms[h];
  if (na > 0) std::printf("fast: %d additional handles solved (their weights: %s)\n", na, o.additional.c_str());
  return dfm::skin_pose(rig, params, na);
}

// --dynamics: from rest, the files' pose as a step input at step 0; each step's solved transforms
// through evaluate_pose (a pinned bone below a solved one follows it) and skinned on the CPU.
int simulate(const Options& o, const Input& in, const Eigen::MatrixXd& W, const Eigen::MatrixXd& A, const dfm::Rig& rig) {
  if (o.method != dfm::SkinMethod::LBS) throw dfm::cli::UsageError("--fast solves for linear blend skinning: use --method lbs");
  dfm::PoseParams params;
  Options statics = o;
  statics.fast = false;
  const int nh = dfm::num_handles(rig), na = static_cast<int>(A.cols());
  dfm::Pose target_pose = posed_handles(statics, in, W, A, rig, params);
  target_pose.transforms.resize(nh + na, dfm::zero_transform());
  const std::vector<int> free = dfm::parse_handle_list(rig, o.free_list);
  const std::vector<dfm::FastConstraint> constraints = fast_constraints(rig, free, na);
  const std::vector<Eigen::Vector3d> targets = dfm::fast_targets(constraints, target_pose);
  const Eigen::MatrixXi& elements = in.T.rows() ? in.T : in.F;
  const Eigen::MatrixXd WA = dfm::with_additional_weights(W, A);
  const dfm::FastModel model = dfm::fast_model(in.V, elements, WA);
  const dfm::FastMass mass = dfm::fast_mass(in.V, elements, WA, o.density);
  dfm::FastDynamicsOptions opts;
  opts.dt = o.dt;
  opts.damping = o.damping;
  opts.iterations = o.iterations;
  dfm::Pose start = dfm::identity_pose(nh);
  start.transforms.resize(nh + na, dfm::zero_transform());
  dfm::FastDynamics dyn(model, mass, constraints, dfm::fast_joints(rig), opts, start);
  std::printf("dynamics: %d steps of %g s, damping %g/s, density %g, %d iterations per step, %d handles (%d free), "
              "mass %.6g\n",
              o.frames, o.dt, o.damping, o.density, o.iterations, nh, static_cast<int>(free.size()), mass.total);
  const dfm::SkinBinding binding = dfm::make_skin_binding(in.V, dfm::vertex_normals(in.V, in.F), W, rig, 0, {}, A);
  const dfm::FrameNaming naming = dfm::frame_naming(o.sequence);
  dfm::TriMesh frame;
  frame.F = in.F;
  double stepping = 0;
  for (int i = 0; i < o.frames; ++i) {
    dfm::Pose pose = target_pose;  // its Fixed handles are the boundary condition
    const auto t0 = std::chrono::steady_clock::now();
    dyn.step(pose, targets);
    stepping += seconds_since(t0);
    for (int h = 0; h < nh + na; ++h)
      if (constraints[h].state != dfm::HandleConstraint::Fixed) params.solved[h] = pose.transforms[h];
    const dfm::SkinResult posed = dfm::skin(o.method, binding, dfm::skin_pose(rig, params, na), {});
    frame.V = posed.V;
    frame.N = posed.N;
    const std::string path = dfm::frame_path(naming, i);
    dfm::write_surface(path, frame);
    std::printf("dynamics: frame %d kinetic %.9g -> %s\n", i, dyn.kinetic_energy(), path.c_str());
  }
  if (!o.out.empty()) dfm::write_surface(o.out, frame);
  std::printf("dynamics: %d frames, %.2f us per step (%.2f us per iteration)%s%s\n", o.frames, 1e6 * stepping / o.frames,
              1e6 * stepping / (o.frames * o.iterations), o.out.empty() ? "" : "; last frame -> ",
              o.out.empty() ? "" : o.out.c_str());
  return 0;
}

// Skins on the GPU when there is a display (and not --cpu), else on the CPU; `where` says which.
dfm::SkinResult skin_anywhere(const Options& o, const dfm::SkinBinding& kept, const dfm::Pose& pose,
                              const std::vector<dfm::StbsHandle>& stbs, std::string& where) {
  if (!o.force_cpu && dfm::gl::display_available()) {
    try {
      dfm::gl::Context ctx;
      dfm::gl::SkinPass pass(kept);
      pass.set_pose(pose, stbs);
      pass.run(o.method);
      where = "GPU (" + ctx.renderer() + ")";
      return pass.read_back_result();
    } catch (const dfm::Error& e) {
      std::cerr << "pose: GPU skinning unavailable (" << e.what() << "); using the CPU\n";
    }
  }
  where = o.force_cpu ? "CPU (--cpu)" : "CPU (no OpenGL context)";
  return dfm::skin(o.method, kept, pose, stbs);
}

// A scene at a time of its animation: what the editor shows there (the animation's frame; without
// keys the scene's pose), skinned with the scene's weights.
int pose_scene(const Options& o) {
  dfm::Document doc;
  doc.load_scene(o.input);
  if (!doc.has_weights()) throw dfm::Error(o.input + ": the scene has no weights (" + doc.weights_note() + ")");
  if (o.method_given) doc.set_method(o.method);
  // posed_surface holds the first key's pose before it and the last's after it, as glTF samples.
  if (doc.keys().size() >= 2 && (o.at < doc.keys().front().time || o.at > doc.keys().back().time))
    std::printf("pose: %g s is outside the keys (%g to %g s): the nearest key's pose\n", o.at, doc.keys().front().time,
                doc.keys().back().time);
  doc.set_time(o.at);
  const dfm::TriMesh posed = dfm::posed_surface(doc);
  dfm::write_surface(o.out, posed);
  std::printf("pose: %s at t = %g s (%d keys, %s): %d vertices -> %s\n", o.input.c_str(), o.at,
              static_cast<int>(doc.keys().size()), dfm::skin_method_name(doc.method()), static_cast<int>(posed.V.rows()),
              o.out.c_str());
  return 0;
}

int run(const dfm::cli::Args& args) {
  const Options o = parse_options(args);
  if (o.scene) return pose_scene(o);
  const Input in = read_input(o.input);
  Eigen::MatrixXd W;
  const dfm::Rig rig = read_rig(o, in, W);
  const Eigen::MatrixXd A = read_additional(o, in);
  if (o.dynamics) return simulate(o, in, W, A, rig);
  dfm::PoseParams params;
  const dfm::Pose pose = posed_handles(o, in, W, A, rig, params);
  const auto stbs = dfm::stbs_handles(rig, params.bone_twist_stretch);
  const Eigen::MatrixXd N = dfm::vertex_normals(in.V, in.F);
  Eigen::MatrixXd E;
  if (!o.endpoints.empty()) {
    E = dfm::read_dmat(o.endpoints);
    if (E.rows() != in.V.rows() || E.cols() != rig.skeleton.num_bones() || !E.allFinite() || E.minCoeff() < 0 ||
        E.maxCoeff() > 1)
      throw dfm::file_error(o.endpoints, 0, "expected #V x #bones = " + std::to_string(in.V.rows()) + " x " +
                                              std::to_string(rig.skeleton.num_bones()) + " values in [0, 1]");
  } else if (dfm::is_stbs(o.method) && rig.skeleton.num_bones() > 0) {
    std::printf("pose: STBS endpoint weights by projection onto each bone (no --endpoints from the bind)\n");
  }
  const dfm::SkinBinding kept = dfm::make_skin_binding(in.V, N, W, rig, o.k, E, A);

  std::string where;
  const auto t0 = std::chrono::steady_clock::now();
  const dfm::SkinResult posed = skin_anywhere(o, kept, pose, stbs, where);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const double trunc =
      o.k > 0 ? dfm::truncation_error(o.method, dfm::make_skin_binding(in.V, Eigen::MatrixXd(), W, rig, 0, E, A), kept, pose,
                                  stbs)
              : 0.0;
  const double diag = (in.V.colwise().maxCoeff() - in.V.colwise().minCoeff()).norm();

  dfm::TriMesh result;
  result.V = posed.V;
  result.F = in.F;
  result.N = posed.N;
  dfm::write_surface(o.out, result);
  const dfm::SparseInfluences rows = dfm::sparse_influences(kept.influences);
  const std::string kept_text = o.k > 0 ? "k = " + std::to_string(o.k) : "all weights";
  std::printf("pose: %d vertices, %d triangles, %d handles, %s, %s (%.2f per vertex on average, %d at most), "
              "skinned on the %s in %.1f ms\n",
              static_cast<int>(in.V.rows()), static_cast<int>(in.F.rows()), dfm::num_handles(rig),
              dfm::skin_method_name(o.method), kept_text.c_str(),
              in.V.rows() ? double(rows.num_entries()) / in.V.rows() : 0.0, rows.max_row, where.c_str(), ms);
  if (o.k > 0)
    std::printf("pose: largest truncation error of %d influences on this pose: %.3g (%.3g of the bbox diagonal)\n", o.k,
                trunc, diag > 0 ? trunc / diag : 0.0);
  std::printf("pose: wrote %s\n", o.out.c_str());
  return 0;
}

dfm::cli::Register reg{"pose", "skin a mesh into a pose (LBS, DQS, STBS) and save it", kUsage, &run};

}  // namespace
