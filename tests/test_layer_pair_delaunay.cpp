// layer_pair_delaunay (the Voronoi overlay of two layers) against CGAL's 4D Delaunay triangulation of
// the same points lifted to two times (delaunay_4d), simplex for simplex.
#include <algorithm>
#include <array>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include "core/anim/delaunay_4d.h"
#include "core/anim/layer_pair_delaunay.h"
#include "tests/key_mesh_test_meshes.h"

using namespace dfm;

namespace {

using Simplex = std::array<int, 5>;

std::vector<Simplex> canonical(const MatrixX5iRow& S) {
  std::vector<Simplex> out;
  for (Eigen::Index s = 0; s < S.rows(); ++s) {
    Simplex x;
    for (int c = 0; c < 5; ++c) x[c] = S(s, c);
    std::sort(x.begin(), x.end());
    out.push_back(x);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// CGAL's dD triangulation of A at time 0 and B at time `gap`, A's points first.
std::vector<Simplex> reference(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double gap) {
  Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor> P(A.rows() + B.rows(), 4);
  P.topLeftCorner(A.rows(), 3) = A;
  P.topRightCorner(A.rows(), 1).setZero();
  P.bottomLeftCorner(B.rows(), 3) = B;
  P.bottomRightCorner(B.rows(), 1).setConstant(gap);
  return canonical(delaunay_4d(P).simplices);
}

std::optional<std::vector<Simplex>> overlay(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  const Tetrahedralization da = delaunay_3d(A), db = delaunay_3d(B);
  const auto S = layer_pair_delaunay({A, da.tets, da.neighbours}, {B, db.tets, db.neighbours});
  if (!S) return std::nullopt;
  return canonical(*S);
}

Eigen::MatrixXd random_points(int n, std::mt19937& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  Eigen::MatrixXd X(n, 3);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) X(i, d) = u(rng);
  return X;
}

// A body-centred cubic lattice of cube edge a over [0, n a]^3: exact grid positions, as a
// transition's middle lattice.
Eigen::MatrixXd bcc(int n, double a, const Eigen::RowVector3d& offset) {
  std::vector<Eigen::RowVector3d> p;
  for (int x = 0; x <= 2 * n; ++x)
    for (int y = 0; y <= 2 * n; ++y)
      for (int z = 0; z <= 2 * n; ++z) {
        const int odd = (x & 1) + (y & 1) + (z & 1);
        if (odd == 0 || odd == 3) p.push_back(Eigen::RowVector3d(x, y, z) * (0.5 * a) + offset);
      }
  Eigen::MatrixXd X(static_cast<Eigen::Index>(p.size()), 3);
  for (size_t i = 0; i < p.size(); ++i) X.row(static_cast<Eigen::Index>(i)) = p[i];
  return X;
}

}  // namespace

TEST_CASE("layer_pair_delaunay: random layers give CGAL's 4D Delaunay triangulation, at any separation", "[transition]") {
  std::mt19937 rng(11);
  for (const auto& [na, nb] : {std::pair{60, 40}, std::pair{300, 120}, std::pair{150, 400}}) {
    const Eigen::MatrixXd A = random_points(na, rng, -1, 1), B = random_points(nb, rng, -0.8, 1.3);
    const auto S = overlay(A, B);
    REQUIRE(S);
    CHECK(*S == reference(A, B, 0.37));
    CHECK(*S == reference(A, B, 5.0));
  }
}

TEST_CASE("layer_pair_delaunay: an irregular key against a lattice's exact grid", "[transition]") {
  std::mt19937 rng(5);
  // Points on a sphere and jittered inside it, against a lattice around it (its Voronoi cells are
  // congruent, so many crossings pass near their edges).
  std::normal_distribution<double> g;
  Eigen::MatrixXd A(500, 3);
  for (int i = 0; i < 500; ++i) {
    Eigen::RowVector3d x(g(rng), g(rng), g(rng));
    A.row(i) = x.normalized() * (i < 300 ? 1.0 : 0.3 + 0.6 * std::uniform_real_distribution<double>()(rng));
  }
  const Eigen::MatrixXd B = bcc(5, 0.5, Eigen::RowVector3d::Constant(-1.3));
  const auto S = overlay(A, B);
  REQUIRE(S);
  CHECK(*S == reference(A, B, 0.1));
  // Both layers lattices, one finer and turned (lattices aligned with each other tie exactly by
  // symmetry, which the next test case covers).
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::MatrixXd C = bcc(6, 0.37, Eigen::RowVector3d::Constant(-1.13)) * R.transpose();
  const auto L = overlay(C, B);
  REQUIRE(L);
  CHECK(*L == reference(C, B, 0.2));
}

TEST_CASE("layer_pair_delaunay: a symmetric key against a lattice shifted as a transition's", "[transition]") {
  // The torus is symmetric under x <-> y and z -> -z, so many of its Voronoi edges run exactly
  // parallel to the lattice's bisectors, and some of its tetrahedra are nearly flat.
  const TriMesh torus = dfm::test::torus(Eigen::Vector3d::Zero(), 0.32, 0.12, 40, 20);
  const double a = 0.06;
  const Eigen::MatrixXd B = bcc(9, a, Eigen::RowVector3d(-0.5, -0.5, -0.3) - a * Eigen::RowVector3d(0.137, 0.291, 0.413));
  const auto S = overlay(torus.V, B);
  REQUIRE(S);
  CHECK(*S == reference(torus.V, B, 0.05));
  const auto T = overlay(B, torus.V);
  REQUIRE(T);
  CHECK(*T == reference(B, torus.V, 0.05));
}

TEST_CASE("layer_pair_delaunay: an exact tie is left to the symbolic perturbation", "[transition]") {
  // A's one tetrahedron has its circumcentre at (0.5, 0.5, 0.5), exactly halfway between two of B's
  // points: two triangulations are Delaunay.
  Eigen::MatrixXd A(4, 3), B(5, 3);
  A << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  B << 0.25, 0.5, 0.5, 0.75, 0.5, 0.5, 0.3, 2.9, 0.7, 0.8, 0.4, 3.1, 4.1, 3.7, 4.3;
  CHECK_FALSE(overlay(A, B));
  // Lattices aligned with each other tie by symmetry.
  CHECK_FALSE(overlay(bcc(6, 0.37, Eigen::RowVector3d::Constant(-1.13)), bcc(5, 0.5, Eigen::RowVector3d::Constant(-1.3))));
  // Moved off the tie, it is unique again.
  B(0, 0) = 0.2;
  const auto S = overlay(A, B);
  REQUIRE(S);
  CHECK(*S == reference(A, B, 1.0));
}

TEST_CASE("delaunay_3d: tetrahedra, neighbours, errors", "[transition]") {
  Eigen::MatrixXd X(5, 3);
  X << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1;
  const Tetrahedralization d = delaunay_3d(X);
  REQUIRE(d.tets.rows() >= 2);
  for (int t = 0; t < d.tets.rows(); ++t)
    for (int j = 0; j < 4; ++j) {
      const int u = d.neighbours(t, j);
      if (u < 0) continue;
      int shared = 0;  // neighbours share the three corners other than j
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) shared += a != j && d.tets(t, a) == d.tets(u, b);
      CHECK(shared == 3);
    }
  Eigen::MatrixXd flat(4, 3);
  flat << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0;
  CHECK_THROWS_WITH(delaunay_3d(flat), Catch::Contains("coplanar"));
  X.row(4) = X.row(1);
  CHECK_THROWS_WITH(delaunay_3d(X), Catch::Contains("coincide"));
}
