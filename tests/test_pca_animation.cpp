// Animations from base shapes (Alexa 2003, 7.2): rigid motion removal, the rank-k decomposition and
// per-frame reconstruction, against references computed here (Horn's quaternion alignment, a Jacobi
// SVD) rather than the production Kabsch and BDCSVD.
#include <cmath>

#include <catch2/catch.hpp>

#include "core/anim/pca_animation.h"
#include "core/util/error.h"
#include "tests/pca_test_frames.h"

using namespace dfm;
using Catch::Contains;

namespace {

// sqrt(sum_i |frame_i - reconstruction_i|_F^2) in world space, through the public reconstruction.
double world_error(const std::vector<Eigen::MatrixXd>& frames, const PcaAnimation& a) {
  double sum = 0;
  for (int i = 0; i < a.num_frames(); ++i) sum += (frames[i] - pca_frame(a, i)).squaredNorm();
  return std::sqrt(sum);
}

}  // namespace

TEST_CASE("pca: for every k the error is the best rank-k error of the centred, aligned frames (Eckart-Young)",
          "[pca]") {
  const TriMesh bar = test::pca_bar();
  const int n = 14;
  const std::vector<Eigen::MatrixXd> frames = test::bending_bar_frames(bar, n, 2e-3);
  const test::ReferencePca ref = test::reference_pca(frames);
  const PcaDecomposition d = decompose_frames(frames);
  REQUIRE(d.max_bases() == n);
  const double scale = ref.X.norm();
  // The noise keeps every discarded sigma far above rounding, so the relative check holds down to the
  // last base; the centred matrix has rank n - 1, so k >= n - 1 leaves only rounding (absolute floor).
  REQUIRE(ref.sigma[n - 2] > 1e-4 * scale);
  for (int k = 0; k <= n; ++k) {
    INFO("k = " << k);
    const PcaAnimation a = pca_animation(d, k, bar.F, frame_times(n, 24));
    const double best = ref.best_error(k);
    const PcaErrors e = pca_errors(d, a);
    CHECK(std::abs(e.total - best) <= 1e-9 * best + 1e-12 * scale);
    // The same through the world-space reconstruction (rigid motion put back).
    CHECK(std::abs(world_error(frames, a) - best) <= 1e-9 * best + 1e-12 * scale);
    double sum = 0;
    for (double f : e.frobenius) sum += f * f;
    CHECK(std::sqrt(sum) == Approx(e.total).epsilon(1e-12).margin(1e-14 * scale));
    for (int i = 0; i < n; ++i) CHECK(e.max_vertex[i] <= e.frobenius[i] * (1 + 1e-12));
  }
  // Singular values agree with the Jacobi reference.
  for (int j = 0; j + 1 < n; ++j) CHECK(d.singular_values[j] == Approx(ref.sigma[j]).epsilon(1e-9));
}

TEST_CASE("pca: the stored rigid motion is Horn's alignment to frame 0, so reconstruction puts it back", "[pca]") {
  const TriMesh bar = test::pca_bar();
  std::vector<Eigen::MatrixXd> frames = test::bending_bar_frames(bar, 6, 1e-3, 11);
  const test::ReferencePca ref = test::reference_pca(frames);
  const AlignedFrames al = align_frames(frames);
  for (size_t i = 0; i < frames.size(); ++i) {
    INFO("frame " << i);
    const Eigen::Matrix3d R = al.motion[i].rotation.toRotationMatrix();
    CHECK((R - ref.rotation[i]).norm() < 1e-12);
    CHECK((al.motion[i].translation - ref.centroid[i]).norm() < 1e-12);
    CHECK(al.aligned[i].colwise().mean().norm() < 1e-12);
    CHECK((test::apply(Eigen::Translation3d(ref.centroid[i]) * Eigen::Affine3d(R), al.aligned[i]) - frames[i]).norm() < 1e-12);
  }
  CHECK((al.motion[0].rotation.toRotationMatrix() - Eigen::Matrix3d::Identity()).norm() < 1e-14);
}

TEST_CASE("pca: a mirrored frame is aligned by a rotation, not a reflection", "[pca]") {
  const TriMesh bar = test::pca_bar();
  const Eigen::MatrixXd shape = test::bend_and_twist(bar.V, 0.9, 0.6);  // chiral: twisted and bent
  Eigen::MatrixXd mirrored = shape;
  mirrored.col(2) *= -1;
  const AlignedFrames al = align_frames({shape, mirrored});
  const Eigen::Matrix3d R = al.motion[1].rotation.toRotationMatrix();
  CHECK(R.determinant() == Approx(1.0).epsilon(1e-12));
  const Eigen::MatrixXd P = mirrored.rowwise() - mirrored.colwise().mean();
  const Eigen::MatrixXd Q = shape.rowwise() - shape.colwise().mean();
  CHECK((R.transpose() - test::horn_rotation(P, Q)).norm() < 1e-10);
  CHECK((al.aligned[1] - Q).norm() > 0.1);  // a reflection would have matched it exactly
}

TEST_CASE("pca: rigid motions of one shape compress to k = 0 with no error", "[pca]") {
  const TriMesh bar = test::pca_bar();
  const Eigen::MatrixXd shape = test::bend_and_twist(bar.V, 0.7, 0.5);
  std::mt19937 rng(3);
  std::vector<Eigen::MatrixXd> frames;
  for (int i = 0; i < 9; ++i) frames.push_back(test::apply(test::random_rigid(rng), shape));
  const PcaDecomposition d = decompose_frames(frames);
  const double scale = shape.norm();
  CHECK(d.singular_values[0] < 1e-12 * scale);
  const PcaAnimation a = pca_animation(d, 0, bar.F, frame_times(9, 30));
  CHECK(a.num_bases() == 0);
  CHECK(pca_errors(d, a).total < 1e-12 * scale);
  for (int i = 0; i < 9; ++i) CHECK((pca_frame(a, i) - frames[i]).norm() < 1e-12 * scale);
}

TEST_CASE("pca: frames without rigid motion need no alignment (identity rotations)", "[pca]") {
  const TriMesh bar = test::pca_bar();
  std::vector<Eigen::MatrixXd> frames;
  for (int i = 0; i < 5; ++i) frames.push_back(test::bend_and_twist(bar.V, 0.0, 0.0));
  const PcaDecomposition d = decompose_frames(frames);
  for (const RigidMotion& m : d.motion) CHECK(m.rotation.angularDistance(Eigen::Quaterniond::Identity()) < 1e-12);
  CHECK((d.mean - (bar.V.rowwise() - bar.V.colwise().mean())).norm() < 1e-14);
}

TEST_CASE("pca: every k from 0 to min(frames, 3V) is allowed, others and bad inputs are errors", "[pca]") {
  const TriMesh bar = test::pca_bar(3, 3);  // 11 vertices: 3V = 33 > frames
  const std::vector<Eigen::MatrixXd> frames = test::bending_bar_frames(bar, 5, 1e-3);
  const PcaDecomposition d = decompose_frames(frames);
  CHECK(d.max_bases() == 5);
  CHECK_NOTHROW(pca_animation(d, 5, bar.F, frame_times(5, 24)));
  CHECK_THROWS_WITH(pca_animation(d, 6, bar.F, frame_times(5, 24)), Contains("allow 0 to 5"));
  CHECK_THROWS_AS(pca_animation(d, -1, bar.F, frame_times(5, 24)), Error);
  CHECK_THROWS_WITH(pca_animation(d, 2, bar.F, {0, 1, 1, 2, 3}), Contains("strictly increasing"));
  CHECK_THROWS_WITH(pca_animation(d, 2, bar.F, {0, 1}), Contains("2 frame times for 5 frames"));
  Eigen::MatrixXi badF = bar.F;
  badF(0, 0) = 11;
  CHECK_THROWS_WITH(pca_animation(d, 2, badF, frame_times(5, 24)), Contains("outside"));
  std::vector<Eigen::MatrixXd> uneven = frames;
  uneven[3] = Eigen::MatrixXd(uneven[3].topRows(10));  // a copy: resizing from its own block would read freed memory
  CHECK_THROWS_WITH(decompose_frames(uneven), Contains("frame 3 has 10 vertices"));
  uneven = frames;
  uneven[2](1, 1) = std::nan("");
  CHECK_THROWS_WITH(decompose_frames(uneven), Contains("frame 2 has a non-finite"));
  CHECK_THROWS_AS(decompose_frames({}), Error);
  CHECK_THROWS_AS(frame_times(3, 0.0), Error);
  const PcaAnimation a = pca_animation(d, 2, bar.F, frame_times(5, 24));
  CHECK_THROWS_WITH(pca_frame(a, 5), Contains("outside the animation's 5 frames"));
}

TEST_CASE("pca: more frames than 3V: at most 3V bases, and all of them reproduce every frame", "[pca]") {
  const TriMesh bar = test::pca_bar(2, 3);  // 8 vertices: 3V = 24
  const std::vector<Eigen::MatrixXd> frames = test::bending_bar_frames(bar, 30, 1e-2);
  const PcaDecomposition d = decompose_frames(frames);
  CHECK(d.max_bases() == 24);
  const PcaAnimation a = pca_animation(d, 24, bar.F, frame_times(30, 24));
  for (int i = 0; i < 30; ++i) CHECK((pca_frame(a, i) - frames[i]).norm() < 1e-12 * frames[i].norm());
  const test::ReferencePca ref = test::reference_pca(frames);
  // Centroid 0 and Kabsch's optimality (sum_v a_v x r_v = 0) are 6 linear constraints on each aligned
  // frame, so the rank is at most 3V - 6 = 18: from there on the error is rounding only.
  for (int k : {1, 5, 12, 17, 20}) {
    const double best = ref.best_error(k);
    CHECK(std::abs(pca_errors(d, pca_animation(d, k, bar.F, frame_times(30, 24))).total - best) <=
          1e-9 * best + 1e-12 * ref.X.norm());
  }
  CHECK(ref.best_error(17) > 1e-6 * ref.X.norm());
  CHECK(ref.best_error(18) < 1e-12 * ref.X.norm());
}
