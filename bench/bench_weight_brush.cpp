// Issue 34's speed lines: a weight-brush dab on the armadillo (about 43K vertices, 10 handles) in each
// mode, as weight_dab alone and as the document's paint_weights inside a stroke (undo bookkeeping
// included); and a weight transfer from the armadillo onto its midpoint subdivision moved off the
// surface by 0.1% of the diagonal (a finer remesh). The weights are inverse-distance blends of 10
// farthest-point samples: a dab's cost does not depend on where the weights came from.
// Usage: bench_weight_brush [MESH] [DABS]
#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "core/bind/closest_surface_point.h"
#include "core/bind/weight_transfer.h"
#include "core/mesh/io.h"
#include "core/mesh/mesh_info.h"
#include "core/scene/document.h"
#include "core/scene/weight_brush.h"

using namespace dfm;

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

Eigen::MatrixXd sample_weights(const Eigen::MatrixXd& V, int n) {
  std::vector<int> picks = {0};
  Eigen::VectorXd d = (V.rowwise() - V.row(0)).rowwise().norm();
  while (static_cast<int>(picks.size()) < n) {
    Eigen::Index far = 0;
    d.maxCoeff(&far);
    picks.push_back(static_cast<int>(far));
    d = d.cwiseMin((V.rowwise() - V.row(far)).rowwise().norm());
  }
  Eigen::MatrixXd W(V.rows(), n);
  for (int j = 0; j < n; ++j) W.col(j) = (V.rowwise() - V.row(picks[j])).rowwise().norm().array().pow(-4).min(1e12).matrix();
  for (Eigen::Index v = 0; v < V.rows(); ++v) W.row(v) /= W.row(v).sum();
  return W;
}

TriMesh midpoint_subdivision(const TriMesh& m) {
  std::map<std::pair<int, int>, int> mid;
  std::vector<Eigen::RowVector3d> extra;
  auto at = [&](int a, int b) {
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    auto [it, fresh] = mid.emplace(key, static_cast<int>(m.V.rows() + extra.size()));
    if (fresh) extra.push_back(0.5 * (m.V.row(a) + m.V.row(b)));
    return it->second;
  };
  TriMesh out;
  out.F.resize(4 * m.F.rows(), 3);
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const int a = m.F(f, 0), b = m.F(f, 1), c = m.F(f, 2), ab = at(a, b), bc = at(b, c), ca = at(c, a);
    out.F.row(4 * f) << a, ab, ca;
    out.F.row(4 * f + 1) << ab, b, bc;
    out.F.row(4 * f + 2) << ca, bc, c;
    out.F.row(4 * f + 3) << ab, bc, ca;
  }
  out.V.resize(m.V.rows() + static_cast<Eigen::Index>(extra.size()), 3);
  out.V.topRows(m.V.rows()) = m.V;
  for (size_t i = 0; i < extra.size(); ++i) out.V.row(m.V.rows() + static_cast<Eigen::Index>(i)) = extra[i];
  return out;
}

void report(const char* what, std::vector<double> ms) {
  std::sort(ms.begin(), ms.end());
  std::printf("  %-28s median %6.2f ms, 90th %6.2f, max %6.2f (%zu dabs)\n", what, ms[ms.size() / 2], ms[ms.size() * 9 / 10],
              ms.back(), ms.size());
}

}  // namespace

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : std::string(DFM_DATA_DIR) + "/armadillo.obj";
  const int dabs = argc > 2 ? std::stoi(argv[2]) : 60;
  const TriMesh mesh = read_surface(path);
  const Eigen::MatrixXd W = sample_weights(mesh.V, 10);
  const double diag = bounding_box(mesh.V).diagonal().norm();
  std::printf("%s: %d vertices, 10 handles; dab radius 5%% of the diagonal\n", path.c_str(), static_cast<int>(mesh.V.rows()));

  auto t = Clock::now();
  const WeightPaintSurface surface = weight_paint_surface(mesh.V, mesh.F);
  std::printf("  paint surface (normals, graph Laplacian), once per surface: %.1f ms\n", ms_since(t));

  Document doc;
  doc.set_surface(mesh, path);
  for (int j = 0; j < 10; ++j) doc.add_point(mesh.V.row(j * 97).transpose());
  doc.set_weights(W, {});
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(mesh.V.rows()) - 1);
  const char* names[] = {"add", "subtract", "mix", "smooth"};
  for (int mode = 0; mode < 4; ++mode) {
    WeightBrush b;
    b.mode = static_cast<WeightPaintMode>(mode), b.radius = 0.05 * diag, b.strength = 0.5, b.value = 0.3;
    std::vector<double> alone, in_doc;
    Eigen::MatrixXd X = W;
    doc.begin_gesture();
    for (int i = 0; i < dabs; ++i) {
      const Eigen::Vector3d c = mesh.V.row(pick(rng)).transpose();
      t = Clock::now();
      const WeightDab dab = weight_dab(X, surface, i % 10, c, b);
      apply_weight_dab(X, dab);
      alone.push_back(ms_since(t));
      t = Clock::now();
      doc.paint_weights(i % 10, c, b, {}, false);
      in_doc.push_back(ms_since(t));
    }
    doc.end_gesture();
    std::printf(" %s:\n", names[mode]);
    report("weight_dab + apply", alone);
    report("Document::paint_weights", in_doc);
  }

  TriMesh fine = midpoint_subdivision(mesh);
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(fine.V.rows(), 3);
  for (Eigen::Index f = 0; f < fine.F.rows(); ++f) {
    const Eigen::RowVector3d a = fine.V.row(fine.F(f, 0)), e1 = fine.V.row(fine.F(f, 1)) - a, e2 = fine.V.row(fine.F(f, 2)) - a;
    for (int k = 0; k < 3; ++k) N.row(fine.F(f, k)) += e1.cross(e2);
  }
  N.rowwise().normalize();
  fine.V += 1e-3 * diag * N;
  // The closest-point search the transfer makes, on one thread, both ways in this process: the grid
  // whose cells grow to the 5% search distance (SurfaceLocator) against the AABB tree (SurfaceTree).
  {
    const int n = std::min<int>(20000, static_cast<int>(fine.V.rows()));
    t = Clock::now();
    const SurfaceLocator grid(mesh.V, mesh.F, 0.05 * diag);
    double sum_grid = 0;
    for (int i = 0; i < n; ++i) sum_grid += grid.closest(fine.V.row(i).transpose()).distance;
    const double ms_grid = ms_since(t);
    t = Clock::now();
    const SurfaceTree tree(mesh.V, mesh.F, 0.05 * diag);
    double sum_tree = 0;
    for (int i = 0; i < n; ++i) sum_tree += tree.closest(fine.V.row(i).transpose()).distance;
    const double ms_tree = ms_since(t);
    std::printf("closest points for %d vertices, one thread: grid %.0f ms, tree %.0f ms (grid / tree %.1f); "
                "summed distances agree to %.1e\n",
                n, ms_grid, ms_tree, ms_grid / ms_tree, std::abs(sum_grid - sum_tree) / std::max(1e-300, sum_grid));
  }
  WeightTransferReport rep;
  t = Clock::now();
  const Eigen::MatrixXd T = transfer_weights(mesh.V, mesh.F, W, fine.V, fine.F, {}, &rep);
  std::printf("transfer onto the subdivision (%d vertices, moved off by 0.1%% of the diagonal): %.2f s, %d matched, %d "
              "inpainted; rows sum to 1 within %.1e\n",
              static_cast<int>(fine.V.rows()), ms_since(t) / 1000, rep.matched, rep.inpainted,
              (T.rowwise().sum().array() - 1).abs().maxCoeff());
  return 0;
}
