// Animation manifold slicing throughput: tetrahedra sliced per second on the CPU (baseline) and on
// the GPU path (geometry shader + transform feedback; Mesa llvmpipe under xvfb-run here).
// Manifold: armadillo.obj turned and shifted over 50 layers (~12.7 M tetrahedra).
// Full sweep on x: every tetrahedron is visited per slice. Per frame on t: only the active slab.
// Memory: the CPU manifold keeps doubles (so key-time slices are the keyframes bit for bit); the GPU
// copy uses float positions and int32 indices.
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <Eigen/Geometry>

#include "core/anim/manifold.h"
#include "core/anim/slice.h"
#include "core/mesh/io.h"
#include "render/gl_context.h"
#include "render/slice_pass.h"

using namespace dfm;
using Clock = std::chrono::steady_clock;

// The build machine is shared, so wall time mostly measures other people's compiles. Rates use
// process CPU time (all threads, so llvmpipe's worker threads count too); wall time is printed beside.
struct Timer {
  Clock::time_point wall = Clock::now();
  std::clock_t cpu = std::clock();
  double wall_s() const { return std::chrono::duration<double>(Clock::now() - wall).count(); }
  double cpu_s() const { return double(std::clock() - cpu) / CLOCKS_PER_SEC; }
};
static double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : std::string(DFM_DATA_DIR) + "/armadillo.obj";
  const int layers_n = argc > 2 ? std::atoi(argv[2]) : 50;
  const int x_slices = 3, t_frames = 20;

  const TriMesh mesh = read_surface(path);
  const Eigen::Vector3d ctr = mesh.V.colwise().mean();
  const double diag = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
  std::vector<Eigen::MatrixXd> layers;
  std::vector<double> times;
  for (int i = 0; i < layers_n; ++i) {
    const Eigen::Affine3d a(Eigen::Translation3d(ctr + Eigen::Vector3d(0.002 * diag * i, 0, 0)) *
                            Eigen::AngleAxisd(0.03 * i, Eigen::Vector3d::UnitY()) * Eigen::Translation3d(-ctr));
    layers.push_back(((a.linear() * mesh.V.transpose()).colwise() + a.translation()).transpose());
    times.push_back(i);
  }
  auto t0 = Clock::now();
  const AnimationManifold M = build_manifold(layers, mesh.F, times);
  layers.clear();
  layers.shrink_to_fit();
  const double build_s = seconds_since(t0);
  const double nt = M.num_tets();
  std::printf("manifold: %s, %d layers, %d triangles/layer -> %d tets, %d vertices; built in %.2f s\n", path.c_str(),
              layers_n, mesh.num_faces(), M.num_tets(), M.num_vertices(), build_s);
  std::printf("memory: CPU %.0f MB (double positions, int32 tets); GPU copy %.0f MB (float positions, int32 indices)\n",
              (M.V.size() * 8.0 + M.T.size() * 4.0) / 1e6, (M.V.size() * 4.0 + M.T.size() * 4.0) / 1e6);

  const double xlo = M.V.col(0).minCoeff(), xhi = M.V.col(0).maxCoeff();
  std::vector<double> xs, ts;
  for (int i = 0; i < x_slices; ++i) xs.push_back(xlo + (xhi - xlo) * (i + 0.5) / x_slices);
  for (int i = 0; i < t_frames; ++i) ts.push_back((layers_n - 1) * (i + 0.37) / t_frames);

  // CPU baseline.
  long long cpu_x_tris = 0, cpu_t_tets = 0;
  std::vector<int> cpu_x_counts, cpu_t_counts;
  Timer tm;
  for (double x : xs) {
    const int n = slice_manifold(M, SliceAxis::X, x).mesh.num_faces();
    cpu_x_counts.push_back(n);
    cpu_x_tris += n;
  }
  const double cpu_x_s = tm.cpu_s(), cpu_x_w = tm.wall_s();
  tm = Timer();
  for (double t : ts) {
    const auto r = slice_tet_range(M, SliceAxis::T, t);
    cpu_t_tets += r.second - r.first;
    cpu_t_counts.push_back(slice_manifold(M, SliceAxis::T, t).mesh.num_faces());
  }
  const double cpu_t_s = tm.cpu_s(), cpu_t_w = tm.wall_s();
  const double cpu_x_rate = nt * x_slices / cpu_x_s, cpu_t_rate = cpu_t_tets / cpu_t_s;
  std::printf("CPU  x sweep: %d slices, %.3f s CPU (%.3f s wall) = %.1f M tets/CPU-s (%.0f ms/slice, %lld triangles)\n",
              x_slices, cpu_x_s, cpu_x_w, cpu_x_rate / 1e6, 1e3 * cpu_x_s / x_slices, cpu_x_tris);
  std::printf("CPU  t frames: %d frames, %.3f s CPU (%.3f s wall) = %.1f M tets/CPU-s (%.1f ms/frame)\n", t_frames,
              cpu_t_s, cpu_t_w, cpu_t_rate / 1e6, 1e3 * cpu_t_s / t_frames);

  if (!gl::display_available()) {
    std::printf("GPU: no display (run under xvfb-run -a -s \"-screen 0 1280x1024x24\"); skipped\n");
    return 0;
  }
  gl::Context ctx;
  gl::SlicePass pass;
  tm = Timer();
  pass.upload(M);
  glFinish();
  const double up_s = tm.wall_s();
  std::printf("GPU: %s; upload %.2f s\n", ctx.renderer().c_str(), up_s);
  pass.slice(SliceAxis::T, ts[0]);  // warm-up (shader JIT)
  bool same = true;
  tm = Timer();
  for (int i = 0; i < x_slices; ++i) same &= pass.slice(SliceAxis::X, xs[i]) == cpu_x_counts[i];
  const double gpu_x_s = tm.cpu_s(), gpu_x_w = tm.wall_s();
  tm = Timer();
  for (int i = 0; i < t_frames; ++i) same &= pass.slice(SliceAxis::T, ts[i]) == cpu_t_counts[i];
  const double gpu_t_s = tm.cpu_s(), gpu_t_w = tm.wall_s();
  const double gpu_x_rate = nt * x_slices / gpu_x_s, gpu_t_rate = cpu_t_tets / gpu_t_s;
  std::printf("GPU  x sweep: %d slices, %.3f s CPU (%.3f s wall) = %.1f M tets/CPU-s (%.0f ms/slice)  GPU/CPU %.2fx"
              " (wall %.2fx)\n", x_slices, gpu_x_s, gpu_x_w, gpu_x_rate / 1e6, 1e3 * gpu_x_s / x_slices,
              gpu_x_rate / cpu_x_rate, cpu_x_w / gpu_x_w);
  std::printf("GPU  t frames: %d frames, %.3f s CPU (%.3f s wall) = %.1f M tets/CPU-s (%.1f ms/frame)  GPU/CPU %.2fx"
              " (wall %.2fx)\n", t_frames, gpu_t_s, gpu_t_w, gpu_t_rate / 1e6, 1e3 * gpu_t_s / t_frames,
              gpu_t_rate / cpu_t_rate, cpu_t_w / gpu_t_w);
  std::printf("GPU triangle counts %s the CPU's on every slice\n", same ? "equal" : "DIFFER FROM");
  return same ? 0 : 1;
}
