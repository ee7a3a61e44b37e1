// Space-time Laplacian editing (issue 35; core/anim/manifold_edit.h): initialise (region, Laplacian rows,
// reach field, CHOLMOD factorisation) and per-drag (back substitution; a drag without a turn or
// volume preservation: the reach times its translation) times, next to Southern 2008's
// Fig. 4.12 (a ~2,500-vertex block: initialise 0.11 s with equal weights, 0.27 s dual graph Laplacian;
// deform 0.01 s).
// Models: (1) a block tube of 500 surface vertices standing over 5 layers (2,500 manifold vertices), its
// top cap the handle turned by 90 degrees, the bottom rings the anchors (the 4.7 stress test); (2) the
// arm keyed at three poses with 8 linear in-betweens per gap (test_manifold_edit's scene), the wrist
// dragged at the middle key over half the animation.
// Weighting schemes (4.6.1): reciprocal edge lengths (default), equal, and primal boundary (Eq. 4.3's QP
// at the manifold's first and last layers).
// Times are process CPU seconds (the build machine is shared), wall beside; drags: median of 21.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/anim/manifold.h"
#include "core/anim/manifold_edit.h"
#include "core/anim/manifold_edit_region.h"
#include "core/anim/manifold_frame.h"
#include "core/mesh/io.h"

using namespace dfm;

namespace {

struct Timer {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  std::clock_t cpu = std::clock();
  double wall_s() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count(); }
  double cpu_s() const { return double(std::clock() - cpu) / CLOCKS_PER_SEC; }
};

void run(const char* name, const AnimationManifold& M, const EditRegionSpec& rs, const EditHandleSpec& hs,
         const ManifoldDrag& drag, bool volume, LaplacianWeights weights = LaplacianWeights::Reciprocal) {
  Timer init;
  EditRegion sel = select_edit_region(M, rs, hs);
  const size_t nr = sel.region.size(), na = sel.anchors.size(), nh = sel.handle.size();
  ManifoldEditOptions opt;
  opt.preserve_volume = volume;
  opt.weights = weights;
  const ManifoldEditor ed(M, std::move(sel), hs.point, opt);
  const double init_cpu = init.cpu_s(), init_wall = init.wall_s();
  std::vector<double> cpu, wall;
  for (int i = 0; i < 21; ++i) {
    ManifoldDrag d = drag;
    d.translation *= (i + 1) / 21.0;
    Timer t;
    const MatrixX4dRow V = ed.drag(d);
    cpu.push_back(t.cpu_s());
    wall.push_back(t.wall_s());
  }
  // What a redraw after the drag costs on top: the frame at the handle's time (manifold_frame).
  Timer frame;
  const ManifoldSlice f = manifold_frame(M, hs.time);
  const double frame_cpu = frame.cpu_s();
  std::nth_element(cpu.begin(), cpu.begin() + 10, cpu.end());
  std::nth_element(wall.begin(), wall.begin() + 10, wall.end());
  std::printf("%-34s manifold %7d vertices | region %6zu, anchors %5zu, handle %4zu | initialise %.3f s (wall %.3f) | "
              "drag %.4f s (wall %.4f) | frame at T %.4f s (%d vertices)\n",
              name, M.num_vertices(), nr, na, nh, init_cpu, init_wall, cpu[10], wall[10], frame_cpu, f.mesh.num_vertices());
}

// A square tube (block without caps) of side 1 and height 2.5: `around` x `along` vertices.
TriMesh block_tube(int around, int along) {
  TriMesh m;
  m.V.resize(around * along, 3);
  for (int j = 0; j < along; ++j)
    for (int i = 0; i < around; ++i) {
      const double u = 4.0 * i / around;  // perimeter parameter over the square's 4 sides
      const int side = static_cast<int>(u);
      const double f = u - side;
      const double x[] = {f - 0.5, 0.5, 0.5 - f, -0.5}, y[] = {-0.5, f - 0.5, 0.5, 0.5 - f};
      m.V.row(j * around + i) << x[side], y[side], 2.5 * j / (along - 1);
    }
  m.F.resize(2 * around * (along - 1), 3);
  for (int j = 0, f = 0; j + 1 < along; ++j)
    for (int i = 0; i < around; ++i) {
      const int a = j * around + i, b = j * around + (i + 1) % around, c = a + around, d = b + around;
      m.F.row(f++) << a, b, d;
      m.F.row(f++) << a, d, c;
    }
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string arm_path = argc > 1 ? argv[1] : std::string(DFM_DATA_DIR) + "/arm.obj";
  std::printf("Southern 2008 Fig. 4.12 (2,500-vertex block): initialise 0.11 s (equal weights) .. 0.27 s (dual graph "
              "Laplacian), deform 0.01 s\n");
  {
    const TriMesh tube = block_tube(20, 25);
    const AnimationManifold M = build_manifold(std::vector<Eigen::MatrixXd>(5, tube.V), tube.F, {0, 1, 2, 3, 4});
    EditRegionSpec rs;
    rs.center = Eigen::Vector3d(0, 0, 2.5);
    rs.radius = 2.3;  // all but the bottom rings
    rs.t0 = 0;
    rs.t1 = 4;
    EditHandleSpec hs;
    hs.point = Eigen::Vector3d(0, 0, 2.5);
    hs.time = 2;
    ManifoldDrag d;
    d.rotation = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    d.translation = Eigen::Vector3d(0.3, 0, 0);
    run("block tube, top turned 90 deg", M, rs, hs, d, false);
    run("  the same, equal weights", M, rs, hs, d, false, LaplacianWeights::Equal);
    run("  the same, primal boundary (4.4.1)", M, rs, hs, d, false, LaplacianWeights::PrimalBoundary);
    run("  the same, dual with ghosts (4.4.2)", M, rs, hs, d, false, LaplacianWeights::Dual);
  }
  const TriMesh arm = read_surface(arm_path);
  const Eigen::Vector3d elbow(0.081400687, 0.18519857, -0.042544638), wrist(0.5987815, -0.077609889, 0.065252126);
  auto bent = [&](double degrees) {
    Eigen::MatrixXd out = arm.V;
    for (int i = 0; i < arm.V.rows(); ++i) {
      double w = std::clamp((arm.V(i, 0) - elbow.x() + 0.1) / 0.2, 0.0, 1.0);
      w = w * w * (3 - 2 * w);
      out.row(i) = (Eigen::AngleAxisd(w * degrees * M_PI / 180, Eigen::Vector3d::UnitZ()) *
                        (arm.V.row(i).transpose() - elbow) + elbow).transpose();
    }
    return out;
  };
  const std::vector<Eigen::MatrixXd> keys = {bent(0), bent(50), bent(10)};
  std::vector<Eigen::MatrixXd> layers;
  std::vector<double> times;
  for (int k = 0; k < 2; ++k)
    for (int i = 0; i <= 8; ++i) {
      layers.push_back((1 - i / 9.0) * keys[k] + i / 9.0 * keys[k + 1]);
      times.push_back(k + i / 9.0);
    }
  layers.push_back(keys[2]);
  times.push_back(2);
  const AnimationManifold M = build_manifold(layers, arm.F, times);
  const Eigen::Vector3d wrist_mid = Eigen::AngleAxisd(50 * M_PI / 180, Eigen::Vector3d::UnitZ()) * (wrist - elbow) + elbow;
  for (double radius : {0.25, 0.35, 0.5}) {
    EditRegionSpec rs;
    rs.center = wrist_mid;
    rs.radius = radius;
    rs.t0 = 0.5;
    rs.t1 = 1.5;
    EditHandleSpec hs;
    hs.point = wrist_mid;
    hs.time = 1;
    ManifoldDrag d;
    d.translation = Eigen::Vector3d(0.05, 0.12, -0.04);
    const std::string name = "arm, wrist ball r = " + std::to_string(radius).substr(0, 4);
    run(name.c_str(), M, rs, hs, d, false);
    if (radius == 0.35) {
      run((name + " --volume").c_str(), M, rs, hs, d, true);
      EditRegionSpec first = rs;  // from the start: the first layer is the manifold's open boundary
      first.t0 = 0;
      run((name + ", t0 = 0, primal-boundary").c_str(), M, first, hs, d, false, LaplacianWeights::PrimalBoundary);
      run((name + ", t0 = 0, dual").c_str(), M, first, hs, d, false, LaplacianWeights::Dual);
    }
  }
  return 0;
}
