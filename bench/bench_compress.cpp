// Animations from base shapes (Alexa 2003, 7.2, Table 7.1): the elephant bound (BBW) to its 24 bones,
// five poses keyed (arms, legs, spine and head, with the whole body turning and walking), 200 frames
// baked (rotation-aware key interpolation, LBS and then DQS with every weight), each compressed to the
// mean plus k = 3, 5, 10, 50 and all base shapes. Prints Table 7.1's columns (bytes of the .pca file and
// the ratio to the raw float32 frames), the reconstruction errors, how much larger the error is without
// the rigid-motion removal, and the Gram-matrix route against QR + SVD (time and accuracy).
//   bench_compress [OUT_DIR]   (writes OUT_DIR/elephant-{lbs,dqs}-k10.glb; default /tmp)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "core/anim/interpolate.h"
#include "core/anim/pca_animation.h"
#include "core/anim/pca_file.h"
#include "core/bind/bind.h"
#include "core/export/gltf_pca.h"
#include "core/mesh/io.h"
#include "core/rig/pose_params.h"
#include "core/rig/rig_io.h"
#include "core/skin/skin.h"

using Clock = std::chrono::steady_clock;

static double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

static Eigen::Quaterniond turn(double deg, const Eigen::Vector3d& axis) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(deg * M_PI / 180.0, axis.normalized()));
}

// One key: bone rotations (relative to the parent, about the bone's first joint) plus the whole body
// turned about the vertical by `yaw` and moved by `walk` (the three root bones share joint 1).
static dfm::Pose key_pose(const dfm::Rig& rig, double yaw, const Eigen::Vector3d& walk,
                          const std::vector<std::pair<int, Eigen::Quaterniond>>& bones) {
  dfm::PoseParams p = dfm::rest_pose_params(rig);
  for (const auto& [b, q] : bones) p.bone_rotation[b] = q;
  for (int root : {0, 14, 19}) {
    p.bone_rotation[root] = turn(yaw, {0, 1, 0}) * p.bone_rotation[root];
    p.bone_translation[root] = walk;
  }
  return dfm::evaluate_pose(rig, p);
}

static dfm::KeyTrack elephant_keys(const dfm::Rig& rig) {
  const Eigen::Vector3d X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1);
  // Bones (TGF edge order): 0-5 spine to head, 6-9 right arm (7 upper), 10-13 left arm (11 upper),
  // 14-18 right leg (15 thigh, 16 shin), 19-23 left leg (20 thigh, 21 shin).
  dfm::KeyTrack t;
  t.set({0.0, key_pose(rig, 0, {0, 0, 0}, {})});
  t.set({2.0, key_pose(rig, 40, {5, 0, 10}, {{7, turn(70, Z)}, {20, turn(-35, X)}, {21, turn(40, X)}, {4, turn(20, X)}})});
  t.set({4.0, key_pose(rig, 90, {10, 2, 25}, {{11, turn(-70, Z)}, {15, turn(-35, X)}, {16, turn(40, X)}, {2, turn(25, Y)}})});
  t.set({6.0, key_pose(rig, 150, {0, 0, 40}, {{7, turn(-60, X)}, {11, turn(-60, X)}, {1, turn(25, X)}, {5, turn(-30, X)}})});
  t.set({8.0, key_pose(rig, 200, {-15, 0, 45}, {{8, turn(60, Y)}, {12, turn(-60, Y)}, {3, turn(-30, Z)}, {20, turn(30, X)}})});
  return t;
}

// The best rank-k error of the centred frames without the rigid-motion removal (7.2's motivation).
static Eigen::VectorXd unaligned_singular_values(const std::vector<Eigen::MatrixXd>& frames) {
  const int n = static_cast<int>(frames.size());
  const Eigen::Index nv = frames[0].rows();
  Eigen::MatrixXd mean = Eigen::MatrixXd::Zero(nv, 3);
  for (const auto& f : frames) mean += f / n;
  Eigen::MatrixXd X(3 * nv, n);
  for (int i = 0; i < n; ++i)
    for (Eigen::Index v = 0; v < nv; ++v)
      for (int c = 0; c < 3; ++c) X(3 * v + c, i) = frames[i](v, c) - mean(v, c);
  return Eigen::BDCSVD<Eigen::MatrixXd>(X).singularValues();
}

static double tail_norm(const Eigen::VectorXd& s, int k) {
  return k >= s.size() ? 0.0 : std::sqrt(s.tail(s.size() - k).squaredNorm());
}

// The Gram route: eigenvectors of X^T X (n x n), U = X W S^-1; rank-k error from the residual.
static void gram_route(const dfm::PcaDecomposition& d, const std::vector<int>& ks, const std::vector<double>& bdc) {
  const auto t0 = Clock::now();
  const Eigen::MatrixXd G = d.centred.transpose() * d.centred;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(G);
  const Eigen::MatrixXd W = eig.eigenvectors().rowwise().reverse();
  const Eigen::VectorXd s = eig.eigenvalues().reverse().cwiseMax(0).cwiseSqrt();
  const int kmax = ks.back();
  Eigen::MatrixXd U = d.centred * W.leftCols(kmax);
  for (int j = 0; j < kmax; ++j) U.col(j) /= s[j];
  const double t = seconds_since(t0);
  std::printf("Gram route (eigenvectors of the %d x %d Gram matrix, U = X W / s): %.3f s; relative difference of its "
              "rank-k error from the QR + SVD one, and |U^T U - I|:", d.num_frames(), d.num_frames(), t);
  for (size_t i = 0; i < ks.size(); ++i) {
    const Eigen::MatrixXd B = U.leftCols(ks[i]);
    const double e = (d.centred - B * (B.transpose() * d.centred)).norm();
    const double ortho = (B.transpose() * B - Eigen::MatrixXd::Identity(ks[i], ks[i])).cwiseAbs().maxCoeff();
    std::printf(" k=%d %.1e, %.1e;", ks[i], std::abs(e - bdc[i]) / bdc[i], ortho);
  }
  std::printf("\n");
}

// Table 7.1's columns for one baked animation; writes OUT_DIR/elephant-<label>-k10.glb.
static void table(const std::vector<Eigen::MatrixXd>& frames, const Eigen::MatrixXi& F, const std::string& label,
                  const std::string& out_dir) {
  const int n = static_cast<int>(frames.size()), nv = static_cast<int>(frames[0].rows());
  auto t0 = Clock::now();
  const dfm::PcaDecomposition d = dfm::decompose_frames(frames);
  std::printf("\n%s: decompose (align + centre + QR + SVD of %d x %d) %.2f s\n", label.c_str(), 3 * nv, n, seconds_since(t0));
  const double raw = 12.0 * n * nv, topo = 12.0 * F.rows();
  const double diag = d.bbox_diagonal;
  const Eigen::VectorXd unaligned = unaligned_singular_values(frames);
  std::printf("Table 7.1 columns (bbox diagonal %.2f; errors over the %d frames)\n", diag, n);
  std::printf("%8s %12s %8s %10s | %12s %12s %10s %10s | %14s\n", "bases", "bytes", "ratio", "w/o tris", "max frame",
              "mean frame", "max RMS", "max vertex", "no alignment:");
  std::printf("%8s %12s %8s %10s | %12s %12s %10s %10s | %14s\n", "", "(.pca)", "", "", "(Frobenius)", "(Frobenius)",
              "/ diag", "/ diag", "total / total");
  std::printf("%8s %12.0f %7.2f%% %9.2f%% |\n", "original", raw, 100.0, 100.0);
  const std::vector<int> ks = {3, 5, 10, 50, n};
  std::vector<double> totals;
  const std::string pca_path = out_dir + "/bench_compress.pca";
  for (int k : ks) {
    const dfm::PcaAnimation a = dfm::pca_animation(d, k, F, dfm::frame_times(n, 25));
    const dfm::PcaErrors e = dfm::pca_errors(d, a);
    dfm::write_pca(pca_path, a);
    const double bytes = static_cast<double>(std::filesystem::file_size(pca_path));
    double worst = 0, mean = 0, rms = 0, vert = 0;
    for (int i = 0; i < n; ++i) {
      worst = std::max(worst, e.frobenius[i]);
      mean += e.frobenius[i] / n;
      rms = std::max(rms, e.rms_relative(i));
      vert = std::max(vert, e.max_vertex[i] / diag);
    }
    totals.push_back(e.total);
    std::printf("%8d %12.0f %7.2f%% %9.2f%% | %12.4g %12.4g %10.2e %10.2e | %14.3g\n", k, bytes, 100 * bytes / raw,
                100 * (bytes - topo) / raw, worst, mean, rms, vert,
                e.total > 1e-9 * d.singular_values[0] ? tail_norm(unaligned, k) / e.total : 0.0);
    if (k == 10) {
      const std::string glb = out_dir + "/elephant-" + label + "-k10.glb";
      t0 = Clock::now();
      const dfm::PcaGltfReport g = dfm::export_pca_gltf(glb, a, {"elephant", true});
      std::printf("         -> %s (%.0f bytes, %.2f s): normals off by %.2f deg mean, %.1f max (fixed normals %.2f)\n",
                  glb.c_str(), static_cast<double>(std::filesystem::file_size(glb)), seconds_since(t0),
                  g.normal_mean_angle_deg, g.normal_max_angle_deg, g.fixed_normal_mean_angle_deg);
    }
  }
  std::filesystem::remove(pca_path);
  std::printf("singular values:");
  for (int j = 0; j < 12; ++j) std::printf(" %.4g", d.singular_values[j]);
  std::printf(" ... s_50 %.4g, s_100 %.4g\n", d.singular_values[49], d.singular_values[99]);
  totals.pop_back();
  gram_route(d, {3, 5, 10, 50}, totals);
}

int main(int argc, char** argv) {
  const std::string out_dir = argc > 1 ? argv[1] : "/tmp";
  const std::string data = DFM_DATA_DIR;
  dfm::TriMesh surface = dfm::read_surface(data + "/elephant.obj");
  dfm::Rig rig;
  dfm::add_tgf_to_rig(rig, dfm::read_tgf(data + "/elephant.tgf"), "elephant.tgf");
  auto t0 = Clock::now();
  const dfm::BindResult bound = dfm::bind_surface(surface, rig);
  std::printf("elephant: %d vertices, %d triangles, %d bones; bind %.1f s; raw float32 frames: 200 x %d x 12 bytes\n",
              surface.num_vertices(), surface.num_faces(), rig.skeleton.num_bones(), seconds_since(t0),
              surface.num_vertices());
  const dfm::SkinBinding binding = dfm::make_skin_binding(surface.V, Eigen::MatrixXd(), bound.weights, rig, 0);
  const dfm::KeyTrack track = elephant_keys(rig);
  // LBS frames are linear in the bones' 12 affine entries, so their rank is bounded (about 12 per moving
  // bone); DQS blends nonlinearly and shows how a general deformation compresses.
  for (dfm::SkinMethod method : {dfm::SkinMethod::LBS, dfm::SkinMethod::DQS}) {
    const int n = 200;
    std::vector<Eigen::MatrixXd> frames;
    t0 = Clock::now();
    for (int i = 0; i < n; ++i) {
      const double t = track.start() + (track.end() - track.start()) * i / (n - 1);
      frames.push_back(dfm::skin(method, binding, dfm::sample_track(track, t)).V);
    }
    const std::string label = dfm::skin_method_name(method);
    std::printf("\nbaked %d frames with %s (5 keys over %.0f s, every weight) in %.2f s\n", n, label.c_str(), track.end(),
                seconds_since(t0));
    table(frames, surface.F, label, out_dir);
  }
  return 0;
}
