#include <catch2/catch.hpp>
#include <SuiteSparse_config.h>

#include <dlfcn.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <numeric>
#include <random>
#include <vector>

#include <Eigen/Dense>

#include "core/bind/bbw.h"
#include "core/bind/bbw_exact.h"
#include "core/bind/cholmod_memory.h"
#include "core/bind/numeric_setup.h"
#include "core/bind/fem.h"
#include "core/bind/qp.h"
#include "core/bind/sparse_kdk.h"
#include "core/util/error.h"
#include "tests/weights_test_meshes.h"

using namespace dfm;

// Reference box-QP minimizer by enumerating every (lower, free, upper) assignment: the unique one whose
// face minimizer is feasible with correct gradient signs.
static Eigen::VectorXd enumerate_box_qp(const Eigen::MatrixXd& H, const Eigen::VectorXd& g) {
  const int n = static_cast<int>(g.size());
  int total = 1;
  for (int i = 0; i < n; ++i) total *= 3;
  Eigen::VectorXd best;
  for (int code = 0; code < total; ++code) {
    std::vector<int> s(n);
    for (int i = 0, c = code; i < n; ++i, c /= 3) s[i] = c % 3;  // 0 lower, 1 free, 2 upper
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    std::vector<int> F;
    for (int i = 0; i < n; ++i) {
      if (s[i] == 2) x(i) = 1;
      if (s[i] == 1) F.push_back(i);
    }
    if (!F.empty()) {
      Eigen::MatrixXd HF(F.size(), F.size());
      Eigen::VectorXd r(F.size());
      const Eigen::VectorXd gr = H * x + g;
      for (size_t a = 0; a < F.size(); ++a) {
        r(a) = -gr(F[a]);
        for (size_t b = 0; b < F.size(); ++b) HF(a, b) = H(F[a], F[b]);
      }
      const Eigen::VectorXd xf = HF.llt().solve(r);
      for (size_t a = 0; a < F.size(); ++a) x(F[a]) = xf(a);
    }
    const Eigen::VectorXd gr = H * x + g;
    bool ok = true;
    for (int i = 0; i < n && ok; ++i) {
      if (s[i] == 1) ok = x(i) >= -1e-12 && x(i) <= 1 + 1e-12;
      if (s[i] == 0) ok = gr(i) >= -1e-10;
      if (s[i] == 2) ok = gr(i) <= 1e-10;
    }
    if (ok) return x;
  }
  return best;
}

TEST_CASE("box QP matches enumeration of active sets on random dense problems", "[qp]") {
  std::mt19937 rng(11);
  std::normal_distribution<double> N(0, 1);
  for (int trial = 0; trial < 30; ++trial) {
    const int n = 6;
    Eigen::MatrixXd A(n, n);
    for (int i = 0; i < A.size(); ++i) A.data()[i] = N(rng);
    const Eigen::MatrixXd H = A.transpose() * A + 0.05 * Eigen::MatrixXd::Identity(n, n);  // not an M-matrix
    Eigen::VectorXd g(n);
    for (int i = 0; i < n; ++i) g(i) = 3 * N(rng);
    const Eigen::VectorXd ref = enumerate_box_qp(H, g);
    REQUIRE(ref.size() == n);
    const Eigen::SparseMatrix<double> Hs = H.sparseView();
    BoxQPOptions o;
    o.tolerance = 1e-12;
    const BoxQPResult r = solve_box_qp(Hs, g, Eigen::VectorXd::Zero(n), Eigen::VectorXd::Ones(n), {}, o);
    REQUIRE(r.converged);
    REQUIRE(r.kkt_residual <= 1e-12);
    REQUIRE((r.x - ref).cwiseAbs().maxCoeff() < 1e-8);
  }
}

TEST_CASE("box QP KKT residual: zero at the minimizer, positive elsewhere", "[qp]") {
  Eigen::MatrixXd H(2, 2);
  H << 2, 0, 0, 2;
  const Eigen::SparseMatrix<double> Hs = H.sparseView();
  const Eigen::VectorXd g = Eigen::Vector2d(-1, 4);  // unconstrained minimizer (0.5, -2)
  const Eigen::VectorXd lo = Eigen::Vector2d::Zero(), hi = Eigen::Vector2d::Ones();
  REQUIRE(box_qp_kkt_residual(Hs, g, lo, hi, Eigen::Vector2d(0.5, 0)) == Approx(0).margin(1e-15));
  REQUIRE(box_qp_kkt_residual(Hs, g, lo, hi, Eigen::Vector2d(0.4, 0)) == Approx(0.1));   // not stationary
  REQUIRE(box_qp_kkt_residual(Hs, g, lo, hi, Eigen::Vector2d(0.5, 1)) == Approx(1.0));   // wrong sign at upper
  REQUIRE(box_qp_kkt_residual(Hs, g, lo, hi, Eigen::Vector2d(0.5, -0.5)) >= 0.5);        // infeasible
}

// A sparse box QP shaped like the weight problems (H = K^T K + small shift: a 2-ring stencil, not an
// M-matrix), large enough that faces have real fill, solved against an independent reference:
// accelerated projected gradient (FISTA) run to a fixed point on the dense matrix.
TEST_CASE("box QP on a sparse non-M-matrix problem matches accelerated projected gradient", "[qp]") {
  const int n = 120;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(0.5, 1.5);
  std::normal_distribution<double> N(0, 1);
  // K: a path-graph Laplacian with random weights plus random long-range edges (fill for the ordering).
  std::vector<Eigen::Triplet<double>> kt;
  auto edge = [&](int a, int b, double w) {
    kt.emplace_back(a, a, w), kt.emplace_back(b, b, w), kt.emplace_back(a, b, -w), kt.emplace_back(b, a, -w);
  };
  for (int i = 0; i + 1 < n; ++i) edge(i, i + 1, U(rng));
  for (int k = 0; k < 40; ++k) edge(static_cast<int>(rng() % n), static_cast<int>(rng() % n), 0.3 * U(rng));
  Eigen::SparseMatrix<double> K(n, n);
  K.setFromTriplets(kt.begin(), kt.end());
  Eigen::SparseMatrix<double> I(n, n);
  I.setIdentity();
  const Eigen::SparseMatrix<double> H = Eigen::SparseMatrix<double>(K.transpose() * K) + 0.02 * I;
  const Eigen::MatrixXd Hd(H);
  const double Lmax = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Hd).eigenvalues().maxCoeff();
  const Eigen::VectorXd lo = Eigen::VectorXd::Zero(n), hi = Eigen::VectorXd::Ones(n);
  const std::vector<int> ordering = fill_reducing_ordering(H);
  // The ordering is a permutation.
  std::vector<int> sorted = ordering;
  std::sort(sorted.begin(), sorted.end());
  for (int i = 0; i < n; ++i) REQUIRE(sorted[i] == i);
  int dropped = 0;
  for (int trial = 0; trial < 4; ++trial) {
    Eigen::VectorXd g(n);
    for (int i = 0; i < n; ++i) g(i) = 0.2 * N(rng);
    // Reference.
    Eigen::VectorXd x = Eigen::VectorXd::Constant(n, 0.5), y = x;
    double t = 1;
    for (int it = 0; it < 200000; ++it) {
      const Eigen::VectorXd xn = (y - (Hd * y + g) / Lmax).cwiseMax(lo).cwiseMin(hi);
      const double tn = (1 + std::sqrt(1 + 4 * t * t)) / 2;
      y = xn + ((t - 1) / tn) * (xn - x);
      if ((xn - x).cwiseAbs().maxCoeff() < 1e-15) {
        x = xn;
        break;
      }
      x = xn, t = tn;
    }
    REQUIRE(box_qp_kkt_residual(H, g, lo, hi, x) < 1e-8);
    BoxQPOptions o;
    o.tolerance = 1e-10;
    // Both with the ordering computed inside and with a shared one; from the bound-free start and from lo.
    const Eigen::VectorXd x_free = Eigen::VectorXd(Hd.llt().solve(-g));
    const BoxQPResult a = solve_box_qp(H, g, lo, hi, x_free, o);
    const OrderedLower ordered = ordered_lower(H, ordering);
    o.ordered = &ordered;
    const BoxQPResult b = solve_box_qp(H, g, lo, hi, {}, o);
    // Plain Gauss-Seidel sweeps (no over-relaxation) and strongly over-relaxed ones reach the same minimizer.
    o.smoothing_relaxation = 1.0;
    const BoxQPResult d = solve_box_qp(H, g, lo, hi, x_free, o);
    o.smoothing_relaxation = 1.9;
    const BoxQPResult e = solve_box_qp(H, g, lo, hi, x_free, o);
    // Sweeps that skip every move below the face's KKT residual (any relative threshold), with and
    // without sweeps before the first face.
    o.smoothing_relaxation = 1.6;
    o.smoothing_threshold_relative = 1.0;
    const BoxQPResult f = solve_box_qp(H, g, lo, hi, x_free, o);
    o.presmoothing_sweeps_per_variable = 0.5;
    const BoxQPResult h = solve_box_qp(H, g, lo, hi, x_free, o);
    o.smoothing_threshold_relative = 0;
    const BoxQPResult k = solve_box_qp(H, g, lo, hi, x_free, o);
    o.presmoothing_sweeps_per_variable = 0;
    // A few strongly over-relaxed sweeps make PDAS revisit active sets here: the solver drops the sweeps
    // (and still converges, checked below).
    o.smoothing_relaxation = 1.9;
    o.smoothing_sweeps = 3;
    const BoxQPResult cy = solve_box_qp(H, g, lo, hi, x_free, o);
    dropped += cy.sweeps_dropped;
    o.smoothing_relaxation = 1.6;
    o.smoothing_sweeps = 20;
    // Plain PDAS (no sweeps between faces) too.
    o.smoothing_sweeps = 0;
    const BoxQPResult c = solve_box_qp(H, g, lo, hi, x_free, o);
    for (const BoxQPResult* r : {&a, &b, &c, &d, &e, &f, &h, &k, &cy}) {
      REQUIRE(r->converged);
      REQUIRE(r->kkt_residual <= 1e-10);
      REQUIRE((r->x - x).cwiseAbs().maxCoeff() < 1e-6);
    }
    // H renumbered by the ordering and read directly (no OrderedLower): the same minimizer, renumbered.
    {
      const Eigen::VectorXi p = Eigen::Map<const Eigen::VectorXi>(ordering.data(), n);
      const Eigen::SparseMatrix<double> Hp = principal_submatrix(H, p);
      Eigen::VectorXd gp(n), xp(n);
      for (int k = 0; k < n; ++k) gp(k) = g(ordering[k]), xp(k) = x_free(ordering[k]);
      BoxQPOptions on;
      on.tolerance = 1e-10;
      on.in_elimination_order = true;
      const BoxQPResult r = solve_box_qp(Hp, gp, lo, hi, xp, on);
      REQUIRE(r.converged);
      for (int k = 0; k < n; ++k) REQUIRE(std::abs(r.x(k) - x(ordering[k])) < 1e-6);
    }
    // Some variables at each bound and some free: the test exercises all three.
    REQUIRE((x.array() == 0).count() > 0);
    REQUIRE(a.num_free > 0);
  }
  REQUIRE(dropped > 0);
  std::vector<int> wrong(n - 1);
  std::iota(wrong.begin(), wrong.end(), 0);
  REQUIRE_THROWS_AS(ordered_lower(H, wrong), Error);
  wrong.push_back(0);  // right size, a repeated variable
  REQUIRE_THROWS_AS(ordered_lower(H, wrong), Error);
  // The ordered lower triangle reproduces H.
  const OrderedLower L = ordered_lower(H, ordering);
  Eigen::MatrixXd back = Eigen::MatrixXd::Zero(n, n);
  for (int c = 0; c < n; ++c)
    for (int p = L.colptr[c]; p < L.colptr[c + 1]; ++p) {
      REQUIRE(L.rows[p] >= c);
      if (p > L.colptr[c]) REQUIRE(L.rows[p - 1] < L.rows[p]);
      back(L.perm[L.rows[p]], L.perm[c]) = back(L.perm[c], L.perm[L.rows[p]]) = L.values[p];
    }
  REQUIRE((back - Hd).cwiseAbs().maxCoeff() == 0.0);
  BoxQPOptions bad;
  const OrderedLower small = ordered_lower(principal_submatrix(H, Eigen::VectorXi::LinSpaced(n - 1, 0, n - 2)),
                                           fill_reducing_ordering(principal_submatrix(H, Eigen::VectorXi::LinSpaced(n - 1, 0, n - 2))));
  bad.ordered = &small;
  REQUIRE_THROWS_AS(solve_box_qp(H, Eigen::VectorXd::Zero(n), lo, hi, {}, bad), Error);
  for (double omega : {0.0, 2.0, -1.0}) {  // outside (0, 2) the sweeps could raise the objective
    BoxQPOptions o;
    o.smoothing_relaxation = omega;
    REQUIRE_THROWS_AS(solve_box_qp(H, Eigen::VectorXd::Zero(n), lo, hi, {}, o), Error);
  }
}

TEST_CASE("principal_submatrix picks rows and columns in the given order", "[qp]") {
  std::mt19937 rng(8);
  std::normal_distribution<double> N(0, 1);
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(9, 9);
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j)
      if ((i + 2 * j) % 3 != 0) D(i, j) = N(rng);
  const Eigen::SparseMatrix<double> A = D.sparseView();
  for (const std::vector<int>& pick : {std::vector<int>{1, 4, 5, 8}, std::vector<int>{7, 0, 3, 2, 6}}) {
    const Eigen::VectorXi idx = Eigen::Map<const Eigen::VectorXi>(pick.data(), pick.size());
    const Eigen::MatrixXd S(principal_submatrix(A, idx));
    for (int a = 0; a < idx.size(); ++a)
      for (int b = 0; b < idx.size(); ++b) REQUIRE(S(a, b) == D(idx(a), idx(b)));
  }
}

TEST_CASE("symmetric_kdk equals Eigen's K * D * K; bad sizes are errors", "[bbw]") {
  std::mt19937 rng(5);
  std::normal_distribution<double> N(0, 1);
  std::uniform_real_distribution<double> U(0.1, 2.0);
  for (int n : {1, 7, 40}) {
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j <= i; ++j)
        if (i == j || (i * 7 + j * 3) % 5 == 0) A(i, j) = A(j, i) = N(rng);
    const Eigen::SparseMatrix<double> K = A.sparseView();
    Eigen::VectorXd d(n);
    for (int i = 0; i < n; ++i) d(i) = U(rng);
    const Eigen::SparseMatrix<double> Q = symmetric_kdk(K, d);
    const Eigen::MatrixXd ref = A * d.asDiagonal() * A;
    REQUIRE((Eigen::MatrixXd(Q) - ref).cwiseAbs().maxCoeff() < 1e-12 * std::max(1.0, ref.cwiseAbs().maxCoeff()));
    for (int j = 0; j < Q.outerSize(); ++j)
      for (int p = Q.outerIndexPtr()[j] + 1; p < Q.outerIndexPtr()[j + 1]; ++p)
        REQUIRE(Q.innerIndexPtr()[p - 1] < Q.innerIndexPtr()[p]);
  }
  // The bilaplacian of a real tet mesh against Eigen's general product.
  const TetMesh m = test::cube_grid(4, 3, 3, 0.25);
  const Eigen::SparseMatrix<double> K = cotangent_stiffness(m.V, m.T);
  const Eigen::VectorXd minv = lumped_mass(m.V, m.T).cwiseInverse();
  const Eigen::SparseMatrix<double> ref = K * minv.asDiagonal() * K;
  const Eigen::SparseMatrix<double> Q = symmetric_kdk(K, minv);
  // Every stored entry of Eigen's product is stored here too (the grid's right angles make some exact
  // zeros, which this keeps as structural entries).
  REQUIRE(Q.nonZeros() >= ref.nonZeros());
  REQUIRE((Eigen::MatrixXd(Q) - Eigen::MatrixXd(ref)).cwiseAbs().maxCoeff() < 1e-12 * Eigen::MatrixXd(ref).cwiseAbs().maxCoeff());
  REQUIRE_THROWS_AS(symmetric_kdk(K, Eigen::VectorXd::Ones(3)), Error);
  REQUIRE_THROWS_AS(symmetric_kdk(Eigen::SparseMatrix<double>(3, 4), Eigen::VectorXd::Ones(3)), Error);
  // Columns split over threads (a grid large enough to be split): the very same matrix.
  const TetMesh big = test::cube_grid(14, 14, 14, 0.1);
  const Eigen::SparseMatrix<double> Kb = cotangent_stiffness(big.V, big.T);
  const Eigen::VectorXd mb = lumped_mass(big.V, big.T).cwiseInverse();
  const Eigen::SparseMatrix<double> one = symmetric_kdk(Kb, mb, 1), two = symmetric_kdk(Kb, mb, 2),
                                    three = symmetric_kdk(Kb, mb, 3);
  for (const Eigen::SparseMatrix<double>* q : {&two, &three}) {
    REQUIRE(q->nonZeros() == one.nonZeros());
    REQUIRE(std::equal(one.outerIndexPtr(), one.outerIndexPtr() + one.outerSize() + 1, q->outerIndexPtr()));
    REQUIRE(std::equal(one.innerIndexPtr(), one.innerIndexPtr() + one.nonZeros(), q->innerIndexPtr()));
    REQUIRE(std::equal(one.valuePtr(), one.valuePtr() + one.nonZeros(), q->valuePtr()));
  }
}

TEST_CASE("CHOLMOD block cache: a freed large block serves the next request it fits, zeroed for calloc", "[qp]") {
  install_cholmod_block_cache();
  release_cholmod_block_cache();
  auto* mal = SuiteSparse_config.malloc_func;
  auto* cal = SuiteSparse_config.calloc_func;
  auto* fre = SuiteSparse_config.free_func;
  char* a = static_cast<char*>(mal(6u << 20));
  REQUIRE(a != nullptr);
  std::memset(a, 0x5a, 6u << 20);
  fre(a);
  char* b = static_cast<char*>(mal(5u << 20));  // fits: the same block back
  REQUIRE(b == a);
  fre(b);
  char* c = static_cast<char*>(cal(1u << 20, 4));  // 4 MB, zeroed although the block was dirty
  REQUIRE(c == a);
  REQUIRE(std::all_of(c, c + (4u << 20), [](char v) { return v == 0; }));
  char* d = static_cast<char*>(mal(64u << 20));  // does not fit: a fresh block
  REQUIRE(d != c);
  std::memset(d, 1, 64u << 20);
  fre(d);
  fre(c);
  char* e = static_cast<char*>(mal(1u << 20));  // a quarter of the smallest cached block is too wasteful
  REQUIRE(e != c);
  REQUIRE(e != d);
  fre(e);
  void* small = mal(100);  // small blocks are plain malloc
  fre(small);
  release_cholmod_block_cache();
  // Factorizations through the cache still solve, repeatedly (the blocks are reused between them).
  const TetMesh m = test::cube_grid(10, 10, 10, 0.1);
  Eigen::SparseMatrix<double> A = cotangent_stiffness(m.V, m.T);
  for (int i = 0; i < A.rows(); ++i) A.coeffRef(i, i) += 1.0;
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(A.rows(), -1, 1);
  for (int round = 0; round < 3; ++round) {
    SpdSolver chol;
    chol.factorize(A);
    REQUIRE((chol.solve(A * x) - x).norm() < 1e-9 * x.norm());
  }
  release_cholmod_block_cache();
}

TEST_CASE("numeric setup: one BLAS thread, CHOLMOD through the block cache after setup_numerics", "[qp]") {
  setup_numerics();
  REQUIRE(SuiteSparse_config.malloc_func != &std::malloc);
  // Only checkable where the linked BLAS reports its thread count (OpenBLAS does).
  using GetInt = int (*)();
  if (void* f = dlsym(RTLD_DEFAULT, "openblas_get_num_threads")) REQUIRE(reinterpret_cast<GetInt>(f)() == 1);
  if (void* f = dlsym(RTLD_DEFAULT, "omp_get_max_active_levels")) REQUIRE(reinterpret_cast<GetInt>(f)() == 0);
  // The program's GOMP_parallel (numeric_setup.cpp) is the one every library binds to, not libgomp's;
  // and a factorization through it still solves.
  REQUIRE(dlsym(RTLD_DEFAULT, "GOMP_parallel") == reinterpret_cast<void*>(&GOMP_parallel));
  const TetMesh m = test::cube_grid(6, 6, 6, 1.0 / 6);
  Eigen::SparseMatrix<double> A = cotangent_stiffness(m.V, m.T);
  for (int i = 0; i < A.rows(); ++i) A.coeffRef(i, i) += 1.0;
  SpdSolver chol;
  chol.factorize(A);
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(A.rows(), -1, 1);
  REQUIRE((A * chol.solve(A * x) - A * x).norm() < 1e-10 * (A * x).norm());
}

namespace {
// A 8 x 2 x 2 bar of cubes (4 x 1 x 1), with point handles at the centres of both ends and the middle.
struct Bar {
  TetMesh m = test::cube_grid(8, 2, 2, 0.5);
  Eigen::VectorXi b;
  Eigen::MatrixXd bc;
  int id(int i, int j, int k) const { return i + 9 * (j + 3 * k); }
  Bar() {
    b.resize(3);
    b << id(0, 1, 1), id(8, 1, 1), id(4, 1, 1);
    bc = Eigen::MatrixXd::Identity(3, 3);
  }
};

double energy(const Eigen::SparseMatrix<double>& Q, const Eigen::MatrixXd& W) {
  double e = 0;
  for (int j = 0; j < W.cols(); ++j) e += 0.5 * W.col(j).dot(Q * W.col(j));
  return e;
}
}  // namespace

TEST_CASE("bbw on a bar: bounded, partition of unity, interpolating, local and monotone", "[bbw]") {
  Bar bar;
  BbwStats st;
  const Eigen::MatrixXd W = bbw_weights(bar.m.V, bar.m.T, bar.b, bar.bc, {}, &st);
  REQUIRE(st.converged);
  REQUIRE(st.kkt_residual <= 1e-6);
  REQUIRE(W.minCoeff() >= 0);
  REQUIRE(W.maxCoeff() <= 1);
  REQUIRE((W.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-12);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j) REQUIRE(W(bar.b(k), j) == (k == j ? 1.0 : 0.0));
  // Along the centre line the left handle's weight decreases from 1 to 0 at the middle handle, and
  // is 0 beyond it (locality).
  for (int i = 0; i < 8; ++i) REQUIRE(W(bar.id(i + 1, 1, 1), 0) <= W(bar.id(i, 1, 1), 0) + 1e-12);
  REQUIRE(W(bar.id(2, 1, 1), 0) > 0.2);
  for (int i = 5; i <= 8; ++i) REQUIRE(W(bar.id(i, 1, 1), 0) < 1e-3);
  // Symmetry of the problem: left and right handle mirror each other.
  for (int i = 0; i <= 8; ++i) REQUIRE(W(bar.id(i, 1, 1), 0) == Approx(W(bar.id(8 - i, 1, 1), 1)).margin(1e-5));
}

TEST_CASE("bbw per handle is the box-QP minimizer before normalization (independent KKT check)", "[bbw]") {
  Bar bar;
  const Eigen::SparseMatrix<double> Q = bbw_energy_matrix(bar.m.V, bar.m.T);
  // Q = K M^-1 K assembled independently here.
  const Eigen::SparseMatrix<double> K = cotangent_stiffness(bar.m.V, bar.m.T);
  const Eigen::VectorXd Minv = lumped_mass(bar.m.V, bar.m.T).cwiseInverse();
  REQUIRE((Eigen::MatrixXd(Q) - Eigen::MatrixXd(K) * Minv.asDiagonal() * Eigen::MatrixXd(K)).cwiseAbs().maxCoeff() <
          1e-9 * Eigen::MatrixXd(Q).cwiseAbs().maxCoeff());
  // One handle alone (no normalization involved): the gradient on free vertices vanishes where
  // 0 < w < 1 and points outward at the bounds.
  BbwOptions o;
  o.qp.tolerance = 1e-10;
  o.normalize_rows = false;
  const Eigen::MatrixXd W = bbw_weights(bar.m.V, bar.m.T, bar.b, bar.bc, o).leftCols(1);
  const Eigen::VectorXd grad = Q * W.col(0);
  const double gscale = (Eigen::MatrixXd(Q).cwiseAbs() * W.col(0).cwiseAbs()).maxCoeff();
  std::vector<bool> fixed(bar.m.V.rows(), false);
  for (int k = 0; k < 3; ++k) fixed[bar.b(k)] = true;
  for (int v = 0; v < W.rows(); ++v) {
    if (fixed[v]) continue;
    const double w = W(v, 0);
    if (w > 0 && w < 1) REQUIRE(std::abs(grad(v)) < 1e-7 * gscale);
    if (w == 0) REQUIRE(grad(v) > -1e-7 * gscale);
    if (w == 1) REQUIRE(grad(v) < 1e-7 * gscale);
  }
}

TEST_CASE("exact partition of unity: rows sum to 1 inside the QP, energy no higher than normalized", "[bbw]") {
  Bar bar;
  const Eigen::SparseMatrix<double> Q = bbw_energy_matrix(bar.m.V, bar.m.T);
  BbwOptions o;
  o.exact_partition_of_unity = true;
  o.qp.tolerance = 1e-9;
  BbwStats st;
  const Eigen::MatrixXd We = bbw_weights(bar.m.V, bar.m.T, bar.b, bar.bc, o, &st);
  REQUIRE(st.converged);
  REQUIRE(st.kkt_residual <= 1e-9);
  REQUIRE(We.minCoeff() >= 0);
  REQUIRE(We.maxCoeff() <= 1);
  REQUIRE((We.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-9);
  const Eigen::MatrixXd Wd = bbw_weights(bar.m.V, bar.m.T, bar.b, bar.bc);
  // The normalized default weights are feasible for the joint problem, so the joint minimum is lower.
  REQUIRE(energy(Q, We) <= energy(Q, Wd) * (1 + 1e-9));
}

// Independent reference for the joint problem: accelerated projected gradient on the product of
// probability simplices (sum 1 and >= 0 imply <= 1), many iterations on a tiny problem.
static Eigen::RowVectorXd project_simplex(Eigen::RowVectorXd y) {
  Eigen::RowVectorXd s = y;
  std::sort(s.data(), s.data() + s.size(), std::greater<double>());
  double cum = 0, theta = 0;
  for (int k = 0; k < s.size(); ++k) {
    cum += s(k);
    const double t = (cum - 1) / (k + 1);
    if (s(k) - t > 0) theta = t;
  }
  return (y.array() - theta).max(0.0);
}

TEST_CASE("exact partition of unity solver matches projected gradient on a random small problem", "[qp]") {
  std::mt19937 rng(5);
  std::normal_distribution<double> N(0, 1);
  const int n = 6, m = 3;
  Eigen::MatrixXd A(n, n);
  for (int i = 0; i < A.size(); ++i) A.data()[i] = N(rng);
  const Eigen::MatrixXd H = A.transpose() * A + 0.1 * Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd G(n, m);
  for (int i = 0; i < G.size(); ++i) G.data()[i] = 2 * N(rng);
  const Eigen::SparseMatrix<double> Hs = H.sparseView();
  const ExactPouResult r = solve_exact_pou(Hs, G, Eigen::MatrixXd::Constant(n, m, 1.0 / m), 1e-12);
  REQUIRE(r.converged);
  Eigen::MatrixXd X = Eigen::MatrixXd::Constant(n, m, 1.0 / m), Y = X;
  const double step = 1.0 / Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(H).eigenvalues().maxCoeff();
  double t = 1;
  for (int it = 0; it < 20000; ++it) {
    Eigen::MatrixXd Xn = Y - step * (H * Y + G);
    for (int i = 0; i < n; ++i) Xn.row(i) = project_simplex(Xn.row(i));
    const double tn = (1 + std::sqrt(1 + 4 * t * t)) / 2;
    Y = Xn + ((t - 1) / tn) * (Xn - X);
    X = Xn, t = tn;
  }
  REQUIRE((r.X - X).cwiseAbs().maxCoeff() < 1e-6);
  REQUIRE(exact_pou_kkt_residual(Hs, G, X) < 1e-6);
}

TEST_CASE("shape mask keeps painted tets stiffer (Eq. 4.7)", "[bbw]") {
  Bar bar;
  // Paint the tets between x = 0.5 and 1.5.
  Eigen::VectorXd rho = Eigen::VectorXd::Zero(bar.m.T.rows());
  for (int t = 0; t < bar.m.T.rows(); ++t) {
    double cx = 0;
    for (int c = 0; c < 4; ++c) cx += bar.m.V(bar.m.T(t, c), 0) / 4;
    if (cx > 0.5 && cx < 1.5) rho(t) = 1e3;
  }
  BbwOptions o;
  o.shape_mask = rho;
  const Eigen::MatrixXd Wm = bbw_weights(bar.m.V, bar.m.T, bar.b, bar.bc, o);
  const Eigen::MatrixXd W0 = bbw_weights(bar.m.V, bar.m.T, bar.b, bar.bc);
  const Eigen::SparseMatrix<double> Kp = masked_stiffness(bar.m.V, bar.m.T, (rho.array() > 0).cast<double>());
  double e_mask = 0, e_free = 0;
  for (int j = 0; j < 3; ++j) e_mask += Wm.col(j).dot(Kp * Wm.col(j)), e_free += W0.col(j).dot(Kp * W0.col(j));
  REQUIRE(e_mask < 0.2 * e_free);
  REQUIRE((Wm.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-12);
}

TEST_CASE("bbw: progress is reported, cancel stops it, bad input is an error", "[bbw]") {
  Bar bar;
  std::vector<double> fractions;
  BbwOptions o;
  o.progress = [&](const std::string&, double f) { fractions.push_back(f); };
  bbw_weights(bar.m.V, bar.m.T, bar.b, bar.bc, o);
  REQUIRE(fractions.size() >= 4);
  REQUIRE(fractions.back() == 1.0);
  for (size_t k = 1; k < fractions.size(); ++k) REQUIRE(fractions[k] >= fractions[k - 1]);
  std::atomic<bool> cancel{true};
  o.qp.cancel = &cancel;
  REQUIRE_THROWS_WITH(bbw_weights(bar.m.V, bar.m.T, bar.b, bar.bc, o), "cancelled");
  Eigen::VectorXi bad = bar.b;
  bad(1) = bad(0);
  REQUIRE_THROWS_AS(bbw_weights(bar.m.V, bar.m.T, bad, bar.bc), Error);
  REQUIRE_THROWS_AS(bbw_weights(bar.m.V, bar.m.T, bar.b, bar.bc.topRows(2)), Error);
  Eigen::MatrixXd zero_col = bar.bc;
  zero_col.col(2).setZero();
  REQUIRE_THROWS_AS(bbw_weights(bar.m.V, bar.m.T, bar.b, zero_col), Error);
}
