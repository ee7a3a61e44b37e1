// Refitting a lattice's values so that its piecewise linear zero set passes through the field's own
// crossings (crossing_fit.h), against closed forms: polynomials along an edge, a sphere's distance on a
// grid.
#include <cmath>
#include <random>

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "core/anim/crossing_fit.h"

using namespace dfm;

namespace {

// The cubic Hermite interpolant's root by scanning, independent of hermite_root's bisection.
double scanned_root(double fa, double fb, double da, double db) {
  auto cubic = [&](double x) {
    return (1 + 2 * x) * (1 - x) * (1 - x) * fa + x * (1 - x) * (1 - x) * da + x * x * (3 - 2 * x) * fb - x * x * (1 - x) * db;
  };
  const int n = 200000;
  for (int i = 0; i < n; ++i)
    if (cubic((i + 1.0) / n) >= 0) return (i + 0.5) / n;
  return 1;
}

// The cube [0, m]^3 of grid spacing h, each cell in the six tetrahedra around its main diagonal
// (Kuhn's split: neighbouring cells meet face to face).
void kuhn_grid(int m, double h, const Eigen::Vector3d& origin, Eigen::MatrixXd& X, MatrixX4iRow& T) {
  const int n = m + 1;
  X.resize(n * n * n, 3);
  auto id = [&](int i, int j, int k) { return (i * n + j) * n + k; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) X.row(id(i, j, k)) = (origin + h * Eigen::Vector3d(i, j, k)).transpose();
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  T.resize(6 * m * m * m, 4);
  int t = 0;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k)
        for (const auto& p : perms) {
          int c[3] = {i, j, k};
          T(t, 0) = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            T(t, s + 1) = id(c[0], c[1], c[2]);
          }
          ++t;
        }
}

// Distances from the sphere |x| = R of the linear crossings of f on the edges.
std::vector<double> crossing_errors(const Eigen::MatrixXd& X, const std::vector<std::array<int, 2>>& E,
                                    const Eigen::VectorXd& f, double R) {
  std::vector<double> err;
  for (const auto& [a, b] : E)
    if ((f[a] < 0) != (f[b] < 0)) {
      const double l = f[a] / (f[a] - f[b]);
      err.push_back(std::abs(((1 - l) * X.row(a) + l * X.row(b)).norm() - R));
    }
  return err;
}

}  // namespace

TEST_CASE("hermite root: exact for cubics, linear data gives the linear root, limited slopes keep one root",
          "[transition]") {
  // f(x) = x - 0.3: values -0.3, 0.7, slope 1 at both ends.
  CHECK(hermite_root(-0.3, 0.7, 1, 1) == Approx(0.3).margin(1e-12));
  // f(x) = x^2 - 0.09: the Hermite cubic of a quadratic is the quadratic.
  CHECK(hermite_root(-0.09, 0.91, 0, 2) == Approx(0.3).margin(1e-12));
  // f(x) = x^3 - 1/8.
  CHECK(hermite_root(-0.125, 0.875, 0, 3) == Approx(0.5).margin(1e-12));
  // Slopes outside [0, 3 (fb - fa)] are limited first: the result is the limited cubic's only root.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-4, 4);
  for (int i = 0; i < 200; ++i) {
    const double fa = -std::abs(U(rng)) - 1e-3, fb = std::abs(U(rng)) + 1e-3, s = fb - fa;
    const double da = U(rng) * s, db = U(rng) * s;
    const double r = hermite_root(fa, fb, da, db);
    CHECK(r > 0);
    CHECK(r < 1);
    CHECK(r == Approx(scanned_root(fa, fb, std::clamp(da, 0.0, 3 * s), std::clamp(db, 0.0, 3 * s))).margin(1e-5));
  }
}

TEST_CASE("tet edges: each edge once, sorted", "[transition]") {
  MatrixX4iRow T(2, 4);
  T << 0, 1, 2, 3, 3, 2, 1, 4;
  const std::vector<std::array<int, 2>> E = tet_edges(T);
  const std::vector<std::array<int, 2>> want = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {1, 4}, {2, 3}, {2, 4}, {3, 4}};
  CHECK(E == want);
}

TEST_CASE("crossing fit: one edge's crossing lands on the field's root; a sphere's crossings move onto it",
          "[transition]") {
  // One edge, f(x) = x^2 - 0.09 from x = 0 to 1 plus a point on no crossing edge.
  Eigen::MatrixXd X(3, 3);
  X << 0, 0, 0, 1, 0, 0, 1, 1, 0;
  Eigen::VectorXd f(3);
  f << -0.09, 0.91, 1.5;
  Eigen::MatrixXd G(3, 3);
  G << 0, 0, 0, 2, 0, 0, 2, 2, 0;
  const Eigen::VectorXd v = fit_crossings(X, {{0, 1}, {1, 2}}, f, G);
  CHECK(v[0] / (v[0] - v[1]) == Approx(0.3).margin(1e-9));
  CHECK(v[0] < 0);
  CHECK(v[1] > 0);
  CHECK(v[2] == f[2]);

  // The signed distance to a sphere of radius 0.37 on a grid of spacing 0.1. The Hermite roots lie on
  // the sphere (the closed-form crossing of |x| = R along each edge); the refit values' linear
  // crossings move toward them as far as the points' shared values allow.
  Eigen::MatrixXd P;
  MatrixX4iRow T;
  kuhn_grid(12, 0.1, Eigen::Vector3d::Constant(-0.6), P, T);
  const double R = 0.37;
  Eigen::VectorXd d(P.rows());
  Eigen::MatrixXd grad(P.rows(), 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    d[i] = P.row(i).norm() - R;
    grad.row(i) = P.row(i).normalized();
  }
  const std::vector<std::array<int, 2>> E = tet_edges(T);
  double hermite_error = 0, linear_error = 0;
  for (const auto& [p, q] : E) {
    if ((d[p] < 0) == (d[q] < 0)) continue;
    const int a = d[p] < 0 ? p : q, b = d[p] < 0 ? q : p;
    const Eigen::Vector3d x = P.row(a).transpose(), e = (P.row(b) - P.row(a)).transpose();
    const double exact = (-x.dot(e) + std::sqrt(std::pow(x.dot(e), 2) - e.squaredNorm() * (x.squaredNorm() - R * R))) / e.squaredNorm();
    const double r = hermite_root(d[a], d[b], grad.row(a).dot(e), grad.row(b).dot(e));
    hermite_error = std::max(hermite_error, std::abs(r - exact) * e.norm());
    linear_error = std::max(linear_error, std::abs(d[a] / (d[a] - d[b]) - exact) * e.norm());
  }
  INFO("largest error along the edges: linear " << linear_error << ", Hermite " << hermite_error);
  CHECK(hermite_error < 0.2 * linear_error);
  const Eigen::VectorXd fit = fit_crossings(P, E, d, grad);
  for (Eigen::Index i = 0; i < P.rows(); ++i) CHECK((fit[i] < 0) == (d[i] < 0));
  std::vector<double> before = crossing_errors(P, E, d, R), after = crossing_errors(P, E, fit, R);
  REQUIRE(before.size() == after.size());
  std::sort(before.begin(), before.end());
  std::sort(after.begin(), after.end());
  INFO("largest crossing error " << before.back() << " -> " << after.back() << ", median " << before[before.size() / 2]
                                 << " -> " << after[after.size() / 2]);
  CHECK(after.back() < 0.8 * before.back());
  CHECK(after[after.size() / 2] < 0.7 * before[before.size() / 2]);

  CHECK_THROWS_WITH(fit_crossings(P, E, d.head(5), grad), Catch::Contains("one point, value and gradient"));
  CHECK_THROWS_WITH(fit_crossings(X, {{0, 7}}, f, G), Catch::Contains("out of range"));
}
