// The weight tools (core/bind/weight_*.h) on a mirror-symmetric strip made in weight_tools_test_meshes.h:
// BBW's properties survive every tool (Jacobson 2013, 4.3.1: bounds Eq. 4.6, partition of unity Eq. 4.5,
// the handle values of Eq. 4.3), checked against references written here (top-k cut, Dirichlet and edge
// energies from their definitions, the strip's own mirror map).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "core/bind/surface_laplacian.h"
#include "core/bind/weight_difference.h"
#include "core/bind/weight_tools.h"
#include "core/util/error.h"
#include "tests/weight_tools_test_meshes.h"

using namespace dfm;
using namespace dfm::test;

namespace {

// The properties every tool keeps.
void check_weights(const Eigen::MatrixXd& W, double tol = 1e-12) {
  CHECK(W.minCoeff() >= 0);
  CHECK(W.maxCoeff() <= 1 + tol);
  CHECK((W.rowwise().sum().array() - 1).abs().maxCoeff() <= tol);
}

int nonzeros(const Eigen::MatrixXd& W, int i) { return static_cast<int>((W.row(i).array() != 0).count()); }

// Plain cut: the k largest of each row (ties: lower handle), renormalized.
Eigen::MatrixXd plain_cut(const Eigen::MatrixXd& W, int k) {
  Eigen::MatrixXd C = W;
  for (int i = 0; i < W.rows(); ++i) {
    if (nonzeros(W, i) <= k) continue;
    std::vector<int> order(W.cols());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return W(i, a) > W(i, b); });
    for (size_t r = k; r < order.size(); ++r) C(i, order[r]) = 0;
    C.row(i) /= C.row(i).sum();
  }
  return C;
}

struct Strip {
  TriMesh mesh = mirror_strip();
  Rig rig = strip_rig();
  std::vector<bool> fixed = surface_weight_constraints(mesh.V, rig).mask(mesh.num_vertices());
};

}  // namespace

TEST_CASE("surface Laplacians: cotangent energy, edge energy and mass from their definitions") {
  const Strip s;
  const Eigen::MatrixXd X = Eigen::MatrixXd::Random(s.mesh.num_vertices(), 3);
  const Eigen::SparseMatrix<double> K = surface_cotangent_stiffness(s.mesh.V, s.mesh.F);
  CHECK((X.transpose() * K * X).trace() == Approx(dirichlet_energy(s.mesh, X)).epsilon(1e-12));
  const Eigen::SparseMatrix<double> U = uniform_stiffness(s.mesh.num_vertices(), s.mesh.F);
  CHECK((X.transpose() * U * X).trace() == Approx(edge_energy(s.mesh, X)).epsilon(1e-12));
  CHECK(surface_lumped_mass(s.mesh.V, s.mesh.F).sum() == Approx(2.0 * 0.6));
  // An obtuse triangle pair: the negative cotangent coupling is clamped, rows still sum to 0.
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0.5, 0.1, 0, 0.5, -0.1, 0;
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 1, 0, 3;
  const Eigen::MatrixXd Kd = surface_cotangent_stiffness(V, F);
  CHECK(Kd(0, 1) == 0);  // cot of the two obtuse angles opposite edge 01 is negative
  CHECK((Kd - Eigen::MatrixXd(Kd.transpose())).norm() == 0);
  CHECK(Kd.rowwise().sum().cwiseAbs().maxCoeff() < 1e-12);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (i != j) CHECK(Kd(i, j) <= 0);
}

TEST_CASE("constrained surface vertices: point handles, bones, regions and cage facets") {
  const Strip s;
  const WeightConstraints c = surface_weight_constraints(s.mesh.V, s.rig);
  REQUIRE(c.b.size() == 5);
  for (int h = 0; h < 5; ++h) {
    CHECK(c.b(h) == strip_handle_vertex(h));
    CHECK(c.bc.row(h) == Eigen::RowVectorXd::Unit(5, h));
  }
  Rig r;
  r.skeleton.joints.resize(3, 3);
  r.skeleton.joints << -0.5, 0.1, 0, -0.3, 0.1, 0, -0.3, 0.5, 0;  // along a grid row, then a column
  r.skeleton.bones = {{0, 1, -1, ""}, {1, 2, -1, ""}};
  r.regions.push_back({{strip_vertex(19, 5)}, "tip"});
  Cage cage;
  cage.mesh.V.resize(3, 3);
  cage.mesh.V << 0.6, 0, 0, 0.8, 0, 0, 0.6, 0.2, 0;  // a cage facet lying on the strip
  cage.mesh.F.resize(1, 3);
  cage.mesh.F << 0, 1, 2;
  r.cages.push_back(cage);
  const WeightConstraints d = surface_weight_constraints(s.mesh.V, r);
  std::vector<int> expected = {strip_vertex(5, 1), strip_vertex(6, 1), strip_vertex(7, 1),  // bone 0
                               strip_vertex(7, 2), strip_vertex(7, 3), strip_vertex(7, 4), strip_vertex(7, 5),
                               strip_vertex(19, 5),                                        // region
                               strip_vertex(16, 0), strip_vertex(17, 0), strip_vertex(18, 0),
                               strip_vertex(16, 1), strip_vertex(17, 1), strip_vertex(16, 2)};  // the facet
  std::sort(expected.begin(), expected.end());
  REQUIRE(d.b.size() == static_cast<int>(expected.size()));
  for (size_t k = 0; k < expected.size(); ++k) CHECK(d.b(k) == expected[k]);
  auto row_of = [&](int v) {
    for (int k = 0; k < d.b.size(); ++k)
      if (d.b(k) == v) return Eigen::RowVectorXd(d.bc.row(k));
    return Eigen::RowVectorXd();
  };
  // Handles: bones 0 1, cage vertices 2 3 4, region 5. The shared joint is split between its bones.
  CHECK(row_of(strip_vertex(7, 1)).isApprox((Eigen::RowVectorXd(6) << 0.5, 0.5, 0, 0, 0, 0).finished()));
  CHECK(row_of(strip_vertex(19, 5)) == Eigen::RowVectorXd::Unit(6, 5));
  // (0.7, 0.1) on the facet: barycentric (0, 0.5, 0.5) of its corners.
  CHECK(row_of(strip_vertex(17, 1)).isApprox((Eigen::RowVectorXd(6) << 0, 0, 0, 0.5, 0.5, 0).finished()));
}

// Vertices within `rings` edges of a seed (breadth first over the triangles' edges).
std::vector<bool> within_rings(const TriMesh& m, const std::vector<int>& seeds, int rings) {
  std::vector<std::vector<int>> nb(m.num_vertices());
  for (int f = 0; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) nb[m.F(f, k)].push_back(m.F(f, (k + 1) % 3)), nb[m.F(f, (k + 1) % 3)].push_back(m.F(f, k));
  std::vector<bool> in(m.num_vertices(), false);
  for (int s : seeds) in[s] = true;
  std::vector<int> front = seeds;
  for (int r = 0; r < rings; ++r) {
    std::vector<int> next;
    for (int v : front)
      for (int u : nb[v])
        if (!in[u]) in[u] = true, next.push_back(u);
    front = next;
  }
  return in;
}

TEST_CASE("limit influences: k per row, a partition of unity, smoother than cutting") {
  const Strip s;
  const Eigen::MatrixXd W = strip_weights(s.mesh, s.rig);
  int over = 0;
  for (int i = 0; i < W.rows(); ++i) over += nonzeros(W, i) > 2;
  REQUIRE(over > 50);
  for (int k : {2, 3}) {
    for (double radius : {1.0, 3.0}) {
      LimitReport rep;
      const Eigen::MatrixXd L = limit_influences(W, s.mesh.V, s.mesh.F, s.fixed, {k, radius}, &rep);
      const Eigen::MatrixXd C = plain_cut(W, k);
      check_weights(L);
      std::vector<int> cut_rows;
      for (int i = 0; i < W.rows(); ++i)
        if (nonzeros(W, i) > k) cut_rows.push_back(i);
      CHECK(rep.rows_limited == static_cast<int>(cut_rows.size()));
      const std::vector<bool> reach = within_rings(s.mesh, cut_rows, static_cast<int>(std::ceil(3 * radius)));
      for (int i = 0; i < W.rows(); ++i) {
        CHECK(nonzeros(L, i) <= k);
        for (int j = 0; j < W.cols(); ++j)
          if (C(i, j) == 0) CHECK(L(i, j) == 0);  // the kept set is the cut's
        if (!reach[i]) CHECK(L.row(i) == W.row(i));  // beyond the re-solve's reach: bit for bit
      }
      for (int h = 0; h < 5; ++h) CHECK(L.row(strip_handle_vertex(h)) == W.row(strip_handle_vertex(h)));
      const double e_cut = dirichlet_energy(s.mesh, C), e_limit = dirichlet_energy(s.mesh, L);
      const double c_cut = dirichlet_energy(s.mesh, C - W), c_limit = dirichlet_energy(s.mesh, L - W);
      std::printf("limit k=%d radius %.0f: Dirichlet energy %.3f (plain cut %.3f, before %.3f), of the change %.3f "
                  "(plain cut %.3f), %d rows limited\n", k, radius, e_limit, e_cut, dirichlet_energy(s.mesh, W),
                  c_limit, c_cut, rep.rows_limited);
      CHECK(e_limit < 0.97 * e_cut);
    }
    // radius 0 is the plain cut.
    CHECK((limit_influences(W, s.mesh.V, s.mesh.F, s.fixed, {k, 0.0}) - plain_cut(W, k)).cwiseAbs().maxCoeff() < 1e-15);
  }
  // One influence per vertex: every row is 0 or 1, whatever the re-solve did before renormalizing.
  CHECK((limit_influences(W, s.mesh.V, s.mesh.F, s.fixed, {1, 1.0}) - plain_cut(W, 1)).cwiseAbs().maxCoeff() == 0);
  CHECK_THROWS(limit_influences(W, s.mesh.V, s.mesh.F, s.fixed, {0, 1.0}));
  CHECK_THROWS(limit_influences(W, s.mesh.V, s.mesh.F, s.fixed, {2, -1.0}));
}

TEST_CASE("normalize with locked handles scales only the unlocked ones") {
  Eigen::MatrixXd W(5, 3);
  W << 0.2, 0.3, 0.1,   // L = 0.2 -> unlocked 0.4 scaled to 0.8
      0.7, 0.6, 0.0,    // L = 0.7 -> 0.3
      0.9, 0.0, 0.0,    // nothing unlocked to scale: left
      1.2, 0.5, 0.5,    // L > 1: unlocked set to 0 (Blender), sum stays 1.2
      0.5, 0.5, 0.5;    // fixed row
  NormalizeReport rep;
  const Eigen::MatrixXd N = normalize_locked(W, {0}, {false, false, false, false, true}, &rep);
  CHECK(N.col(0) == W.col(0));
  CHECK(N(0, 1) == Approx(0.6));
  CHECK(N(0, 2) == Approx(0.2));
  CHECK(N.row(0).sum() == Approx(1));
  CHECK(N(1, 1) == Approx(0.3));
  CHECK(N(1, 2) == 0);
  CHECK(N.row(2) == W.row(2));
  CHECK(N(3, 1) == 0);
  CHECK(N(3, 2) == 0);
  CHECK(N.row(4) == W.row(4));
  CHECK(rep.rows_scaled == 2);
  CHECK(rep.rows_locked_over_one == 1);
  CHECK(rep.rows_without_free_weight == 1);
  CHECK_THROWS(normalize_locked(W, {3}));

  const Strip s;
  Eigen::MatrixXd Ws = 1.7 * strip_weights(s.mesh, s.rig, 0.5);
  Ws.col(2) = strip_weights(s.mesh, s.rig).col(2);
  const Eigen::MatrixXd Ns = normalize_locked(Ws, {2, 4}, s.fixed);
  CHECK(Ns.col(2) == Ws.col(2));
  CHECK(Ns.col(4) == Ws.col(4));
  for (int i = 0; i < Ws.rows(); ++i)
    if (!s.fixed[i] && Ws(i, 2) + Ws(i, 4) < 1) CHECK(Ns.row(i).sum() == Approx(1).epsilon(1e-14));
}

TEST_CASE("smoothing lowers the Dirichlet energy and keeps locks, handles and unity") {
  const Strip s;
  const Eigen::MatrixXd W = plain_cut(strip_weights(s.mesh, s.rig, 0.5), 1);  // rough: one handle per vertex
  for (bool cot : {false, true}) {
    const Eigen::MatrixXd S = smooth_weights(W, s.mesh.V, s.mesh.F, {}, s.fixed, {5, 0.5, cot});
    check_weights(S, 1e-14);
    const double before = cot ? dirichlet_energy(s.mesh, W) : edge_energy(s.mesh, W);
    const double after = cot ? dirichlet_energy(s.mesh, S) : edge_energy(s.mesh, S);
    std::printf("smooth (%s, 5 x 0.5): energy %.4f -> %.4f\n", cot ? "cotangent" : "uniform", before, after);
    CHECK(after < 0.8 * before);
    for (int h = 0; h < 5; ++h) CHECK(S.row(strip_handle_vertex(h)) == W.row(strip_handle_vertex(h)));
  }
  // One step by hand at an interior vertex with 6 neighbours (uniform): (1 - f) w_i + f * mean.
  const int v = strip_vertex(4, 2);
  const Eigen::MatrixXd S1 = smooth_weights(W, s.mesh.V, s.mesh.F, {}, s.fixed, {1, 0.5, false});
  const int nb[6] = {strip_vertex(3, 2), strip_vertex(5, 2), strip_vertex(4, 1), strip_vertex(4, 3),
                     strip_vertex(3, 1), strip_vertex(5, 3)};  // left half: diagonals (i,j)-(i+1,j+1)
  Eigen::RowVectorXd mean = Eigen::RowVectorXd::Zero(5);
  for (int u : nb) mean += W.row(u) / 6.0;
  const Eigen::RowVectorXd expect = 0.5 * W.row(v) + 0.5 * mean;
  CHECK((S1.row(v) - expect / expect.sum()).cwiseAbs().maxCoeff() < 1e-14);
  // Locked columns stay bit for bit; the unlocked fill the rest of each row.
  const Eigen::MatrixXd SL = smooth_weights(W, s.mesh.V, s.mesh.F, {1, 3}, s.fixed, {3, 1.0, false});
  CHECK(SL.col(1) == W.col(1));
  CHECK(SL.col(3) == W.col(3));
  check_weights(SL, 1e-14);
  CHECK_THROWS(smooth_weights(W, s.mesh.V, s.mesh.F, {}, s.fixed, {1, 1.5, false}));
}

TEST_CASE("mirrored names follow the left/right conventions") {
  CHECK(mirrored_name("l_arm") == "r_arm");
  CHECK(mirrored_name("R_arm") == "L_arm");
  CHECK(mirrored_name("arm.L") == "arm.R");
  CHECK(mirrored_name("arm_r") == "arm_l");
  CHECK(mirrored_name("LeftEye") == "RightEye");
  CHECK(mirrored_name("upper right arm") == "upper left arm");
  CHECK(mirrored_name("armRight") == "armLeft");
  CHECK(mirrored_name("spine") == "");
  CHECK(mirrored_name("bright") == "");
  CHECK(mirrored_name("Rightful") == "");
  CHECK(mirrored_name("arml") == "");
  CHECK(mirrored_name("") == "");
}

TEST_CASE("mirror handles: names first, then mirrored positions; bones by both joints") {
  const Strip s;
  std::vector<int> unmatched;
  const std::vector<int> m = mirror_handles(s.rig, s.mesh.V, Eigen::Vector3d::UnitX(), 0, 1e-3, &unmatched);
  CHECK(m == std::vector<int>(kStripHandleMirror, kStripHandleMirror + 5));
  CHECK(unmatched.empty());
  Rig r;
  r.skeleton.joints.resize(5, 3);
  r.skeleton.joints << 0, 0, 0, 1, 1, 0, -1, 1, 0, 1, 2, 0, -1, 2.5, 0;
  r.skeleton.bones = {{0, 1, -1, ""}, {0, 2, -1, ""}, {1, 3, -1, "hand.L"}, {2, 4, -1, "hand.R"}};
  r.points.push_back({Eigen::Vector3d(0.5, 0, 0), ""});  // no mirror: itself, reported
  const std::vector<int> mb = mirror_handles(r, s.mesh.V, Eigen::Vector3d::UnitX(), 0, 1e-3, &unmatched);
  CHECK(mb == std::vector<int>{0, 2, 1, 4, 3});  // handle 0 is the point, then bones 0..3
  CHECK(unmatched == std::vector<int>{0});
}

TEST_CASE("mirror weights: symmetric weights reproduce; one side copied; twice changes nothing") {
  const Strip s;
  const Eigen::MatrixXd Ws = strip_weights(s.mesh, s.rig);
  MirrorReport rep;
  const Eigen::MatrixXd M0 = mirror_weights(Ws, s.mesh.V, s.mesh.F, s.rig, s.fixed, {}, &rep);
  CHECK((M0 - Ws).cwiseAbs().maxCoeff() < 1e-15);
  CHECK(rep.vertices_unmatched == 0);
  CHECK(rep.unmatched_handles.empty());

  const Eigen::MatrixXd W = strip_weights(s.mesh, s.rig, 0.5);
  const Eigen::MatrixXd M = mirror_weights(W, s.mesh.V, s.mesh.F, s.rig, s.fixed, {}, &rep);
  check_weights(M, 1e-14);
  for (int v = 0; v < W.rows(); ++v) {
    const double x = s.mesh.V(v, 0);
    const int mv = strip_mirror_vertex(v);
    if (x > 1e-9 || s.fixed[v]) CHECK(M.row(v) == W.row(v));  // the source side and handles: untouched
    for (int h = 0; h < 5; ++h) CHECK(M(v, h) == Approx(M(mv, kStripHandleMirror[h])).margin(1e-15));
    if (x < -1e-9 && !s.fixed[v])
      for (int h = 0; h < 5; ++h) CHECK(M(v, h) == W(mv, kStripHandleMirror[h]));  // a copy, bit for bit
  }
  CHECK(rep.vertices_changed > 50);
  const Eigen::MatrixXd MM = mirror_weights(M, s.mesh.V, s.mesh.F, s.rig, s.fixed, {});
  CHECK((MM - M).cwiseAbs().maxCoeff() < 1e-15);

  // The other direction copies the negative side.
  MirrorOptions neg;
  neg.mode = MirrorMode::NegativeToPositive;
  const Eigen::MatrixXd N = mirror_weights(W, s.mesh.V, s.mesh.F, s.rig, s.fixed, neg);
  for (int v = 0; v < W.rows(); ++v)
    if (s.mesh.V(v, 0) < -1e-9) CHECK(N.row(v) == W.row(v));

  // Flip swaps the sides; twice is the identity.
  MirrorOptions flip;
  flip.mode = MirrorMode::Flip;
  const Eigen::MatrixXd F1 = mirror_weights(W, s.mesh.V, s.mesh.F, s.rig, s.fixed, flip);
  check_weights(F1, 1e-14);
  for (int v = 0; v < W.rows(); ++v)
    for (int h = 0; h < 5; ++h) CHECK(F1(v, h) == W(strip_mirror_vertex(v), kStripHandleMirror[h]));
  CHECK(mirror_weights(F1, s.mesh.V, s.mesh.F, s.rig, s.fixed, flip) == W);
}

TEST_CASE("mirror on a nearly symmetric mesh interpolates, and the tolerance leaves the far ones") {
  Strip s;
  // Move the interior vertices a little, off the plane too (not symmetrically): reflections fall near
  // triangles, within the default tolerance (1% of the diagonal) but not within 1e-9 of it.
  for (int v = 0; v < s.mesh.num_vertices(); ++v) {
    const int i = v % (kStripNx + 1), j = v / (kStripNx + 1);
    if (i > 0 && i < kStripNx && j > 0 && j < kStripNy && !s.fixed[v])
      s.mesh.V.row(v) += Eigen::RowVector3d(0.02 * std::sin(7.0 * v), 0.02 * std::cos(5.0 * v), 0.005 * std::sin(3.0 * v));
  }
  const Eigen::MatrixXd W = strip_weights(s.mesh, s.rig, 0.5);
  MirrorReport rep;
  const Eigen::MatrixXd M = mirror_weights(W, s.mesh.V, s.mesh.F, s.rig, s.fixed, {}, &rep);
  check_weights(M, 1e-14);
  CHECK(rep.vertices_unmatched == 0);
  MirrorOptions tight;
  tight.tolerance = 1e-9;
  const Eigen::MatrixXd T = mirror_weights(W, s.mesh.V, s.mesh.F, s.rig, s.fixed, tight, &rep);
  CHECK(rep.vertices_unmatched > 0);
  check_weights(T, 1e-14);
}

TEST_CASE("zero-weight report lists the handles that move nothing") {
  const Strip s;
  Eigen::MatrixXd W = strip_weights(s.mesh, s.rig);
  W.col(0).setZero();
  W.col(3) *= 1e-4;  // (rows no longer sum to 1: the report does not care)
  const auto r = zero_weight_report(W, s.rig, 1e-3);
  REQUIRE(r.size() == 2);
  CHECK(r[0].handle == 0);
  CHECK(r[0].name == "r_outer");
  CHECK(r[0].max_weight == 0);
  CHECK(r[1].handle == 3);
  CHECK(r[1].name == "point 3");
  CHECK(r[1].max_weight == Approx(1e-4));
  CHECK(zero_weight_report(W, s.rig, 0).empty());
  CHECK_THROWS(zero_weight_report(Eigen::MatrixXd::Zero(3, 2), s.rig));
}

TEST_CASE("weight difference: one handle's change, or the share of weight that moved", "[weights]") {
  Eigen::MatrixXd W(3, 3), R(3, 3);
  W << 1, 0, 0,  0.5, 0.5, 0,  0.2, 0.3, 0.5;
  R << 0, 1, 0,  0.5, 0.5, 0,  0.5, 0.3, 0.2;
  // Vertex 0 moved all its weight, vertex 1 none, vertex 2 0.3 from handle 0 to handle 2.
  const Eigen::VectorXd all = weight_difference(W, R);
  CHECK(all[0] == Approx(1.0));
  CHECK(all[1] == 0.0);
  CHECK(all[2] == Approx(0.3));
  const Eigen::VectorXd h2 = weight_difference(W, R, 2);
  CHECK(h2[0] == 0.0);
  CHECK(h2[2] == Approx(0.3));
  CHECK(weight_difference(W, W).maxCoeff() == 0.0);
  CHECK_THROWS_AS(weight_difference(W, R.leftCols(2)), Error);
  CHECK_THROWS_AS(weight_difference(W, R, 3), Error);
}
