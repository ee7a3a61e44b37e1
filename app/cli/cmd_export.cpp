// `deform export`: the bound, posed and keyed surface as glTF 2.0 (.glb, or .gltf + .bin), with the
// handles as a skin's joints, the keys as an animation and optionally baked frames as morph targets.
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "app/cli/command.h"
#include "core/anim/interpolate.h"
#include "core/export/export_document.h"
#include "core/export/gltf_export.h"
#include "core/export/gltf_verify.h"
#include "core/mesh/io.h"
#include "core/rig/pose_io.h"
#include "core/rig/pose_params.h"
#include "core/rig/rig_io.h"
#include "core/mesh/mesh_info.h"
#include "core/scene/document.h"
#include "core/skin/lbs.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace {

const char* kUsage =
    "usage: deform export INPUT -o OUT.glb|OUT.gltf [options]\n"
    "  INPUT is a scene file (*.json: surface, rig, weights, pose and keys come from it) or a mesh\n"
    "  (.obj .off .ply .stl, or a tet mesh .mesh/.node/.ele whose boundary surface is exported).\n"
    "With a mesh:\n"
    "  --weights W.dmat      weights, #V x #handles (V: surface vertices, or tet vertices for a tet mesh)\n"
    "  --skeleton S.tgf      bones and point handles\n"
    "  --pose Q.dmat...      bone rotations per key (hand-pose.dmat layout); the keys are the rest pose at\n"
    "                        t=0 and each file at t=1,2,... (x --key-seconds); the last is the current pose\n"
    "  --points P.txt        point-handle translations applied in every --pose key\n"
    "  --key-seconds S       time between keys (default 1)\n"
    "Always:\n"
    "  -k 4|8                influences per vertex (JOINTS_0/WEIGHTS_0, or also JOINTS_1/WEIGHTS_1); default 4\n"
    "  --residual-morphs TOL when the pruned skin misses LBS with all weights by more than TOL x bbox\n"
    "                        diagonal at a key (1e-4 is a good value), store the misses as morph targets\n"
    "                        of the skinned mesh so the keys play back exactly (default: off)\n"
    "  --morph-frames N      also bake N frames (LBS, all weights, keys interpolated) as morph targets\n"
    "  --verify              re-import the file and report its error against LBS with all weights per key\n"
    "The exporter reports the largest vertex error the influence pruning causes over the keys.";

void load_scene_input(const std::string& path, dfm::GltfExportInput& in) {
  dfm::Document doc;
  doc.load_scene(path);
  if (!doc.has_weights()) throw dfm::file_error(path, 0, "the scene has no weights (" + doc.weights_note() + "): run bind first");
  in = dfm::gltf_input_from_document(doc);
}

void load_mesh_input(const std::string& path, const std::string& weights, const std::string& skeleton,
                     const std::vector<std::string>& poses, const std::string& points, double key_seconds,
                     dfm::GltfExportInput& in) {
  Eigen::VectorXi to_tet;
  int tet_vertices = -1;
  if (dfm::is_tet_mesh_path(path)) {
    const dfm::TetMesh tets = dfm::read_tet_mesh(path);
    tet_vertices = tets.num_vertices();
    in.surface = dfm::tet_boundary_surface(tets, &to_tet);
  } else {
    in.surface = dfm::read_surface(path);
  }
  if (!skeleton.empty()) dfm::add_tgf_to_rig(in.rig, dfm::read_tgf(skeleton), skeleton);
  const int nh = dfm::num_handles(in.rig);
  if (nh == 0) throw dfm::Error("export: the rig has no handles (give --skeleton)");
  const Eigen::MatrixXd W = dfm::read_dmat(weights);
  if (W.cols() != nh)
    throw dfm::file_error(weights, 0, std::to_string(W.cols()) + " weight columns, the rig has " + std::to_string(nh) +
                                          " handles");
  if (W.rows() == in.surface.num_vertices()) {
    in.weights = W;
  } else if (W.rows() == tet_vertices) {
    in.weights.resize(to_tet.size(), nh);
    for (int i = 0; i < to_tet.size(); ++i) in.weights.row(i) = W.row(to_tet[i]);
  } else {
    throw dfm::file_error(weights, 0, std::to_string(W.rows()) + " weight rows, expected " +
                                          std::to_string(in.surface.num_vertices()) + " (surface vertices)" +
                                          (tet_vertices >= 0 ? " or " + std::to_string(tet_vertices) + " (tet vertices)" : ""));
  }
  const dfm::PoseParams rest = dfm::rest_pose_params(in.rig);
  in.current = dfm::evaluate_pose(in.rig, rest);
  if (poses.empty()) return;
  in.keys.push_back({0.0, in.current});
  for (size_t i = 0; i < poses.size(); ++i) {
    dfm::PoseParams p = rest;
    p.bone_rotation = dfm::read_bone_rotations(poses[i], in.rig.skeleton.num_bones());
    if (!points.empty())
      p.point_translation = dfm::read_point_translations(points, dfm::num_point_handles(in.rig));
    in.keys.push_back({key_seconds * (i + 1), dfm::evaluate_pose(in.rig, p)});
  }
  in.current = in.keys.back().pose;
}

// What the command line asks for.
struct Options {
  std::string input, out, weights, skeleton, points;
  std::vector<std::string> poses;
  int k = 4, morph_frames = 0;
  double key_seconds = 1.0, residual_tolerance = 0.0;
  bool verify = false;
};

Options parse_options(const dfm::cli::Args& args) {
  dfm::cli::ArgReader a(args);
  Options o;
  auto& [input, out, weights, skeleton, points, poses, k, morph_frames, key_seconds, residual_tolerance, verify] = o;
  while (!a.done()) {
    const std::string f = a.next();
    if (f == "-o" || f == "--output") out = a.value(f);
    else if (f == "--weights") weights = a.value(f);
    else if (f == "--skeleton") skeleton = a.value(f);
    else if (f == "--pose") {
      while (!a.done() && (a.peek().empty() || a.peek()[0] != '-')) poses.push_back(a.next());
      if (poses.empty()) throw dfm::cli::UsageError("--pose needs at least one file");
    }
    else if (f == "--points") points = a.value(f);
    else if (f == "--key-seconds") key_seconds = a.number(f);
    else if (f == "-k") k = a.integer(f);
    else if (f == "--morph-frames") morph_frames = a.integer(f);
    else if (f == "--residual-morphs") residual_tolerance = a.number(f);
    else if (f == "--verify") verify = true;
    else if (!f.empty() && f[0] == '-') throw dfm::cli::UsageError("unknown option " + f);
    else if (input.empty()) input = f;
    else throw dfm::cli::UsageError("more than one INPUT given");
  }
  if (input.empty()) throw dfm::cli::UsageError("INPUT is required");
  if (out.empty()) throw dfm::cli::UsageError("-o OUT.glb|OUT.gltf is required");
  if (k != 4 && k != 8) throw dfm::cli::UsageError("-k must be 4 or 8");
  if (morph_frames < 0 || morph_frames == 1) throw dfm::cli::UsageError("--morph-frames needs 0 or at least 2");
  if (!(residual_tolerance > 0) && residual_tolerance != 0) throw dfm::cli::UsageError("--residual-morphs needs a positive tolerance");
  if (!(key_seconds > 0)) throw dfm::cli::UsageError("--key-seconds must be positive");
  const std::string oext = dfm::file_extension(out);
  if (oext != "glb" && oext != "gltf") throw dfm::cli::UsageError("-o must name a .glb or .gltf file");
  return o;
}

// The input: a scene file, or a mesh with its weights, rig and poses.
dfm::GltfExportInput read_export_input(const Options& o) {
  const auto& [input, out, weights, skeleton, points, poses, k, morph_frames, key_seconds, residual_tolerance, verify] = o;
  dfm::GltfExportInput in;
  const bool scene = dfm::file_extension(input) == "json";
  if (scene) {
    if (!weights.empty() || !skeleton.empty() || !poses.empty() || !points.empty())
      throw dfm::cli::UsageError("a scene file carries its own rig, weights and pose: drop the rig flags");
    load_scene_input(input, in);
  } else {
    if (weights.empty()) throw dfm::cli::UsageError("--weights W.dmat is required with a mesh INPUT");
    load_mesh_input(input, weights, skeleton, poses, points, key_seconds, in);
    in.name = std::filesystem::path(input).stem().string();  // a scene is named by gltf_input_from_document
    if (in.name.empty()) in.name = "mesh";
  }

  return in;
}

// Morph frames baked evenly between the first and the last key (--morph-frames).
void bake_morph_frames(int morph_frames, dfm::GltfExportInput& in) {
  if (morph_frames <= 0) return;
  {
    if (in.keys.size() < 2) throw dfm::Error("export: --morph-frames needs at least two keys to bake between");
    dfm::KeyTrack track;
    for (const auto& key : in.keys) track.set({key.time, key.pose});
    for (int i = 0; i < morph_frames; ++i) {
      const double t = track.start() + (track.end() - track.start()) * i / (morph_frames - 1);
      in.morph_times.push_back(t);
      in.morph_frames.push_back(dfm::lbs(in.surface.V, in.weights, dfm::sample_track(track, t)));
    }
  }

}

// Re-imports the file and compares its skinning with LBS on all weights (--verify).
void print_verification(const std::string& out, const dfm::GltfExportInput& in, double diag) {
  {
    std::vector<double> times;
    std::vector<dfm::Pose> key_poses;
    for (const auto& key : in.keys) times.push_back(key.time), key_poses.push_back(key.pose);
    const dfm::GltfVerifyResult v = dfm::verify_gltf_export(out, in.surface.V, in.weights, in.current, times, key_poses);
    std::cout << "  verify (re-imported, glTF skinning vs LBS with all weights): max " << v.max_error / diag
              << " of the bbox diagonal; current pose " << v.current_error / diag;
    for (size_t i = 0; i < v.key_errors.size(); ++i) std::cout << "; key " << i << " " << v.key_errors[i] / diag;
    std::cout << "\n";
  }
}

int run(const dfm::cli::Args& args) {
  const Options o = parse_options(args);
  const auto& [input, out, weights, skeleton, points, poses, k, morph_frames, key_seconds, residual_tolerance, verify] = o;
  dfm::GltfExportInput in = read_export_input(o);
  bake_morph_frames(morph_frames, in);
  dfm::GltfExportOptions options;
  options.influences = k;
  options.residual_morph_tolerance = residual_tolerance;
  const dfm::GltfExportReport r = dfm::export_gltf(out, in, options);
  const double diag = r.bbox_diagonal > 0 ? r.bbox_diagonal : 1.0;
  std::cout << "wrote " << out << ": " << r.vertices << " vertices, " << r.triangles << " triangles, " << r.joints
            << " joints, " << r.keys << " keys, " << r.morph_targets << " morph targets, " << r.influences
            << " influences per vertex, " << r.residual_targets << " residual morph targets\n";
  std::cout << std::setprecision(4) << "  pruning error (LBS, all weights vs " << r.influences
            << "), max over the keys: " << r.max_prune_error << " = " << r.max_prune_error / diag
            << " of the bbox diagonal (" << (r.max_prune_error_key < 0 ? std::string("current pose")
                                                                     : "key " + std::to_string(r.max_prune_error_key))
            << ")\n";
  std::cout << "  TRS residual (shear): max " << r.max_shear << ", " << r.sheared_transforms << " transform(s) above 1e-6\n";
  for (const auto& n : r.notes) std::cout << "  note: " << n << "\n";
  if (verify) print_verification(out, in, diag);
  return 0;
}

dfm::cli::Register reg{"export", "export the posed, keyed rig to glTF 2.0 (.glb / .gltf)", kUsage, &run};

}  // namespace
