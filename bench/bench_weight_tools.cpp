// The weight tools on a bound scene (default: assets/default.scene.json): limit total influences
// (smooth re-solve against the plain cut, for several radii), smoothing, mirroring across x = 0, and
// the zero-weight report, with timings. A scene without weights is bound first. Usage: bench_weight_tools [SCENE.scene.json] [K]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include <Eigen/Dense>

#include "core/bind/weight_tools.h"
#include "core/scene/bind_document.h"
#include "core/scene/document.h"

using namespace dfm;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// sum_j integral |grad w_j|^2 over the triangles (from the definition, not the tools' Laplacian).
double dirichlet_energy(const TriMesh& m, const Eigen::MatrixXd& W) {
  double e = 0;
  for (int f = 0; f < m.num_faces(); ++f) {
    Eigen::Matrix<double, 3, 2> E;
    E.col(0) = (m.V.row(m.F(f, 1)) - m.V.row(m.F(f, 0))).transpose();
    E.col(1) = (m.V.row(m.F(f, 2)) - m.V.row(m.F(f, 0))).transpose();
    const Eigen::Matrix2d G = E.transpose() * E;
    if (!(G.determinant() > 1e-20)) continue;
    const double area = 0.5 * std::sqrt(G.determinant());
    const Eigen::Matrix<double, 3, 2> EG = E * G.inverse();
    for (int j = 0; j < W.cols(); ++j) {
      const Eigen::Vector2d dw(W(m.F(f, 1), j) - W(m.F(f, 0), j), W(m.F(f, 2), j) - W(m.F(f, 0), j));
      e += area * (EG * dw).squaredNorm();
    }
  }
  return e;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : "assets/default.scene.json";
  const int k = argc > 2 ? std::stoi(argv[2]) : 4;
  Document doc;
  doc.load_scene(path);
  if (!doc.has_weights()) {
    const auto tb = std::chrono::steady_clock::now();
    run_bind_blocking(doc);
    std::printf("bound in %.1f s (the scene had no weights)\n", seconds_since(tb));
  }
  const TriMesh& m = doc.surface();
  const Eigen::MatrixXd& W = doc.weights();
  auto t0 = std::chrono::steady_clock::now();
  const std::vector<bool> fixed = surface_weight_constraints(m.V, doc.rig()).mask(m.num_vertices());
  std::printf("%s: %d vertices, %d handles; constrained vertices found in %.3f s: %d\n", path.c_str(),
              m.num_vertices(), doc.num_handles(), seconds_since(t0), int(std::count(fixed.begin(), fixed.end(), true)));
  std::printf("Dirichlet energy of the bind's weights: %.4f\n", dirichlet_energy(m, W));
  for (double radius : {0.0, 0.5, 1.0, 1.5, 2.0, 3.0}) {
    LimitReport rep;
    t0 = std::chrono::steady_clock::now();
    const Eigen::MatrixXd L = limit_influences(W, m.V, m.F, fixed, {k, radius}, &rep);
    const double s = seconds_since(t0);
    std::printf("limit k=%d radius %.1f: %.3f s, %d rows limited, energy %.4f, energy of the change %.4f, "
                "max |change| %.4f, mean |change| %.5f\n", k, radius, s, rep.rows_limited, dirichlet_energy(m, L),
                dirichlet_energy(m, L - W), (L - W).cwiseAbs().maxCoeff(), (L - W).cwiseAbs().sum() / double(W.rows()));
  }
  for (bool cot : {false, true}) {
    t0 = std::chrono::steady_clock::now();
    const Eigen::MatrixXd S = smooth_weights(W, m.V, m.F, {}, fixed, {5, 0.5, cot});
    std::printf("smooth 5 x 0.5 %s: %.3f s, energy %.4f\n", cot ? "cotangent" : "uniform", seconds_since(t0),
                dirichlet_energy(m, S));
  }
  MirrorReport mr;
  t0 = std::chrono::steady_clock::now();
  const Eigen::MatrixXd M = mirror_weights(W, m.V, m.F, doc.rig(), fixed, {}, &mr);
  std::printf("mirror x = 0 (+ to -): %.3f s, %d vertices changed, %d unmatched, %zu unmatched handles, "
              "max |change| %.4f\n", seconds_since(t0), mr.vertices_changed, mr.vertices_unmatched,
              mr.unmatched_handles.size(), (M - W).cwiseAbs().maxCoeff());
  for (int h = 0; h < doc.num_handles(); ++h)
    if (mr.handle_mirror[h] != h) std::printf("  %s <-> %s\n", handle_name(doc.rig(), h).c_str(), handle_name(doc.rig(), mr.handle_mirror[h]).c_str());
  const auto z = zero_weight_report(W, doc.rig(), 1e-3);
  std::printf("zero-weight report (< 1e-3): %zu handles\n", z.size());
  for (const auto& h : z) std::printf("  %d %s max %.2e\n", h.handle, h.name.c_str(), h.max_weight);
  return 0;
}
