// Monotone weights (Jacobson 2013, ch. 5): the pairwise-constraint QP against brute force on small
// problems, and binds counted for spurious local extrema by a counter written here.
#include <random>
#include <utility>
#include <set>
#include <vector>

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "core/bind/bbw.h"
#include "core/bind/bind.h"
#include "core/bind/bind_volume.h"
#include "core/bind/monotone_joint.h"
#include "core/bind/monotone_qp.h"
#include "core/mesh/io.h"
#include "core/rig/rig_io.h"
#include "tests/test_support.h"

using namespace dfm;

namespace {

// The minimizer of 1/2 x^T H x + g^T x subject to x[upper] >= x[lower], by trying every subset of the
// constraints as equalities (dense KKT solve) and keeping the best feasible point.
Eigen::VectorXd brute_force_qp(const Eigen::MatrixXd& H, const Eigen::VectorXd& g, const MonotoneProblem& p) {
  const int n = static_cast<int>(H.rows()), nc = static_cast<int>(p.constraints.size());
  auto value = [&](const Eigen::VectorXd& x, int v) { return v < n ? x[v] : p.fixed_values[v - n]; };
  double best = 1e300;
  Eigen::VectorXd best_x;
  for (int mask = 0; mask < (1 << nc); ++mask) {
    std::vector<int> eq;
    for (int c = 0; c < nc; ++c)
      if (mask >> c & 1) eq.push_back(c);
    const int k = static_cast<int>(eq.size());
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + k, n + k);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + k);
    K.topLeftCorner(n, n) = H;
    rhs.head(n) = -g;
    for (int r = 0; r < k; ++r) {  // x[upper] - x[lower] = 0, fixed nodes moved to the right
      const MonotoneConstraint& c = p.constraints[eq[r]];
      if (c.upper < n) K(n + r, c.upper) += 1, K(c.upper, n + r) += 1;
      else rhs[n + r] -= p.fixed_values[c.upper - n];
      if (c.lower < n) K(n + r, c.lower) -= 1, K(c.lower, n + r) -= 1;
      else rhs[n + r] += p.fixed_values[c.lower - n];
    }
    Eigen::FullPivLU<Eigen::MatrixXd> lu(K);
    const Eigen::VectorXd sol = lu.solve(rhs);
    if ((K * sol - rhs).norm() > 1e-9) continue;  // inconsistent equalities
    const Eigen::VectorXd x = sol.head(n);
    bool feasible = true;
    for (const MonotoneConstraint& c : p.constraints) feasible = feasible && value(x, c.upper) >= value(x, c.lower) - 1e-12;
    const double f = 0.5 * x.dot(H * x) + g.dot(x);
    if (feasible && f < best) best = f, best_x = x;
  }
  return best_x;
}

// The joint minimizer over two handles of sum_j 1/2 x_j^T H x_j + g_j^T x_j subject to both problems'
// constraints and x_0 + x_1 = 1, by trying every subset of the constraints as equalities (dense KKT).
Eigen::MatrixXd brute_force_joint(const Eigen::MatrixXd& H, const Eigen::MatrixXd& G, const MonotoneProblem (&p)[2]) {
  const int n = static_cast<int>(H.rows()), n0 = static_cast<int>(p[0].constraints.size());
  const int nc = n0 + static_cast<int>(p[1].constraints.size());
  auto value = [&](const Eigen::VectorXd& x, int j, int v) { return v < n ? x[j * n + v] : p[j].fixed_values[v - n]; };
  double best = 1e300;
  Eigen::MatrixXd best_x;
  for (int mask = 0; mask < (1 << nc); ++mask) {
    std::vector<int> eq;
    for (int c = 0; c < nc; ++c)
      if (mask >> c & 1) eq.push_back(c);
    const int k = static_cast<int>(eq.size()), size = 2 * n + n + k;
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(size, size);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(size);
    for (int j = 0; j < 2; ++j) K.block(j * n, j * n, n, n) = H, rhs.segment(j * n, n) = -G.col(j);
    for (int i = 0; i < n; ++i) {  // x_0i + x_1i = 1
      K(2 * n + i, i) = K(i, 2 * n + i) = K(2 * n + i, n + i) = K(n + i, 2 * n + i) = 1;
      rhs[2 * n + i] = 1;
    }
    for (int r = 0; r < k; ++r) {
      const int j = eq[r] < n0 ? 0 : 1, row = 3 * n + r;
      const MonotoneConstraint& c = p[j].constraints[eq[r] - j * n0];
      if (c.upper < n) K(row, j * n + c.upper) += 1, K(j * n + c.upper, row) += 1;
      else rhs[row] -= p[j].fixed_values[c.upper - n];
      if (c.lower < n) K(row, j * n + c.lower) -= 1, K(j * n + c.lower, row) -= 1;
      else rhs[row] += p[j].fixed_values[c.lower - n];
    }
    Eigen::FullPivLU<Eigen::MatrixXd> lu(K);
    const Eigen::VectorXd sol = lu.solve(rhs);
    if ((K * sol - rhs).norm() > 1e-9) continue;
    const Eigen::VectorXd x = sol.head(2 * n);
    bool feasible = true;
    for (int j = 0; j < 2; ++j)
      for (const MonotoneConstraint& c : p[j].constraints)
        feasible = feasible && value(x, j, c.upper) >= value(x, j, c.lower) - 1e-12;
    double f = 0;
    for (int j = 0; j < 2; ++j) {
      const Eigen::VectorXd xj = x.segment(j * n, n);
      f += 0.5 * xj.dot(H * xj) + G.col(j).dot(xj);
    }
    if (feasible && f < best) {
      best = f;
      best_x.resize(n, 2);
      best_x.col(0) = x.head(n), best_x.col(1) = x.tail(n);
    }
  }
  return best_x;
}

// Symmetric tet-edge adjacency, built here (not with the library's helper).
std::vector<std::set<int>> tet_edges(const Eigen::MatrixXi& T, int n) {
  std::vector<std::set<int>> nb(n);
  const int e[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (int t = 0; t < T.rows(); ++t)
    for (const auto& ab : e) nb[T(t, ab[0])].insert(T(t, ab[1])), nb[T(t, ab[1])].insert(T(t, ab[0]));
  return nb;
}

// Vertices of spurious local maxima (sign +1) or minima (-1) of column j: not on a handle, and no path of
// equal values leads from them to a handle vertex or to a vertex with a strictly larger (smaller)
// neighbour. Fixpoint iteration over the edges; counts vertices, not plateaus.
int extremal_vertices(const std::vector<std::set<int>>& nb, const Eigen::MatrixXd& W, int j,
                      const std::vector<char>& on_handle, int sign) {
  const int n = static_cast<int>(nb.size());
  std::vector<char> escapes(n, 0);
  for (int v = 0; v < n; ++v) {
    escapes[v] = on_handle[v];
    for (int w : nb[v]) escapes[v] = escapes[v] || sign * (W(w, j) - W(v, j)) > 0;
  }
  for (bool changed = true; changed;) {
    changed = false;
    for (int v = 0; v < n; ++v)
      if (!escapes[v])
        for (int w : nb[v])
          if (W(w, j) == W(v, j) && escapes[w]) escapes[v] = 1, changed = true;
  }
  int count = 0;
  for (int v = 0; v < n; ++v) count += !escapes[v] && !nb[v].empty();
  return count;
}

int count_all(const std::vector<std::set<int>>& nb, const Eigen::MatrixXd& W, const std::vector<char>& on_handle,
              int sign) {
  int total = 0;
  for (int j = 0; j < W.cols(); ++j) total += extremal_vertices(nb, W, j, on_handle, sign);
  return total;
}

void require_partition_of_unity(const Eigen::MatrixXd& W) {
  REQUIRE(W.minCoeff() >= 0);
  REQUIRE(W.maxCoeff() <= 1);
  REQUIRE((W.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-12);
}

// A bind's weights on its tets: in [0, 1], rows summing to 1 (user's and tets'); (maxima, minima) vertex
// counts from the counter above.
std::pair<int, int> checked_bind_extrema(const BindResult& r, bool monotone, const char* what) {
  require_partition_of_unity(r.weights);
  require_partition_of_unity(r.tet_weights);
  REQUIRE(r.report.bbw.monotone == monotone);
  const int n = static_cast<int>(r.tet_weights.rows());
  std::vector<char> on_handle(n, 0);
  for (int k = 0; k < r.volume.b.size(); ++k) on_handle[r.volume.b(k)] = 1;
  const auto nb = tet_edges(r.volume.tets.T, n);
  const std::pair<int, int> e{count_all(nb, r.tet_weights, on_handle, +1), count_all(nb, r.tet_weights, on_handle, -1)};
  WARN((monotone ? "monotone " : "default ") << what << ": " << e.first << " vertices in spurious maxima, " << e.second
                                             << " in minima (tet graph)");
  return e;
}

// The same bind with default and with monotone weights (bind(o) with o.bbw.monotone off, then on):
// the default weights have spurious maxima on the tets, the monotone ones neither maxima nor minima.
template <class Bind>
void require_monotone_removes_extrema(const Bind& bind, const char* what) {
  std::pair<int, int> e[2];
  for (bool monotone : {false, true}) {
    BindOptions o;
    o.bbw.monotone = monotone;
    e[monotone] = checked_bind_extrema(bind(o), monotone, what);
  }
  CHECK(e[0].first > 0);
  CHECK(e[1].first == 0);
  CHECK(e[1].second == 0);
}

}  // namespace

TEST_CASE("monotone QP: the minimizer brute force finds over every active set", "[monotone]") {
  std::mt19937 rng(19);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 25; ++trial) {
    const int n = 5;
    Eigen::MatrixXd A(n, n);
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) A(r, c) = normal(rng);
    const Eigen::MatrixXd H = A.transpose() * A + 0.2 * Eigen::MatrixXd::Identity(n, n);
    Eigen::VectorXd g(n);
    for (int r = 0; r < n; ++r) g[r] = 2 * normal(rng);
    // An order as a representative function gives (5.14): node 6 (value 1) >= x0 >= ... >= x4 >= node 5
    // (value 0), plus two shortcuts; every chain ends on a fixed value, so the box holds too.
    MonotoneProblem p;
    p.fixed_values = {0.0, 1.0};
    p.constraints = {{6, 0}, {0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 5}, {0, 2}, {1, 4}};
    const Eigen::VectorXd expect = brute_force_qp(H, g, p);
    REQUIRE(expect.size() == n);
    // Start from the unconstrained minimizer (violates some constraints), or from nothing.
    const Eigen::VectorXd x0 = trial % 2 ? Eigen::VectorXd(H.ldlt().solve(-g)) : Eigen::VectorXd();
    const MonotoneQPResult r = solve_monotone_qp(H.sparseView(), g, p, x0, 1e-10);
    INFO("trial " << trial);
    CHECK(r.optimal);
    CHECK((r.x - expect).cwiseAbs().maxCoeff() < 1e-8);
    for (const MonotoneConstraint& c : p.constraints) {  // exactly, not within a tolerance
      const double up = c.upper < n ? r.x[c.upper] : p.fixed_values[c.upper - n];
      const double lo = c.lower < n ? r.x[c.lower] : p.fixed_values[c.lower - n];
      CHECK(up >= lo);
    }
  }
}

TEST_CASE("monotone joint QP (exact row sums, 5.3.4): the minimizer brute force finds", "[monotone]") {
  std::mt19937 rng(54);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 12; ++trial) {
    const int n = 4;
    Eigen::MatrixXd A(n, n), G(n, 2);
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) A(r, c) = normal(rng);
    const Eigen::MatrixXd H = A.transpose() * A + 0.2 * Eigen::MatrixXd::Identity(n, n);
    for (int r = 0; r < n; ++r) G(r, 0) = 2 * normal(rng), G(r, 1) = 2 * normal(rng);
    // Handle 0 decreases along 0..3, handle 1 increases (nodes 4, 5: values 0, 1), so x_0 + x_1 = 1 is feasible.
    MonotoneProblem p[2];
    p[0].fixed_values = p[1].fixed_values = {0.0, 1.0};
    p[0].constraints = {{5, 0}, {0, 1}, {1, 2}, {2, 3}, {3, 4}};
    p[1].constraints = {{5, 3}, {3, 2}, {2, 1}, {1, 0}, {0, 4}};
    const Eigen::MatrixXd expect = brute_force_joint(H, G, p);
    REQUIRE(expect.rows() == n);
    // Start from each handle's unconstrained minimizer: its orderings pick the first active sets. With
    // PDAS steps (10) it reaches the minimizer; adding only (the default), when it ends feasible, a point
    // no better.
    const Eigen::MatrixXd X0 = H.ldlt().solve(-G);
    auto objective = [&](const Eigen::MatrixXd& X) {
      return 0.5 * (X.col(0).dot(H * X.col(0)) + X.col(1).dot(H * X.col(1))) + G.col(0).dot(X.col(0)) +
             G.col(1).dot(X.col(1));
    };
    for (int steps : {10, 1}) {
      const MonotoneJointResult r = solve_monotone_joint(H.sparseView(), G, {p[0], p[1]}, X0, 1e-10, nullptr, steps);
      INFO("trial " << trial << ", " << steps << " PDAS steps");
      if (steps == 1 && !r.feasible) continue;  // adding only can fix a whole row wrongly; the bind retries
      CHECK(r.feasible);
      if (steps == 10) CHECK((r.X - expect).cwiseAbs().maxCoeff() < 1e-8);
      CHECK(objective(r.X) >= objective(expect) - 1e-9);
      CHECK((r.X.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-12);
      for (int j = 0; j < 2; ++j)
        for (const MonotoneConstraint& c : p[j].constraints) {  // exactly, not within a tolerance
          const double up = c.upper < n ? r.X(c.upper, j) : p[j].fixed_values[c.upper - n];
          const double lo = c.lower < n ? r.X(c.lower, j) : p[j].fixed_values[c.lower - n];
          CHECK(up >= lo);
        }
    }
  }
}

TEST_CASE("hand.mesh, wrist and index finger bones: spurious extrema in the other fingers, none when monotone",
          "[monotone][data]") {
  DFM_DATA_OR_SKIP(mesh_path, "hand.mesh");
  DFM_DATA_OR_SKIP(tgf_path, "hand.tgf");
  // Three bones of hand.tgf (joints 1, 2, 6, 7 in the file's numbering): the other fingers are
  // appendages with no handle, where Figure 5.1's oscillations live.
  const TgfData all = read_tgf(tgf_path);
  TgfData tgf;
  tgf.joints.resize(4, 3);
  const int joints[4] = {0, 1, 5, 6};
  for (int k = 0; k < 4; ++k) tgf.joints.row(k) = all.joints.row(joints[k]);
  tgf.edges.resize(3, 2);
  tgf.edges << 0, 1, 1, 2, 2, 3;
  tgf.flags = Eigen::MatrixXi::Zero(3, 3);
  tgf.flags.col(0).setOnes();
  Rig rig;
  add_tgf_to_rig(rig, tgf, "three bones of hand.tgf");
  REQUIRE(num_handles(rig) == 3);
  const TetMesh tets = read_tet_mesh(mesh_path);
  require_monotone_removes_extrema([&](const BindOptions& o) { return bind_tet_mesh(tets, rig, o); }, "bind, 3 bones");
}

// [heavy]: release only (~10 s CPU: 20 handles, solved three times); under the sanitizers the three-bone
// hand above runs the same monotone and joint solves.
TEST_CASE("hand.mesh + hand.tgf: the default weights have spurious maxima, the monotone ones none",
          "[heavy][monotone][data]") {
  DFM_DATA_OR_SKIP(mesh_path, "hand.mesh");
  DFM_DATA_OR_SKIP(tgf_path, "hand.tgf");
  Rig rig;
  add_tgf_to_rig(rig, read_tgf(tgf_path), tgf_path);
  const BindVolume vol = bind_volume_from_tets(read_tet_mesh(mesh_path), rig);
  const int n = vol.tets.num_vertices();
  const auto nb = tet_edges(vol.tets.T, n);
  std::vector<char> on_handle(n, 0);
  for (int k = 0; k < vol.b.size(); ++k) on_handle[vol.b(k)] = 1;

  const Eigen::MatrixXd W = bbw_weights(vol.tets.V, vol.tets.T, vol.b, vol.bc);
  require_partition_of_unity(W);
  const int default_maxima = count_all(nb, W, on_handle, +1), default_minima = count_all(nb, W, on_handle, -1);
  WARN("default bind: " << default_maxima << " vertices in spurious maxima, " << default_minima << " in minima");
  CHECK(default_maxima > 0);

  // 5.3.2's guarantee is for each handle's own minimizer: checked before the rows are normalized.
  BbwOptions o;
  o.monotone = true;
  o.normalize_rows = false;
  BbwStats stats;
  const Eigen::MatrixXd F = bbw_weights(vol.tets.V, vol.tets.T, vol.b, vol.bc, o, &stats);
  CHECK(stats.monotone);
  CHECK(F.minCoeff() >= 0);
  CHECK(F.maxCoeff() <= 1);
  CHECK(count_all(nb, F, on_handle, +1) == 0);
  CHECK(count_all(nb, F, on_handle, -1) == 0);
  for (int k = 0; k < vol.b.size(); ++k) CHECK(F.row(vol.b(k)) == vol.bc.row(k));

  // Divided by the row sums (5.3.4: sums that differ between neighbours turn flat stretches into extrema).
  Eigen::MatrixXd Wm = F;
  for (int i = 0; i < n; ++i) Wm.row(i) /= Wm.row(i).sum();
  WARN("monotone, rows divided by their sums: " << count_all(nb, Wm, on_handle, +1) << " vertices in spurious maxima, "
                                                << count_all(nb, Wm, on_handle, -1) << " in minima");

  // The bind's monotone weights: solved jointly with exact row sums, no division, no extrema.
  o.normalize_rows = true;
  const Eigen::MatrixXd Wj = bbw_weights(vol.tets.V, vol.tets.T, vol.b, vol.bc, o, &stats);
  CHECK(stats.monotone_joint);
  require_partition_of_unity(Wj);
  const int maxima = count_all(nb, Wj, on_handle, +1), minima = count_all(nb, Wj, on_handle, -1);
  WARN("monotone bind, exact row sums: " << maxima << " vertices in spurious maxima, " << minima << " in minima");
  CHECK(maxima == 0);
  CHECK(minima == 0);
}

// [heavy]: release only (~10 s: TetGen and two binds of 13K tet vertices).
TEST_CASE("arm.obj + arm.tgf: the monotone bind has no spurious extrema on its tets", "[heavy][monotone][data]") {
  DFM_DATA_OR_SKIP(obj, "arm.obj");
  DFM_DATA_OR_SKIP(tgf, "arm.tgf");
  const TriMesh arm = read_surface(obj);
  Rig rig;
  add_tgf_to_rig(rig, read_tgf(tgf), tgf);
  require_monotone_removes_extrema([&](const BindOptions& o) { return bind_surface(arm, rig, o); }, "arm bind");
}
