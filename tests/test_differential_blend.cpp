// Local transitions in Laplacian coordinates (core/sculpt/differential_blend.h; Alexa 2002, 4.3) against
// references written here: a dense least-squares solve of Eq. 4.18 built from 4.3.1's definition of L,
// the linear blend (one uniform state, 4.3.1's "morphing the whole shape ... will be the same in absolute
// and Laplacian coordinates"), the keys themselves, and edge lengths across a region's border.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <set>

#include <Eigen/Dense>

#include "core/sculpt/differential_blend.h"
#include "core/util/error.h"
#include "tests/sculpt_test_meshes.h"

using namespace dfm;
using namespace dfm::test;

namespace {

// Two keys of one disk: K0 gently curved, K1 = K0 with a bump in the middle, a ripple, and moved away.
struct Keys {
  TriMesh mesh;
  Eigen::MatrixXd K0, K1;
};

Keys make_keys(double h, int rings) {
  Keys k;
  k.mesh = ring_disk(h, rings);
  k.K0 = k.mesh.V;
  for (int i = 0; i < k.K0.rows(); ++i) k.K0(i, 2) = 0.1 * k.K0(i, 0) * k.K0(i, 0);
  k.K1 = k.K0;
  for (int i = 0; i < k.K1.rows(); ++i) {
    const double x = k.K0(i, 0), y = k.K0(i, 1), r2 = x * x + y * y;
    k.K1(i, 2) += 0.3 * std::exp(-r2 / 0.05) + 0.02 * std::sin(7 * x);
  }
  k.K1.rowwise() += Eigen::RowVector3d(2.0, -1.0, 0.5);
  return k;
}

std::set<std::pair<int, int>> edges(const Eigen::MatrixXi& F) {
  std::set<std::pair<int, int>> e;
  for (int f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) e.emplace(std::min(F(f, c), F(f, (c + 1) % 3)), std::max(F(f, c), F(f, (c + 1) % 3)));
  return e;
}

double length(const Eigen::MatrixXd& X, const std::pair<int, int>& e) { return (X.row(e.first) - X.row(e.second)).norm(); }

}  // namespace

TEST_CASE("differential blend: Eq. 4.18 solved in the least-squares sense, as a dense reference does", "[sculpt]") {
  const Keys k = make_keys(1.0 / 4, 4);
  const int n = static_cast<int>(k.K0.rows());
  // L = I - D A from the edge list (Eq. 4.16-4.17).
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  for (const auto& e : edges(k.mesh.F)) A(e.first, e.second) = A(e.second, e.first) = 1;
  Eigen::MatrixXd L = Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i < n; ++i) L.row(i) -= A.row(i) / A.row(i).sum();
  Eigen::VectorXd s(n);
  for (int i = 0; i < n; ++i) s(i) = 0.5 + 0.5 * std::sin(3.0 * i);  // arbitrary, in [0, 1]
  Eigen::MatrixXd W(n, 3), P(n, 3);
  for (int i = 0; i < n; ++i) {
    W.row(i) = (1 - s(i)) * (L * k.K0).row(i) + s(i) * (L * k.K1).row(i);
    P.row(i) = (1 - s(i)) * k.K0.row(i) + s(i) * k.K1.row(i);
  }
  // Minimum-norm least squares, then the translation that puts the centroid at P's.
  Eigen::MatrixXd ref = L.completeOrthogonalDecomposition().solve(W);
  ref.rowwise() += P.colwise().mean() - ref.colwise().mean();
  const Eigen::MatrixXd X = DifferentialBlend(k.K0, k.K1, k.mesh.F).at(s);
  std::printf("differential blend vs dense least squares (%d vertices): %.3g\n", n, (X - ref).cwiseAbs().maxCoeff());
  CHECK((X - ref).cwiseAbs().maxCoeff() < 1e-10);
  // The residual is a real least-squares one (W is not in L's range), so the test is not trivial.
  CHECK((L * X - W).norm() > 1e-3);
}

TEST_CASE("differential blend: one uniform state is the linear blend; states 0 and 1 are the keys exactly", "[sculpt]") {
  const Keys k = make_keys(1.0 / 16, 16);
  const Eigen::Index n = k.K0.rows();
  const DifferentialBlend blend(k.K0, k.K1, k.mesh.F);
  double worst = 0;
  for (double s : {0.25, 0.37, 0.5, 0.9, 1.3}) {
    const Eigen::MatrixXd X = blend.at(Eigen::VectorXd::Constant(n, s));
    worst = std::max(worst, (X - ((1 - s) * k.K0 + s * k.K1)).cwiseAbs().maxCoeff());
  }
  std::printf("differential blend, uniform states (%d vertices): largest distance from the linear blend %.3g\n",
              static_cast<int>(n), worst);
  CHECK(worst < 1e-9);
  CHECK((blend.at(Eigen::VectorXd::Zero(n)).array() == k.K0.array()).all());
  CHECK((blend.at(Eigen::VectorXd::Ones(n)).array() == k.K1.array()).all());
  // Through the time mapping with offsets: t = 0 and t = 1 are the keys whatever the offsets.
  Eigen::VectorXd offsets(n);
  for (Eigen::Index i = 0; i < n; ++i) offsets(i) = 0.8 * std::sin(double(i));
  CHECK((blend.at(transition_states(offsets, 0.0)).array() == k.K0.array()).all());
  CHECK((blend.at(transition_states(offsets, 1.0)).array() == k.K1.array()).all());
}

TEST_CASE("differential blend: a region at state 1 takes the second key's shape with no seam", "[sculpt]") {
  const double h = 1.0 / 16;
  const Keys k = make_keys(h, 16);
  const Eigen::Index n = k.K0.rows();
  Eigen::VectorXd s = Eigen::VectorXd::Zero(n);
  std::vector<char> in(n, 0);
  for (Eigen::Index i = 0; i < n; ++i)
    if (k.mesh.V.row(i).head<2>().norm() < 0.5 + 0.25 * h) s(i) = 1, in[i] = 1;
  const Eigen::MatrixXd X = DifferentialBlend(k.K0, k.K1, k.mesh.F).at(s);
  Eigen::MatrixXd P(n, 3);  // the absolute per-vertex blend, for comparison
  for (Eigen::Index i = 0; i < n; ++i) P.row(i) = in[i] ? k.K1.row(i) : k.K0.row(i);
  double border = 0, border_abs = 0, keys = 0, inner = 0, outer = 0;
  for (const auto& e : edges(k.mesh.F)) {
    keys = std::max(keys, std::abs(length(k.K1, e) - length(k.K0, e)));
    if (in[e.first] != in[e.second]) {
      border = std::max(border, std::abs(length(X, e) - length(k.K0, e)));
      border_abs = std::max(border_abs, std::abs(length(P, e) - length(k.K0, e)));
    }
    // Edge vectors well inside the region against K1's, well outside against K0's.
    const double r = 0.5 * (k.mesh.V.row(e.first) + k.mesh.V.row(e.second)).head<2>().norm();
    const Eigen::RowVector3d v = X.row(e.second) - X.row(e.first);
    if (r < 0.25) inner = std::max(inner, (v - (k.K1.row(e.second) - k.K1.row(e.first))).norm() / length(k.K1, e));
    if (r > 0.75) outer = std::max(outer, (v - (k.K0.row(e.second) - k.K0.row(e.first))).norm() / length(k.K0, e));
  }
  std::printf("region at state 1: largest edge-length change across the border %.4g (keys' largest %.4g; the "
              "absolute per-vertex blend %.4g); edge vectors off by %.3g inside (vs K1), %.3g outside (vs K0)\n",
              border, keys, border_abs, inner, outer);
  CHECK(border <= keys);
  CHECK(border_abs > 10 * keys);  // what interpolating absolute coordinates would do (Fig. 4.5 c)
  CHECK(inner < 0.1);
  CHECK(outer < 0.1);
}

TEST_CASE("transition states from offsets: early, late, keys at the ends", "[sculpt]") {
  Eigen::VectorXd o(3);
  o << 0.5, 0.0, -0.5;
  CHECK(transition_states(o, 0.0).isZero(0));
  CHECK((transition_states(o, 1.0).array() == 1).all());
  const Eigen::VectorXd a = transition_states(o, 0.25), b = transition_states(o, 0.75);
  CHECK(a(0) == Approx(0.5));   // early: over [0, 0.5]
  CHECK(a(1) == Approx(0.25));
  CHECK(a(2) == 0.0);           // late: over [0.5, 1]
  CHECK(b(0) == 1.0);
  CHECK(b(2) == Approx(0.5));
  CHECK(transition_states(o, 1.5)(0) == 1.5);  // extrapolates uniformly outside the interval
  Eigen::VectorXd bad(1);
  bad << 1.0;
  CHECK_THROWS_AS(transition_states(bad, 0.5), Error);
  const Keys k = make_keys(0.5, 2);
  CHECK_THROWS_AS(DifferentialBlend(k.K0, k.K1.topRows(3), k.mesh.F), Error);
  CHECK_THROWS_AS(DifferentialBlend(k.K0, k.K1, k.mesh.F).at(Eigen::VectorXd::Zero(2)), Error);
}
