// Skinning throughput on armadillo.obj (43k vertices):
//  * CPU: sparse k-influence LBS (core/skin) vs libigl's dense formulation U = M T, M the
//    #V x 4#H lbs_matrix precomputed once (the baseline); DQS and STBS alongside;
//  * GPU: render/skin_pass transform feedback, vertices per second, on whatever driver is present
//    (Mesa llvmpipe under xvfb-run here).
// Weights are synthetic (no bind in the loop): H point handles at farthest-point samples of the
// surface, w ∝ 1/d^4 normalized -- smooth and dense, so every vertex has H nonzero weights.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/mesh/io.h"
#include "core/skin/skin.h"
#include "core/util/error.h"
#include "render/gl_context.h"
#include "render/skin_pass.h"

using Clock = std::chrono::steady_clock;

static double best_ms(int reps, const std::function<void()>& f) {
  double best = 1e300;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = Clock::now();
    f();
    best = std::min(best, std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  return best;
}

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  const std::string path = argc > 1 ? argv[1] : std::string(DFM_DATA_DIR) + "/armadillo.obj";
  const dfm::TriMesh mesh = dfm::read_surface(path);
  const int nv = mesh.num_vertices();
  std::printf("bench_skin: %s, %d vertices; synthetic weights (no BBW in the loop)\n", path.c_str(), nv);

  for (int H : {10, 20}) {
    // Farthest-point samples as point handles.
    dfm::Rig rig;
    std::vector<double> dist(nv, 1e300);
    int next = 0;
    for (int h = 0; h < H; ++h) {
      rig.points.push_back({mesh.V.row(next).transpose(), ""});
      for (int i = 0; i < nv; ++i) dist[i] = std::min(dist[i], (mesh.V.row(i) - mesh.V.row(next)).norm());
      next = static_cast<int>(std::max_element(dist.begin(), dist.end()) - dist.begin());
    }
    Eigen::MatrixXd W(nv, H);
    for (int i = 0; i < nv; ++i) {
      for (int h = 0; h < H; ++h) W(i, h) = 1.0 / std::pow((mesh.V.row(i) - rig.points[h].position.transpose()).norm() + 1e-3, 4);
      W.row(i) /= W.row(i).sum();
    }
    // A plausible pose: each handle turns up to ~20 degrees about itself and moves ~5% of the size.
    std::mt19937 g(7);
    std::normal_distribution<double> n01(0, 1);
    const double diag = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
    dfm::Pose pose;
    for (int h = 0; h < H; ++h) {
      Eigen::Quaterniond q(1.0, 0.1 * n01(g), 0.1 * n01(g), 0.1 * n01(g));
      const Eigen::Vector3d c = rig.points[h].position;
      const Eigen::Vector3d t(n01(g), n01(g), n01(g));
      pose.transforms.push_back(Eigen::Translation3d(c + 0.05 * diag * t) * q.normalized() * Eigen::Translation3d(-c));
    }

    const Eigen::MatrixXd M = dfm::lbs_matrix(mesh.V, W);
    Eigen::MatrixXd U;
    const double dense_ms = best_ms(7, [&] { U.noalias() = M * dfm::pose_matrix(pose); });
    std::printf("\nH = %d handles\n  dense U = M T (libigl lbs_matrix, %d x %d):  %8.2f ms   (baseline)\n", H, nv,
                4 * H, dense_ms);
    const dfm::SkinBinding all = dfm::make_skin_binding(mesh.V, Eigen::MatrixXd(), W, rig, 0);
    Eigen::MatrixXd Ua;
    const double all_ms = best_ms(7, [&] { dfm::lbs(mesh.V, Eigen::MatrixXd(), all.influences, pose, Ua); });
    std::printf("  sparse LBS, all %2d influences:               %8.2f ms   %.2fx faster; max |diff| %.2g\n", H,
                all_ms, dense_ms / all_ms, (Ua - U).cwiseAbs().maxCoeff());
    for (int k : {4, 8}) {
      const dfm::SkinBinding b = dfm::make_skin_binding(mesh.V, Eigen::MatrixXd(), W, rig, k);
      Eigen::MatrixXd Uk;
      const double ms = best_ms(7, [&] { dfm::lbs(mesh.V, Eigen::MatrixXd(), b.influences, pose, Uk); });
      const double dq = best_ms(3, [&] { dfm::dqs(mesh.V, Eigen::MatrixXd(), b.influences, pose, Uk); });
      const double st = best_ms(3, [&] { Uk = dfm::skin(dfm::SkinMethod::STBS, b, pose).V; });
      std::printf("  sparse LBS, k = %d:                           %8.2f ms   %.2fx faster than dense "
                  "(DQS %.2f ms, STBS %.2f ms); truncation error %.3g of the bbox diagonal\n",
                  k, ms, dense_ms / ms, dq, st, dfm::truncation_error(dfm::SkinMethod::LBS, all, b, pose) / diag);
    }

    std::unique_ptr<dfm::gl::Context> context;
    try {
      context = std::make_unique<dfm::gl::Context>();
    } catch (const dfm::Error& e) {
      std::printf("  GPU: no OpenGL context (%s)\n", e.what());
      continue;
    }
    dfm::gl::Context& ctx = *context;
    for (int k : {0, 4, 8}) {  // 0: every weight (the default), in sparse rows
      const dfm::SkinBinding b = dfm::make_skin_binding(mesh.V, dfm::vertex_normals(mesh.V, mesh.F), W, rig, k);
      dfm::gl::SkinPass pass(b);
      pass.set_pose(pose);
      for (dfm::SkinMethod m : {dfm::SkinMethod::LBS, dfm::SkinMethod::DQS, dfm::SkinMethod::STBS}) {
        pass.run(m);  // compile + warm up
        glFinish();
        const int frames = 10;
        const double ms = best_ms(3, [&] {
          for (int f = 0; f < frames; ++f) {
            pass.set_pose(pose);
            pass.run(m);
          }
          glFinish();
        }) / frames;
        const std::string kept = k > 0 ? "k = " + std::to_string(k)
                                       : "all " + std::to_string(pass.num_entries()) + " weights (" +
                                             std::to_string(pass.max_influences()) + " at most)";
        std::printf("  GPU %s %s (%s): %7.2f ms/frame = %.3g vertices/s (positions + normals)\n",
                    dfm::skin_method_name(m), kept.c_str(), ctx.renderer().c_str(), ms, nv / (ms * 1e-3));
      }
    }
  }
  return 0;
}
