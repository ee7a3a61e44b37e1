// Generalized winding numbers: direct O(#F) sum vs the hierarchical tree (far-field expansion), on a
// large surface (armadillo, 86K triangles, or a given file). Prints times, speed-up and the largest
// difference for several tree accuracies (beta).
//   bench_winding [mesh] [#query points]
#include <chrono>
#include <cstdio>
#include <algorithm>
#include <random>
#include <string>

#include "core/bind/winding_bvh.h"
#include "core/bind/winding_number.h"
#include "core/mesh/io.h"

using Clock = std::chrono::steady_clock;
static double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : std::string(DFM_DATA_DIR) + "/armadillo.obj";
  const int n = argc > 2 ? std::stoi(argv[2]) : 20000;
  dfm::TriMesh m = dfm::read_surface(path);
  std::printf("%s: %d vertices, %d triangles; %d query points (uniform in the padded box, 1/4 near the surface)\n",
              path.c_str(), m.num_vertices(), m.num_faces(), n);
  const Eigen::RowVector3d lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-0.1, 1.1);
  Eigen::MatrixXd P(n, 3);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) P(i, k) = lo(k) + u(rng) * (hi(k) - lo(k));
  for (int i = 0; i < n / 4; ++i) {
    const int f = static_cast<int>(rng() % m.F.rows());
    P.row(i) = (m.V.row(m.F(f, 0)) + m.V.row(m.F(f, 1)) + m.V.row(m.F(f, 2))) / 3.0 +
               1e-3 * (hi - lo).norm() * Eigen::RowVector3d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
  }
  const int threads = 1;  // single core: a fair algorithmic comparison
  // The direct sum is timed on the first nd points (it is O(#F) each) and scaled to all n.
  const int nd = std::min(n, 1000);
  auto t = Clock::now();
  const Eigen::VectorXd wd = dfm::winding_numbers_direct(m.V, m.F, P.topRows(nd), threads);
  const double t_direct = since(t) * n / nd;
  std::printf("direct:        %8.3f s for %d points (timed on %d: %.2f us/point)\n", t_direct, n, nd, 1e6 * t_direct / n);
  t = Clock::now();
  const dfm::WindingTree tree = dfm::build_winding_tree(m.V, m.F);
  const double t_build = since(t);
  std::printf("tree build:    %8.3f s  (%zu nodes)\n", t_build, tree.nodes.size());
  const dfm::WindingAccuracy def;
  for (dfm::WindingAccuracy acc : {dfm::WindingAccuracy{2.0, 1e300}, dfm::WindingAccuracy{4.0, 1e300}, def}) {
    t = Clock::now();
    const Eigen::VectorXd wt = dfm::winding_numbers(tree, P, acc, threads);
    const double tt = since(t);
    int disagree = 0;
    for (int i = 0; i < nd; ++i) disagree += (wd(i) > 0.5) != (wt(i) > 0.5);
    std::printf("tree beta=%.1f node_tol=%-7.0e%s: %7.3f s  speed-up %7.1fx (%6.1fx incl. build)  max |diff| %.2e  in/out flips %d\n",
                acc.beta, acc.node_tolerance, acc.node_tolerance == def.node_tolerance && acc.beta == def.beta ? " (default)" : "          ", tt, t_direct / tt, t_direct / (tt + t_build), (wd - wt.head(nd)).cwiseAbs().maxCoeff(), disagree);
  }
  return 0;
}
