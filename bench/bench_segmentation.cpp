// Robust-volume segmentation (Jacobson 2013, 8.5.1): graph cut vs the 0.5 threshold on real meshes,
// in one process. Per mesh: the robust path's tetrahedralization (TetGen on the points in a padded
// box), winding numbers at centroids, then both segmentations timed. For a closed mesh it also makes a
// messy copy (random patches punched out, flipped, duplicated) and counts tets each method labels
// differently from the closed mesh's own winding number, for several (gamma, sigma, surface factor).
// The defaults are GraphCutOptions{} (core/bind/graph_cut_segmentation.h).
//   bench_segmentation [--constrained] [mesh ...]
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "core/bind/fem.h"
#include "core/bind/graph_cut_segmentation.h"
#include "core/bind/robust_volume.h"
#include "core/bind/tet_face_adjacency.h"
#include "core/bind/tetrahedralize.h"
#include "core/bind/winding_bvh.h"
#include "core/mesh/io.h"
#include "core/mesh/mesh_info.h"
#include "core/util/error.h"

using Clock = std::chrono::steady_clock;
static double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

namespace {

struct Volume {
  dfm::TetgenResult r;
  Eigen::MatrixXd C;
  dfm::TetFaceAdjacency adj;
  Eigen::VectorXd vol;
  std::vector<char> on;
  double adj_s = 0;
  bool constrained = false;  // TetGen accepted the surface's facets
};

// constrained: the surface's facets are TetGen constraints too (section 8.5's CDT), else points only.
Volume tetrahedralize_box(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, bool constrained) {
  const Eigen::RowVector3d lo = V.colwise().minCoeff(), hi = V.colwise().maxCoeff();
  const double pad = 0.05 * (hi - lo).norm();
  dfm::Plc plc;
  plc.V.resize(V.rows() + 8, 3);
  plc.V.topRows(V.rows()) = V;
  const int o = static_cast<int>(V.rows());
  for (int c = 0; c < 8; ++c)
    for (int k = 0; k < 3; ++k) plc.V(o + c, k) = ((c >> k) & 1) ? hi(k) + pad : lo(k) - pad;
  static const int box[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  plc.F.resize(12 + (constrained ? F.rows() : 0), 3);
  for (int f = 0; f < 12; ++f)
    for (int k = 0; k < 3; ++k) plc.F(f, k) = o + box[f][k];
  if (constrained) plc.F.bottomRows(F.rows()) = F;
  Volume v;
  if (constrained) {
    const auto t = Clock::now();
    try {
      v.r = dfm::tetrahedralize(plc, "pq1.414Y");
    } catch (const dfm::Error& e) {
      std::printf("  TetGen refused the facets after %.3f s (%.120s...): points only\n", since(t), e.what());
      plc.F.conservativeResize(12, 3);
      constrained = false;
    }
  }
  if (!constrained) v.r = dfm::tetrahedralize(plc, "pq1.414Y");
  v.constrained = constrained;
  v.C = dfm::tet_centroids(v.r.mesh);
  v.vol = dfm::tet_volumes(v.r.mesh.V, v.r.mesh.T).cwiseAbs();
  const auto t = Clock::now();
  v.adj = dfm::tet_face_adjacency(v.r.mesh);
  Eigen::MatrixXi G = F;
  for (int f = 0; f < G.rows(); ++f)
    for (int k = 0; k < 3; ++k) G(f, k) = v.r.input_to_tet(G(f, k));
  v.on = dfm::shared_faces_on_surface(v.adj, G);
  v.adj_s = since(t);
  return v;
}

Eigen::VectorXd winding(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& C) {
  return dfm::winding_numbers(dfm::build_winding_tree(V, F), C, dfm::WindingAccuracy{2.0, 1e300});
}

double kept_volume(const Eigen::VectorXd& vol, const std::vector<char>& in) {
  double s = 0;
  for (int t = 0; t < vol.size(); ++t) s += in[t] ? vol(t) : 0.0;
  return s;
}

// Patches of faces (centroids within `r` of a random face's centroid) punched out, flipped, duplicated.
Eigen::MatrixXi mess_up(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, double r, std::mt19937& rng) {
  Eigen::MatrixXd C(F.rows(), 3);
  for (int f = 0; f < F.rows(); ++f) C.row(f) = (V.row(F(f, 0)) + V.row(F(f, 1)) + V.row(F(f, 2))) / 3;
  std::vector<int> what(F.rows(), 0);  // 1 punch, 2 flip, 3 duplicate
  for (int p = 0; p < 12; ++p) {
    const int seed = static_cast<int>(rng() % F.rows());
    for (int f = 0; f < F.rows(); ++f)
      if ((C.row(f) - C.row(seed)).norm() < r) what[f] = 1 + p % 3;
  }
  std::vector<Eigen::RowVector3i> out;
  for (int f = 0; f < F.rows(); ++f) {
    Eigen::RowVector3i t = F.row(f);
    if (what[f] == 1) continue;
    if (what[f] == 2) std::swap(t(1), t(2));
    out.push_back(t);
    if (what[f] == 3) out.push_back(t);
  }
  Eigen::MatrixXi G(out.size(), 3);
  for (size_t i = 0; i < out.size(); ++i) G.row(i) = out[i];
  return G;
}

int disagree(const std::vector<char>& x, const Eigen::VectorXd& ref) {
  int n = 0;
  for (size_t t = 0; t < x.size(); ++t) n += static_cast<bool>(x[t]) != (ref(t) > 0.5);
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> paths;
  bool constrained = false;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--constrained") constrained = true;
    else paths.push_back(argv[i]);
  }
  if (paths.empty())
    for (const char* n : {"beetle.off", "camelhead.off", "decimated-knight.off", "cow.off"}) paths.push_back(std::string(DFM_DATA_DIR) + "/" + n);
  for (const std::string& path : paths) {
    const dfm::TriMesh raw = dfm::read_surface(path);
    const dfm::WeldedSurface ws = dfm::weld_surface(raw.V, raw.F);
    Volume v = tetrahedralize_box(ws.V, ws.F, constrained);
    int on_count = 0;
    for (char c : v.on) on_count += c;
    const Eigen::VectorXd& VW = v.vol;
    const int nt = static_cast<int>(v.r.mesh.T.rows());
    auto t = Clock::now();
    const Eigen::VectorXd w = winding(ws.V, ws.F, v.C);
    const double w_s = since(t);
    t = Clock::now();
    const std::vector<char> th = dfm::threshold_segmentation(w);
    const double th_s = since(t);
    t = Clock::now();
    const std::vector<char> cut = dfm::graph_cut_segmentation(w, VW, v.adj.tets, v.adj.area, v.on);
    const double cut_s = since(t);
    int kt = 0, kc = 0, diff = 0;
    for (int i = 0; i < nt; ++i) kt += th[i], kc += cut[i], diff += th[i] != cut[i];
    std::printf("%s: %d faces (%s)\n  %d tets (TetGen %.3f s%s), winding numbers %.3f s, adjacency+facets %.3f s; "
                "%d input facets are shared tet faces\n",
                path.c_str(), static_cast<int>(ws.F.rows()), ws.report.describe().c_str(), nt, v.r.seconds,
                v.constrained ? ", facets constrained" : "", w_s, v.adj_s, on_count);
    std::printf("  threshold: %.4f s, kept %d tets, volume %.6g\n  cut:       %.3f s, kept %d tets, volume %.6g; %d tets labelled differently\n",
                th_s, kt, kept_volume(v.vol, th), cut_s, kc, kept_volume(v.vol, cut), diff);
    // Where the two disagree: winding numbers of the tets the cut relabels, by bin.
    const double edges[] = {-1e300, 0.25, 0.45, 0.55, 0.75, 1e300};
    std::printf("  relabelled tets by winding number (count, volume):");
    for (int b = 0; b < 5; ++b) {
      int n = 0;
      double vol = 0;
      for (int i = 0; i < nt; ++i)
        if (th[i] != cut[i] && w(i) >= edges[b] && w(i) < edges[b + 1]) ++n, vol += v.vol(i);
      std::printf(" [%.2f,%.2f) %d %.3g;", std::max(edges[b], -9.0), std::min(edges[b + 1], 9.0), n, vol);
    }
    std::printf("\n");
    std::printf("  divergence-theorem volume of the surface (exact only when closed): %.6g\n", dfm::signed_volume(ws.V, ws.F));
    for (double g : {0.5, 1.0, 4.0}) {
      const std::vector<char> x = dfm::graph_cut_segmentation(w, VW, v.adj.tets, v.adj.area, v.on, dfm::GraphCutOptions{g, 0.4, 0});
      std::printf("  cut gamma %.1f: volume %.6g\n", g, kept_volume(v.vol, x));
    }
    if (!dfm::is_closed(ws.F)) continue;
    // Messy copy on the same points (same tets): score against the closed mesh's winding number.
    std::mt19937 rng(3);
    const double r = 2 * dfm::bounding_box(ws.V).diagonal().norm() / std::sqrt(static_cast<double>(ws.F.rows()));
    const Eigen::MatrixXi G = mess_up(ws.V, ws.F, r, rng);
    Eigen::MatrixXi Gt = G;
    for (int f = 0; f < Gt.rows(); ++f)
      for (int k = 0; k < 3; ++k) Gt(f, k) = v.r.input_to_tet(Gt(f, k));
    const std::vector<char> on = dfm::shared_faces_on_surface(v.adj, Gt);
    const Eigen::VectorXd wm = winding(ws.V, G, v.C);
    std::printf("  messy copy (%d of %d faces kept or doubled, %d boundary edges): threshold misclassifies %d tets\n",
                static_cast<int>(G.rows()), static_cast<int>(ws.F.rows()), dfm::boundary_edge_count(G),
                disagree(dfm::threshold_segmentation(wm), w));
    for (double g : {0.5, 1.0, 2.0, 4.0})
      for (double s : {0.3, 0.4})
        for (double f : {0.0, 0.1}) {
          dfm::GraphCutOptions o{g, s, f};
          std::printf("    cut gamma %4.1f sigma %.1f surface %.1f: %d\n", g, s, f,
                      disagree(dfm::graph_cut_segmentation(wm, VW, v.adj.tets, v.adj.area, on, o), w));
        }
  }
  return 0;
}
