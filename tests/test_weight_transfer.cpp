// Weight transfer (core/bind/weight_transfer.h; Abdrashitov et al. 2023): onto the source itself the
// weights come back exactly; onto a midpoint subdivision each new vertex reads the mean of its edge's
// ends; a region pushed out of reach is inpainted within the range of its border (the maximum
// principle) with rows in [0, 1] summing to 1; a piece with no match takes its closest points' weights.
#include <catch2/catch.hpp>

#include <map>

#include "core/bind/weight_transfer.h"
#include "core/mesh/io.h"
#include "core/util/error.h"
#include "tests/test_support.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;

namespace {

// Smooth weights: a softmax of the distances to four points, rows summing to 1.
Eigen::MatrixXd smooth_weights(const Eigen::MatrixXd& V) {
  const Eigen::RowVector3d lo = V.colwise().minCoeff(), hi = V.colwise().maxCoeff();
  Eigen::MatrixXd W(V.rows(), 4);
  for (int j = 0; j < 4; ++j) {
    const Eigen::RowVector3d c = lo + (hi - lo).cwiseProduct(Eigen::RowVector3d(0.2 + 0.2 * j, 0.5, 0.3 + 0.1 * j));
    for (int i = 0; i < V.rows(); ++i) W(i, j) = std::exp(-4 * (V.row(i) - c).norm() / (hi - lo).norm());
  }
  for (int i = 0; i < V.rows(); ++i) W.row(i) /= W.row(i).sum();
  return W;
}

// Each triangle into four by its edge midpoints; mid[(a, b)] is the midpoint vertex of edge a < b.
TriMesh midpoint_subdivision(const TriMesh& m, std::map<std::pair<int, int>, int>& mid) {
  TriMesh out;
  std::vector<Eigen::RowVector3d> V;
  for (int i = 0; i < m.V.rows(); ++i) V.push_back(m.V.row(i));
  auto at = [&](int a, int b) {
    const std::pair<int, int> e(std::min(a, b), std::max(a, b));
    auto it = mid.find(e);
    if (it != mid.end()) return it->second;
    V.push_back(0.5 * (m.V.row(a) + m.V.row(b)));
    return mid[e] = static_cast<int>(V.size()) - 1;
  };
  std::vector<Eigen::Vector3i> F;
  for (int f = 0; f < m.F.rows(); ++f) {
    const int a = m.F(f, 0), b = m.F(f, 1), c = m.F(f, 2), ab = at(a, b), bc = at(b, c), ca = at(c, a);
    F.insert(F.end(), {{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}});
  }
  out.V.resize(static_cast<Eigen::Index>(V.size()), 3);
  for (size_t i = 0; i < V.size(); ++i) out.V.row(static_cast<Eigen::Index>(i)) = V[i];
  out.F.resize(static_cast<Eigen::Index>(F.size()), 3);
  for (size_t f = 0; f < F.size(); ++f) out.F.row(static_cast<Eigen::Index>(f)) = F[f].transpose();
  return out;
}

void check_rows(const Eigen::MatrixXd& W) {
  CHECK(W.minCoeff() >= 0);
  CHECK(W.maxCoeff() <= 1);
  CHECK((W.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-12);
}

}  // namespace

TEST_CASE("weight transfer onto the source itself gives its weights back exactly", "[bind][transfer]") {
  const TriMesh s = test::icosphere(Eigen::Vector3d::Zero(), 1.0, 2);
  const Eigen::MatrixXd W = smooth_weights(s.V);
  WeightTransferReport r;
  CHECK(transfer_weights(s.V, s.F, W, s.V, s.F, {}, &r) == W);
  CHECK(r.matched == s.V.rows());
  CHECK(r.inpainted == 0);
}

TEST_CASE("weight transfer onto arm.obj subdivided once: each vertex reads the weights at its point", "[bind][transfer][data]") {
  DFM_DATA_OR_SKIP(path, "arm.obj");
  const TriMesh arm = read_surface(path);
  const Eigen::MatrixXd W = smooth_weights(arm.V);
  std::map<std::pair<int, int>, int> mid;
  const TriMesh fine = midpoint_subdivision(arm, mid);
  WeightTransferReport r;
  const Eigen::MatrixXd T = transfer_weights(arm.V, arm.F, W, fine.V, fine.F, {}, &r);
  REQUIRE(T.rows() == fine.V.rows());
  CHECK(r.matched == fine.V.rows());
  CHECK(T.topRows(arm.V.rows()) == W);
  double worst = 0;
  for (const auto& [e, v] : mid) worst = std::max(worst, (T.row(v) - 0.5 * (W.row(e.first) + W.row(e.second))).cwiseAbs().maxCoeff());
  WARN("arm subdivided once: " << fine.V.rows() << " vertices, largest difference from the weights at the same points " << worst);
  CHECK(worst < 1e-3);
}

TEST_CASE("weight transfer inpaints what is out of reach, within its border's range; a piece with no match reads its closest points",
          "[bind][transfer]") {
  const TriMesh s = test::icosphere(Eigen::Vector3d::Zero(), 1.0, 3);
  const Eigen::MatrixXd W = smooth_weights(s.V);
  TriMesh t = s;
  for (int i = 0; i < t.V.rows(); ++i)
    if (t.V(i, 2) > 0.6) t.V.row(i) *= 1.5;  // a cap pushed out past 5% of the diagonal
  WeightTransferReport r;
  const Eigen::MatrixXd T = transfer_weights(s.V, s.F, W, t.V, t.F, {}, &r);
  check_rows(T);
  REQUIRE(r.inpainted > 20);
  CHECK(r.nearest == 0);
  CHECK(r.matched + r.inpainted == t.V.rows());
  // The inpainted rows lie within the range of the matched rows around them (each column harmonic
  // before the clamp and the division, both of which keep an in-range row in range here).
  std::vector<char> cap(t.V.rows(), 0);
  for (int i = 0; i < t.V.rows(); ++i) cap[i] = t.V(i, 2) > 0.6 * 1.5 - 1e-12 && s.V(i, 2) > 0.6;
  Eigen::RowVectorXd lo = Eigen::RowVectorXd::Constant(4, 1.0), hi = Eigen::RowVectorXd::Zero(4);
  double jump = 0, source_jump = 0;
  for (int f = 0; f < t.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = t.F(f, k), b = t.F(f, (k + 1) % 3);
      source_jump = std::max(source_jump, (W.row(a) - W.row(b)).cwiseAbs().maxCoeff());
      if (cap[a] == cap[b]) continue;
      const int border = cap[a] ? b : a;
      lo = lo.cwiseMin(T.row(border));
      hi = hi.cwiseMax(T.row(border));
      jump = std::max(jump, (T.row(a) - T.row(b)).cwiseAbs().maxCoeff());
    }
  for (int i = 0; i < t.V.rows(); ++i)
    if (cap[i])
      for (int j = 0; j < 4; ++j) {
        CHECK(T(i, j) >= lo[j] - 0.02);
        CHECK(T(i, j) <= hi[j] + 0.02);
      }
  WARN("inpainted cap: " << r.inpainted << " vertices; largest step across its border " << jump
                         << " (largest between neighbours on the source " << source_jump << ")");
  CHECK(jump <= 2.5 * source_jump);

  // A second piece far away: no match anywhere, so its closest source points' weights.
  TriMesh two = s;
  const TriMesh far = test::icosphere(Eigen::Vector3d(5, 0, 0), 0.2, 1);
  two.V.conservativeResize(s.V.rows() + far.V.rows(), 3);
  two.V.bottomRows(far.V.rows()) = far.V;
  two.F.conservativeResize(s.F.rows() + far.F.rows(), 3);
  two.F.bottomRows(far.F.rows()) = far.F.array() + static_cast<int>(s.V.rows());
  const Eigen::MatrixXd T2 = transfer_weights(s.V, s.F, W, two.V, two.F, {}, &r);
  CHECK(r.nearest == far.V.rows());
  check_rows(T2.bottomRows(far.V.rows()));
  CHECK(T2.topRows(s.V.rows()) == W);
}

TEST_CASE("weight transfer refuses weights that do not fit the source", "[bind][transfer]") {
  const TriMesh s = test::icosphere(Eigen::Vector3d::Zero(), 1.0, 1);
  CHECK_THROWS_AS(transfer_weights(s.V, s.F, Eigen::MatrixXd::Ones(3, 2), s.V, s.F), Error);
  Eigen::MatrixXi bad = s.F;
  bad(0, 0) = 999;
  CHECK_THROWS_AS(transfer_weights(s.V, s.F, smooth_weights(s.V), s.V, bad), Error);
}
