// Additional weight functions (Jacobson 2013, 7.3.3) and the cigar of Fig. 7.7d-e: a capsule bent by
// 90 degrees by two fully constrained end regions. Without additional weights FAST has nothing to
// solve (plain LBS: a pinch); with 10 it lowers the ARAP energy, recomputed here with per-vertex
// best-fit rotations, and the middle keeps more of its cross-section, measured here by slicing.
#include <cmath>
#include <set>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "core/bind/additional_weights.h"
#include "core/bind/bind.h"
#include "core/pose/fast_model.h"
#include "core/pose/fast_solver.h"
#include "core/skin/lbs.h"
#include "core/util/error.h"
#include "tests/capsule_test_mesh.h"
#include "tests/test_support.h"

using namespace dfm;
using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Spokes-and-rims ARAP energy with each vertex's own best-fit rotation (Eq. 7.4), as test_fast's.
double per_vertex_arap_energy(const MatrixXd& V, const Eigen::MatrixXi& F, const MatrixXd& U) {
  auto cot = [&](int f, int corner) {
    const Vector3d p = V.row(F(f, corner)), a = V.row(F(f, (corner + 1) % 3)), b = V.row(F(f, (corner + 2) % 3));
    const Vector3d u = a - p, w = b - p;
    return 0.5 * u.dot(w) / u.cross(w).norm();
  };
  std::vector<Matrix3d> S(V.rows(), Matrix3d::Zero()), R(V.rows());
  for (int f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int i = F(f, (c + 1) % 3), j = F(f, (c + 2) % 3);
      const Vector3d d = (V.row(i) - V.row(j)).transpose(), dp = (U.row(i) - U.row(j)).transpose();
      for (int k = 0; k < 3; ++k) S[F(f, k)] += cot(f, c) * d * dp.transpose();
    }
  for (int v = 0; v < V.rows(); ++v) {
    Eigen::JacobiSVD<Matrix3d> svd(S[v], Eigen::ComputeFullU | Eigen::ComputeFullV);
    Matrix3d W = svd.matrixV();
    if ((W * svd.matrixU().transpose()).determinant() < 0) W.col(2) *= -1;
    R[v] = W * svd.matrixU().transpose();
  }
  double E = 0;
  for (int f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int i = F(f, (c + 1) % 3), j = F(f, (c + 2) % 3);
      const Vector3d d = (V.row(i) - V.row(j)).transpose(), dp = (U.row(i) - U.row(j)).transpose();
      for (int k = 0; k < 3; ++k) E += 0.5 * cot(f, c) * (dp - R[F(f, k)] * d).squaredNorm();
    }
  return E;
}

// Area of the closed surface's section by the plane through `o` with normal `n`, on the side of `o`
// in direction `side` (half-plane): the intersection segments, oriented by the surface, summed as
// triangles fanned from o.
double section_area(const MatrixXd& U, const Eigen::MatrixXi& F, const Vector3d& o, const Vector3d& n,
                    const Vector3d& side) {
  double area = 0;
  for (int f = 0; f < F.rows(); ++f) {
    Vector3d pts[2];
    int count = 0;
    double s[3];
    for (int k = 0; k < 3; ++k) s[k] = (U.row(F(f, k)).transpose() - o).dot(n);
    // Walk the edges in the face's order: the + to - crossing first, then - to +, so that every
    // segment runs the same way round the section.
    for (int k = 0; k < 3; ++k) {
      const int a = k, b = (k + 1) % 3;
      if ((s[a] > 0) != (s[b] > 0)) {
        const double t = s[a] / (s[a] - s[b]);
        const Vector3d p = (1 - t) * U.row(F(f, a)).transpose() + t * U.row(F(f, b)).transpose();
        pts[s[a] > 0 ? 0 : 1] = p;
        ++count;
      }
    }
    if (count != 2) continue;
    if ((0.5 * (pts[0] + pts[1]) - o).dot(side) <= 0) continue;
    area += 0.5 * (pts[0] - o).cross(pts[1] - o).dot(n);
  }
  return std::abs(area);
}

}  // namespace

TEST_CASE("farthest-point samples: each the farthest from the seeds and the samples before it", "[fast][weights]") {
  MatrixXd V(5, 3);
  V << 0, 0, 0, 1, 0, 0, 3, 0, 0, 10, 0, 0, 6, 0, 0;
  const std::vector<int> s = farthest_point_samples(V, {0}, 3);
  CHECK(s == std::vector<int>{3, 4, 2});
  CHECK_THROWS_WITH(farthest_point_samples(V, {0, 1, 2, 3, 4}, 1), Catch::Contains("only 0 vertices"));
}

TEST_CASE("additional weights on the cigar of Fig. 7.7: lower ARAP energy, less pinch (7.3.3)",
          "[fast][weights]") {
  const double a = 2.0, r = 0.5;
  const TriMesh cigar = test::capsule(a, r, 4, 40, 16);
  // Two fully constrained end regions: the vertices beyond |x| = a - 0.25.
  Rig rig;
  rig.regions.resize(2);
  for (int i = 0; i < cigar.V.rows(); ++i) {
    if (cigar.V(i, 0) < -a + 0.25) rig.regions[0].vertices.push_back(i);
    if (cigar.V(i, 0) > a - 0.25) rig.regions[1].vertices.push_back(i);
  }
  const BindResult bind = bind_surface(cigar, rig);
  const AdditionalWeights extra = additional_weights(bind, 10);
  REQUIRE(extra.weights.rows() == cigar.V.rows());
  REQUIRE(extra.weights.cols() == 10);
  CHECK(extra.weights.minCoeff() >= -1e-9);
  CHECK(extra.weights.maxCoeff() <= 1 + 1e-9);

  // Bend by 90 degrees: the left region stays, the right one ends a quarter circle of length 2a
  // (radius rho, centre c) turned to +y.
  const double rho = 2 * a / (kPi / 2);
  const Vector3d c(-a, rho, 0);
  Eigen::Affine3d right = Eigen::Affine3d::Identity();
  right.linear() = Eigen::AngleAxisd(kPi / 2, Vector3d::UnitZ()).toRotationMatrix();
  right.translation() = Vector3d(-a + rho, rho, 0) - right.linear() * Vector3d(a, 0, 0);

  auto solve = [&](const MatrixXd& W, int free) {
    const FastModel model = fast_model(cigar.V, cigar.F, W);
    std::vector<FastConstraint> cons(W.cols());
    for (int j = 2; j < W.cols(); ++j) cons[j].state = HandleConstraint::Free;
    FastSolver solver(model, cons);
    Pose pose = identity_pose(static_cast<int>(W.cols()));
    pose.transforms[1] = right;
    solver.set_targets(pose, std::vector<Vector3d>(W.cols(), Vector3d::Zero()));
    if (free) solver.iterate(pose, 200);
    return lbs(cigar.V, W, pose);
  };
  MatrixXd W_more(cigar.V.rows(), 12);
  W_more << bind.weights, extra.weights;
  const MatrixXd U_lbs = solve(bind.weights, 0), U_more = solve(W_more, 10);
  // Both keep the constrained regions where the constraint puts them.
  for (int i : rig.regions[1].vertices) CHECK((U_more.row(i).transpose() - right * Vector3d(cigar.V.row(i).transpose())).norm() < 1e-6);

  const double e_lbs = per_vertex_arap_energy(cigar.V, cigar.F, U_lbs);
  const double e_more = per_vertex_arap_energy(cigar.V, cigar.F, U_more);
  // Sections through the bend's axis at 30..60 degrees along the arc, against the rest middle section.
  const double rest = section_area(cigar.V, cigar.F, Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY()) +
                      section_area(cigar.V, cigar.F, Vector3d::Zero(), Vector3d::UnitX(), -Vector3d::UnitY());
  CHECK(rest == Approx(kPi * r * r).epsilon(0.05));  // a 16-gon
  auto min_section = [&](const MatrixXd& U) {
    double smallest = 1e300;
    for (int k = 0; k <= 30; ++k) {
      const double phi = kPi / 6 + (kPi / 6) * k / 30;
      const Vector3d n(std::cos(phi), std::sin(phi), 0), outward(std::sin(phi), -std::cos(phi), 0);
      smallest = std::min(smallest, section_area(U, cigar.F, c, n, outward));
    }
    return smallest / rest;
  };
  const double pinch_lbs = min_section(U_lbs), pinch_more = min_section(U_more);
  WARN("cigar bent 90 degrees (" << cigar.V.rows() << " vertices): ARAP energy LBS (no additional weights) "
                                 << e_lbs << ", FAST with 10 additional weights " << e_more
                                 << "; smallest middle section over rest: " << pinch_lbs << " vs " << pinch_more);
  CHECK(e_more < e_lbs);
  CHECK(pinch_more > pinch_lbs);
  CHECK_THROWS_WITH(additional_weights(bind, 0), Catch::Contains("k must be >= 1"));
}
