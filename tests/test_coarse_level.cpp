// Coarse level for the multilevel start of the bounded weight solves: interpolation rows, constraints
// carried over, carving to the domain (two separate spheres stay separate), and bbw with and without
// the multilevel start reaching the same minimizer.
#include <catch2/catch.hpp>

#include <Eigen/LU>

#include "core/bind/bbw.h"
#include "core/bind/coarse_level.h"
#include "core/bind/tetrahedralize.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;

namespace {

TetMesh mesh_of(const TriMesh& s, const std::string& switches) {
  Plc plc;
  plc.V = s.V;
  plc.F = s.F;
  return tetrahedralize(plc, switches).mesh;
}

// The vertex nearest to p.
int nearest(const Eigen::MatrixXd& V, const Eigen::Vector3d& p) {
  int best = 0;
  for (int i = 1; i < V.rows(); ++i)
    if ((V.row(i).transpose() - p).squaredNorm() < (V.row(best).transpose() - p).squaredNorm()) best = i;
  return best;
}

}  // namespace

TEST_CASE("coarse level: interpolation rows, constraints, orientation and volume on a box", "[bbw]") {
  const TetMesh m = mesh_of(test::box_mesh({0, 0, 0}, {2, 1, 1}), "pq1.414a0.0005");
  REQUIRE(m.V.rows() > 1500);
  Eigen::VectorXi b(3);
  b << nearest(m.V, {0.2, 0.5, 0.5}), nearest(m.V, {1.0, 0.5, 0.5}), nearest(m.V, {1.8, 0.5, 0.5});
  const Eigen::MatrixXd bc = Eigen::MatrixXd::Identity(3, 3);
  CoarseLevel cl;
  REQUIRE_FALSE(build_coarse_level(m.V, m.T, b, bc, cl, static_cast<int>(m.V.rows()) + 1));  // too small
  REQUIRE(build_coarse_level(m.V, m.T, b, bc, cl, 100));
  REQUIRE(cl.V.rows() < m.V.rows() / 3);
  REQUIRE(cl.V.rows() > m.V.rows() / 20);
  // Every constrained vertex is a coarse vertex at the same place with the same values.
  REQUIRE(cl.b.size() == 3);
  for (int k = 0; k < 3; ++k) {
    int fine = -1;
    for (int q = 0; q < 3; ++q)
      if ((m.V.row(b(q)) - cl.V.row(cl.b(k))).norm() == 0) fine = q;
    REQUIRE(fine >= 0);
    REQUIRE(cl.bc.row(k) == bc.row(fine));
  }
  // Positively oriented tets covering (nearly all of) the box; nothing outside it.
  double volume = 0;
  for (int t = 0; t < cl.T.rows(); ++t) {
    Eigen::Matrix3d J;
    for (int c = 0; c < 3; ++c) J.col(c) = (cl.V.row(cl.T(t, c + 1)) - cl.V.row(cl.T(t, 0))).transpose();
    REQUIRE(J.determinant() > 0);
    volume += J.determinant() / 6;
  }
  REQUIRE(volume <= 2.0 + 1e-9);
  REQUIRE(volume > 0.9 * 2.0);
  // Interpolation: rows are convex combinations; a coarse vertex's row picks itself.
  REQUIRE(cl.P.rows() == m.V.rows());
  REQUIRE(cl.P.cols() == cl.V.rows());
  const Eigen::SparseMatrix<double> Pt = cl.P.transpose();
  int empty = 0;
  for (int v = 0; v < Pt.cols(); ++v) {
    double sum = 0;
    int count = 0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(Pt, v); it; ++it) {
      REQUIRE(it.value() > 0);
      sum += it.value(), ++count;
    }
    if (count == 0) ++empty;
    else REQUIRE(sum == Approx(1.0).margin(1e-12));
  }
  REQUIRE(empty == 0);  // a convex box loses no coarse vertex to carving
  for (int c = 0; c < cl.V.rows(); ++c) {
    const int v = nearest(m.V, cl.V.row(c).transpose());
    REQUIRE((m.V.row(v) - cl.V.row(c)).norm() == 0);
    REQUIRE(cl.P.coeff(v, c) == 1.0);
    REQUIRE(Pt.col(v).nonZeros() == 1);
  }
  // Linear functions are reproduced up to the neighbour averaging's first-order error.
  const Eigen::VectorXd xc = cl.V.col(0), xf = cl.P * xc;
  REQUIRE((xf - m.V.col(0)).cwiseAbs().maxCoeff() < 0.2);
}

TEST_CASE("coarse level: carving keeps two separate spheres separate; a part without a handle is dropped",
          "[bbw]") {
  const TriMesh two = test::concat(test::icosphere({0, 0, 0}, 1.0, 3), test::icosphere({2.6, 0, 0}, 1.0, 3));
  const TetMesh m = mesh_of(two, "pq1.414a0.002");
  Eigen::VectorXi b(2);
  b << nearest(m.V, {0, 0, 0}), nearest(m.V, {2.6, 0, 0});
  const Eigen::MatrixXd bc = Eigen::MatrixXd::Identity(2, 2);
  CoarseLevel cl;
  REQUIRE(build_coarse_level(m.V, m.T, b, bc, cl, 100));
  for (int t = 0; t < cl.T.rows(); ++t) {
    int left = 0;
    for (int c = 0; c < 4; ++c) left += cl.V(cl.T(t, c), 0) < 1.3;
    REQUIRE((left == 0 || left == 4));  // no tet bridges the gap
  }
  // Only the left sphere has a handle: the right one is not part of the coarse level, and a handle with
  // no constrained coarse vertex makes the level unusable.
  Eigen::VectorXi b1(1);
  b1 << b(0);
  REQUIRE(build_coarse_level(m.V, m.T, b1, Eigen::MatrixXd::Ones(1, 1), cl, 100));
  REQUIRE(cl.V.col(0).maxCoeff() < 1.3);
  Eigen::MatrixXd lost(2, 2);
  lost << 1, 0, 1, 0;  // handle 1 is 0 at both constrained vertices
  REQUIRE_FALSE(build_coarse_level(m.V, m.T, b, lost, cl, 100));
}

TEST_CASE("bbw from the multilevel start reaches the same minimizer as from the bound-free start", "[bbw]") {
  const TetMesh m = mesh_of(test::box_mesh({0, 0, 0}, {3, 1, 1}), "pq1.414a0.0008");
  Eigen::VectorXi b(4);
  b << nearest(m.V, {0.1, 0.5, 0.5}), nearest(m.V, {1.0, 0.5, 0.5}), nearest(m.V, {2.0, 0.5, 0.5}),
      nearest(m.V, {2.9, 0.5, 0.5});
  const Eigen::MatrixXd bc = Eigen::MatrixXd::Identity(4, 4);
  BbwOptions plain, multilevel;
  plain.multilevel_min_vertices = 0;
  multilevel.multilevel_min_vertices = 100;
  plain.qp.tolerance = multilevel.qp.tolerance = 1e-9;
  BbwStats sp, sm;
  const Eigen::MatrixXd Wp = bbw_weights(m.V, m.T, b, bc, plain, &sp);
  const Eigen::MatrixXd Wm = bbw_weights(m.V, m.T, b, bc, multilevel, &sm);
  REQUIRE_FALSE(sp.multilevel);
  REQUIRE(sm.multilevel);
  REQUIRE(sm.converged);
  REQUIRE(sm.kkt_residual <= 1e-9);
  REQUIRE((Wp - Wm).cwiseAbs().maxCoeff() < 1e-5);
  REQUIRE(Wm.minCoeff() >= 0);
  REQUIRE((Wm.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-12);
  // The coarse level stopped as soon as the first solver has nothing to do (how many handles it handed
  // over by then depends on timing): the others start from the bound-free solution, same minimizer.
  BbwOptions impatient = multilevel;
  impatient.multilevel_patience_seconds = 0;
  impatient.threads = 1;
  BbwStats si;
  const Eigen::MatrixXd Wi = bbw_weights(m.V, m.T, b, bc, impatient, &si);
  REQUIRE(si.converged);
  REQUIRE((Wp - Wi).cwiseAbs().maxCoeff() < 1e-5);
  REQUIRE((Wi.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-12);
  // No coarse level at all (a region handle constrains over a quarter of the vertices): every handle
  // starts from the bound-free solution, factorized after the renumbering; same minimizer as the plain path.
  {
    std::vector<int> region;
    for (int v = 0; v < m.V.rows(); ++v)
      if (m.V(v, 0) < 0.9) region.push_back(v);
    REQUIRE(4 * region.size() > static_cast<size_t>(m.V.rows()));
    Eigen::VectorXi rb(region.size() + 1);
    Eigen::MatrixXd rbc = Eigen::MatrixXd::Zero(rb.size(), 2);
    for (size_t k = 0; k < region.size(); ++k) rb(k) = region[k], rbc(k, 0) = 1;
    rb(rb.size() - 1) = nearest(m.V, {2.9, 0.5, 0.5});
    rbc(rb.size() - 1, 1) = 1;
    BbwStats rp, rm;
    const Eigen::MatrixXd Rp = bbw_weights(m.V, m.T, rb, rbc, plain, &rp);
    const Eigen::MatrixXd Rm = bbw_weights(m.V, m.T, rb, rbc, multilevel, &rm);
    REQUIRE(rm.multilevel_handles == 0);
    REQUIRE(rm.converged);
    REQUIRE((Rp - Rm).cwiseAbs().maxCoeff() < 1e-6);
  }
  // Each handle is reported once, as soon as it is solved, with its own (unnormalized) minimizer.
  BbwOptions raw = multilevel;
  raw.normalize_rows = false;
  Eigen::MatrixXd reported = Eigen::MatrixXd::Constant(m.V.rows(), 4, -1);
  std::vector<int> calls(4, 0);
  raw.handle_solved = [&](int j, const Eigen::VectorXd& w) {
    REQUIRE(j >= 0);
    REQUIRE(j < 4);
    ++calls[j];
    reported.col(j) = w;
  };
  const Eigen::MatrixXd Wr = bbw_weights(m.V, m.T, b, bc, raw);
  REQUIRE(calls == std::vector<int>(4, 1));
  REQUIRE((reported - Wr).cwiseAbs().maxCoeff() == 0.0);
}
