// Issue 37's speed lines: a handle move on the armadillo's surface (about 43K vertices) with a free region
// of about 10K vertices (the nearest by distance to a vertex, after a handle of the nearest 1K; the rest
// fixed): the factorization of the region choice (target < 2 s) and a handle move, one sparse product and
// one back substitution (target < 30 ms), for order 2 (biharmonic) and 3 (triharmonic); and the
// differential blend (Alexa 4.3) of the armadillo with a moved copy: factor once, one state vector.
// Usage: bench_sculpt [MESH] [FREE] [MOVES]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

#include "core/mesh/io.h"
#include "core/sculpt/differential_blend.h"
#include "core/sculpt/variational_deform.h"

using namespace dfm;

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

}  // namespace

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : std::string(DFM_DATA_DIR) + "/armadillo.obj";
  const int nfree = argc > 2 ? std::stoi(argv[2]) : 10000;
  const int moves = argc > 3 ? std::stoi(argv[3]) : 30;
  const TriMesh mesh = read_surface(path);
  const int nv = mesh.num_vertices();
  const double diag = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
  // Regions by distance from the vertex nearest the bounding box's top (the head).
  Eigen::Index top = 0;
  mesh.V.col(1).maxCoeff(&top);
  std::vector<int> order(nv);
  std::iota(order.begin(), order.end(), 0);
  const Eigen::VectorXd dist = (mesh.V.rowwise() - mesh.V.row(top)).rowwise().norm();
  std::sort(order.begin(), order.end(), [&](int a, int b) { return dist(a) < dist(b); });
  const int nh = std::min(1000, nv / 10);
  const std::vector<int> handle(order.begin(), order.begin() + nh);
  const std::vector<int> fixed(order.begin() + nh + std::min(nfree, nv - nh - 1), order.end());
  std::printf("%s: %d vertices, %d faces; handle %d, free %d, fixed %zu\n", path.c_str(), nv, mesh.num_faces(), nh,
              nv - nh - static_cast<int>(fixed.size()), fixed.size());
  for (int o : {2, 3}) {
    const auto t0 = Clock::now();
    VariationalDeform deform(mesh.V, mesh.F, fixed, handle, {o});
    const double factor_ms = ms_since(t0);
    std::vector<double> ms;
    Eigen::MatrixXd X;
    for (int k = 0; k < moves; ++k) {
      const double s = 0.002 * diag * (k + 1);
      const auto t1 = Clock::now();
      X = deform.solve(handle_translation(Eigen::RowVector3d(s, 0.5 * s, -0.3 * s)));
      ms.push_back(ms_since(t1));
    }
    std::sort(ms.begin(), ms.end());
    std::printf("  order %d: factor %.0f ms (target < 2000); handle move median %.2f ms, max %.2f (%d moves; target < 30)\n",
                o, factor_ms, ms[ms.size() / 2], ms.back(), moves);
  }
  // Differential blend of the armadillo and a copy with its head raised.
  Eigen::MatrixXd K1 = mesh.V;
  for (int i = 0; i < nh + nfree && i < nv; ++i) K1.row(order[i]) += Eigen::RowVector3d(0, 0.05 * diag, 0);
  const auto t2 = Clock::now();
  DifferentialBlend blend(mesh.V, K1, mesh.F);
  const double blend_factor_ms = ms_since(t2);
  Eigen::VectorXd states = Eigen::VectorXd::Zero(nv);
  for (int i = 0; i < nh; ++i) states(order[i]) = 1;
  const auto t3 = Clock::now();
  const Eigen::MatrixXd B = blend.at(states);
  std::printf("  differential blend: factor %.0f ms, one state vector %.2f ms\n", blend_factor_ms, ms_since(t3));
  return B.allFinite() ? 0 : 1;
}
