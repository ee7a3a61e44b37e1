// `deform compress`: a frame sequence of one connectivity as the mean plus k base shapes after its rigid
// motion is removed (Alexa 2003, 7.2), saved as a compact .pca file and optionally as glTF morph targets
// (7.3). Prints the sizes and each frame's reconstruction error.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "app/cli/command.h"
#include "core/anim/pca_animation.h"
#include "core/anim/pca_file.h"
#include "core/export/gltf_pca.h"
#include "core/mesh/io.h"
#include "core/scene/document.h"
#include "core/scene/key_surfaces.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace {

const char* kUsage =
    "usage: deform compress --frames F0 F1 ... | SCENE.scene.json [--count N]  -k K -o ANIM.pca\n"
    "                       [--fps F] [--gltf OUT.glb|OUT.gltf] [--no-normals]\n"
    "  --frames F0 F1 ...  surfaces with the same vertices and triangles, one per frame (time i / fps)\n"
    "  SCENE.scene.json    a bound scene: its pose keys baked (skinned with its method and weights) as\n"
    "                      the keys plus its in-betweens, or --count N frames evenly from first to last key\n"
    "  -k K                base shapes kept, 0 <= K <= min(frames, 3 x vertices)\n"
    "  -o ANIM.pca         the compressed animation (float32; see core/anim/pca_file.h)\n"
    "  --fps F             frames per second of --frames (default 24)\n"
    "  --gltf OUT          also write glTF 2.0: the K bases as morph targets, the coefficients as animated\n"
    "                      weights, the rigid motion as the node's translation and rotation\n"
    "  --no-normals        glTF without NORMAL (and without fitted NORMAL deltas)\n"
    "Prints the raw size (frames x vertices x 3 float32), the file size and ratio, and per frame the\n"
    "reconstruction error: the Frobenius norm of the aligned frame minus its rank-K reconstruction, its RMS\n"
    "per vertex and largest vertex distance as fractions of frame 0's bounding-box diagonal.";

struct Frames {
  std::vector<Eigen::MatrixXd> V;
  Eigen::MatrixXi F;
  std::vector<double> times;
};

Frames read_frame_files(const std::vector<std::string>& files, double fps) {
  Frames fr;
  for (size_t i = 0; i < files.size(); ++i) {
    dfm::TriMesh m = dfm::read_surface(files[i]);
    if (i == 0) fr.F = m.F;
    else if (m.V.rows() != fr.V[0].rows() || m.F != fr.F)
      throw dfm::Error(files[i] + ": its vertices or triangles differ from " + files[0] + "'s (" +
                       std::to_string(m.V.rows()) + " vertices, " + std::to_string(m.F.rows()) + " triangles vs " +
                       std::to_string(fr.V[0].rows()) + ", " + std::to_string(fr.F.rows()) +
                       "): compression needs one connectivity");
    fr.V.push_back(std::move(m.V));
  }
  fr.times = dfm::frame_times(static_cast<int>(files.size()), fps);
  return fr;
}

Frames bake_scene(const std::string& path, int count) {
  dfm::Document doc;
  doc.load_scene(path);
  dfm::BakedLayers layers;
  try {
    layers = dfm::baked_pose_frames(doc, count);
  } catch (const dfm::Error& e) {
    throw dfm::Error(path + ": " + e.what());
  }
  return {std::move(layers.positions), doc.surface().F, std::move(layers.times)};
}

void print_errors(const dfm::PcaAnimation& a, const dfm::PcaErrors& e) {
  const double diag = e.bbox_diagonal > 0 ? e.bbox_diagonal : 1.0;
  std::printf("  frame      time   error (Frobenius)   RMS / diag   max vertex / diag\n");
  double sum = 0, worst = 0;
  for (int i = 0; i < a.num_frames(); ++i) {
    std::printf("  %5d %9.4f   %17.6g   %10.3g   %17.3g\n", i, a.times[i], e.frobenius[i], e.rms_relative(i),
                e.max_vertex[i] / diag);
    sum += e.frobenius[i];
    worst = std::max(worst, e.frobenius[i]);
  }
  std::printf("  all frames: total %.6g (sqrt of the sum of squares: the best rank-%d error of the centred, aligned "
              "frames), per frame max %.6g, mean %.6g\n",
              e.total, a.num_bases(), worst, sum / a.num_frames());
}

// Largest distance between the frames decoded from the written file and the double result.
double storage_error(const dfm::PcaAnimation& a, const dfm::PcaAnimation& file) {
  double worst = 0;
  for (int i = 0; i < a.num_frames(); ++i)
    worst = std::max(worst, (dfm::pca_frame(a, i) - dfm::pca_frame(file, i)).rowwise().norm().maxCoeff());
  return worst;
}

int run(const dfm::cli::Args& args) {
  using dfm::cli::UsageError;
  std::vector<std::string> files;
  std::string scene, out, gltf;
  int k = -1, count = 0;
  double fps = 24;
  bool normals = true, count_given = false;
  dfm::cli::ArgReader r(args);
  while (!r.done()) {
    const std::string f = r.next();
    if (f == "--frames") files = r.values(f);
    else if (f == "-k") k = r.integer(f);
    else if (f == "-o" || f == "--output") out = r.value(f);
    else if (f == "--fps") fps = r.number(f);
    else if (f == "--count") count = r.integer(f), count_given = true;
    else if (f == "--gltf") gltf = r.value(f);
    else if (f == "--no-normals") normals = false;
    else if (!f.empty() && f[0] == '-') throw UsageError("unknown option " + f);
    else if (scene.empty()) scene = f;
    else throw UsageError("more than one input: " + scene + ", " + f);
  }
  if (files.empty() == scene.empty()) throw UsageError("give either --frames F0 F1 ... or one SCENE.scene.json");
  if (!scene.empty() && dfm::file_extension(scene) != "json") throw UsageError(scene + " is not a scene (.json); frames go after --frames");
  if (count_given && (scene.empty() || count < 2)) throw UsageError("--count N (N >= 2) goes with a scene input");
  if (k < 0) throw UsageError("-k K (K >= 0) is required");
  if (out.empty()) throw UsageError("-o ANIM.pca is required");
  if (!(fps > 0) || !std::isfinite(fps)) throw UsageError("--fps must be positive");
  if (!gltf.empty() && dfm::file_extension(gltf) != "glb" && dfm::file_extension(gltf) != "gltf")
    throw UsageError("--gltf must name a .glb or .gltf file");

  const Frames fr = scene.empty() ? read_frame_files(files, fps) : bake_scene(scene, count);
  const int n = static_cast<int>(fr.V.size()), nv = static_cast<int>(fr.V[0].rows());
  if (k > std::min(n, 3 * nv))
    throw UsageError("-k " + std::to_string(k) + " is more than min(frames, 3 x vertices) = " + std::to_string(std::min(n, 3 * nv)));
  const auto t0 = std::chrono::steady_clock::now();
  const dfm::PcaDecomposition d = dfm::decompose_frames(fr.V);
  const double svd_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const dfm::PcaAnimation a = dfm::pca_animation(d, k, fr.F, fr.times);
  const dfm::PcaErrors e = dfm::pca_errors(d, a);
  dfm::write_pca(out, a);
  const dfm::PcaAnimation stored = dfm::read_pca(out);

  double max_angle = 0;
  for (const auto& m : a.motion) max_angle = std::max(max_angle, 2 * std::acos(std::min(1.0, std::abs(m.rotation.w()))));
  std::printf("compress: %d frames of %d vertices and %d triangles, k = %d (at most %d)\n", n, nv,
              static_cast<int>(fr.F.rows()), k, d.max_bases());
  std::printf("  rigid motion removed (each frame aligned to frame 0, no scale): largest rotation %.2f deg\n",
              max_angle * 180.0 / M_PI);
  std::printf("  thin SVD of the %d x %d centred, aligned frame matrix: %.3f s (with the alignment); singular values",
              3 * nv, n, svd_s);
  for (int j = 0; j < std::min<int>(8, d.singular_values.size()); ++j) std::printf(" %.4g", d.singular_values[j]);
  std::printf("%s\n", d.singular_values.size() > 8 ? " ..." : "");
  const double raw = 12.0 * n * nv, bytes = static_cast<double>(dfm::pca_file_bytes(nv, fr.F.rows(), n, k));
  const double topo = 12.0 * fr.F.rows();
  std::printf("  size: frames as float32 %.0f bytes (%d x %d x 3 x 4); %s %.0f bytes = %.2f%%; without the "
              "triangles %.0f bytes = %.2f%%\n",
              raw, n, nv, out.c_str(), bytes, 100 * bytes / raw, bytes - topo, 100 * (bytes - topo) / raw);
  print_errors(a, e);
  const double se = storage_error(a, stored);
  std::printf("  float32 storage: frames decoded from the file differ from the double result by at most %.3g "
              "(%.3g of the diagonal)\n", se, se / (e.bbox_diagonal > 0 ? e.bbox_diagonal : 1.0));
  std::printf("wrote %s\n", out.c_str());
  if (!gltf.empty()) {
    dfm::PcaGltfOptions o;
    o.normals = normals;
    const dfm::PcaGltfReport g = dfm::export_pca_gltf(gltf, a, o);
    std::printf("wrote %s: %d morph targets, %d frames", gltf.c_str(), g.morph_targets, g.frames);
    if (normals)
      std::printf("; blended normals off by %.3g deg on average, %.3g at most (fixed normals: %.3g on average)",
                  g.normal_mean_angle_deg, g.normal_max_angle_deg, g.fixed_normal_mean_angle_deg);
    std::printf("\n");
  }
  return 0;
}

dfm::cli::Register reg{"compress", "a same-connectivity frame sequence as mean + k base shapes (.pca, glTF morphs)",
                       kUsage, &run};

}  // namespace
