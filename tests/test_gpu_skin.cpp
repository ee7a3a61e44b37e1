// GPU skinning (render/skin_pass) against the double-precision CPU reference, on the real driver.
#include <random>

#include <catch2/catch.hpp>

#include "core/mesh/io.h"
#include "core/mesh/mesh_info.h"
#include "core/rig/additional_handles.h"
#include "core/rig/pose_io.h"
#include "core/rig/pose_params.h"
#include "core/rig/rig_io.h"
#include "core/skin/skin.h"
#include "core/util/error.h"
#include "render/gl_context.h"
#include "render/skin_pass.h"
#include "tests/skin_test_weights.h"
#include "tests/test_support.h"

using namespace dfm;

static double bbox_diagonal(const Eigen::MatrixXd& V) { return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm(); }

// Compares the GPU pass with the CPU reference of the same binding. k = 0 keeps every weight: the
// GPU must then equal skinning with all of them, which differs from any truncation by far more than
// the tolerance (checked, so a GPU that silently kept only some influences fails).
static void check_binding(gl::Context& ctx, const SkinBinding& b, const Rig& rig, const PoseParams& params, int k,
                          double tol) {
  const Pose pose = evaluate_pose(rig, params);
  const auto stbs = stbs_handles(rig, params.bone_twist_stretch);
  gl::SkinPass pass(b);
  const SparseInfluences rows = sparse_influences(b.influences);
  REQUIRE(pass.num_entries() == rows.num_entries());
  REQUIRE(pass.max_influences() == rows.max_row);
  if (k > 0) REQUIRE(pass.max_influences() <= k);
  pass.set_pose(pose, stbs);
  const double diag = bbox_diagonal(b.V);
  for (SkinMethod m : {SkinMethod::LBS, SkinMethod::DQS, SkinMethod::STBS, SkinMethod::STBS_DQS}) {
    INFO("method " << skin_method_name(m) << ", k = " << k << ", " << ctx.renderer());
    pass.run(m);
    const SkinResult gpu = pass.read_back_result();
    const SkinResult cpu = skin(m, b, pose, stbs);
    const double pos_err = (gpu.V - cpu.V).rowwise().norm().maxCoeff();
    const double nrm_err = b.N.size() ? (gpu.N - cpu.N).rowwise().norm().maxCoeff() : 0.0;
    WARN(skin_method_name(m) << (k > 0 ? " k=" + std::to_string(k) : std::string(" all weights")) << " (at most "
                             << rows.max_row << " per vertex): max |GPU - CPU| = " << pos_err / diag
                             << " of the bbox diagonal; normals " << nrm_err);
    REQUIRE(pos_err <= tol * diag);
    REQUIRE(nrm_err <= 1e-4);
    // The pose really moved the mesh (the comparison is not trivially of two rest meshes).
    REQUIRE((cpu.V - b.V).rowwise().norm().maxCoeff() > 0.05 * diag);
    if (k == 0) {
      SkinBinding eight = b;
      eight.influences = top_influences(influences_to_dense(b.influences, b.num_handles), 8, true);
      eight.endpoints = gather_by_influence(eight.influences, bone_endpoint_weights(b.V, rig));
      eight.N.resize(0, 0);
      REQUIRE((skin(m, eight, pose, stbs).V - gpu.V).rowwise().norm().maxCoeff() > 100 * tol * diag);
    }
  }
}

static void check_pose(gl::Context& ctx, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Rig& rig,
                       const PoseParams& params, int k, double tol = 1e-5) {
  const Eigen::MatrixXd W = test::inverse_distance_bone_weights(V, rig);
  check_binding(ctx, make_skin_binding(V, vertex_normals(V, F), W, rig, k), rig, params, k, tol);
}

static PoseParams posed_hand(const Rig& rig, const std::string& qfile) {
  PoseParams params = rest_pose_params(rig);
  params.bone_rotation = read_bone_rotations(qfile, rig.skeleton.num_bones());
  params.bone_translation[10] = Eigen::Vector3d(0.05, 0.1, -0.02);
  params.bone_twist_stretch[3] = {1.0, 1.2, -0.4};  // with a twist at its first joint too
  params.bone_twist_stretch[7] = {-2.0, 0.8};
  return params;
}

// Posed arm with a bent elbow, a twisted and stretched forearm and a translated root: exercises
// every term of every method (4 bones: k = 4).
TEST_CASE("GPU skinning equals the CPU reference for every method: arm, k = 4", "[gl][skin]") {
  DFM_DATA_OR_SKIP(obj, "arm.obj");
  DFM_DATA_OR_SKIP(tgf, "arm.tgf");
  const TriMesh mesh = read_surface(obj);
  Rig rig;
  add_tgf_to_rig(rig, read_tgf(tgf), tgf);
  PoseParams params = rest_pose_params(rig);
  params.bone_translation[0] = Eigen::Vector3d(0.1, -0.2, 0.05);
  params.bone_rotation[1] = Eigen::Quaterniond(Eigen::AngleAxisd(0.6, Eigen::Vector3d(0, 0, 1)));
  params.bone_rotation[3] = Eigen::Quaterniond(Eigen::AngleAxisd(-0.8, Eigen::Vector3d(0, 1, 0)));
  params.bone_twist_stretch[2] = {2.5, 1.3};
  gl::Context ctx;
  check_pose(ctx, mesh.V, mesh.F, rig, params, 4);
}

// The hand tet mesh (all 7,234 vertices) in hand-pose.dmat with twists on two fingers: 20 bones, k = 8.
TEST_CASE("GPU skinning equals the CPU reference for every method: hand, k = 8", "[gl][skin]") {
  DFM_DATA_OR_SKIP(meshfile, "hand.mesh");
  DFM_DATA_OR_SKIP(tgf, "hand.tgf");
  DFM_DATA_OR_SKIP(qfile, "hand-pose.dmat");
  const TetMesh tets = read_tet_mesh(meshfile);
  Rig rig;
  add_tgf_to_rig(rig, read_tgf(tgf), tgf);
  gl::Context ctx;
  check_pose(ctx, tets.V, tet_boundary_faces(tets.T), rig, posed_hand(rig, qfile), 8);
}

// Every weight on the GPU (the default): the inverse-distance weights give each of the hand's
// vertices all 20 bones, far past any fixed per-vertex count.
TEST_CASE("GPU skinning with all weights equals the CPU reference for every method: hand and arm", "[gl][skin]") {
  DFM_DATA_OR_SKIP(meshfile, "hand.mesh");
  DFM_DATA_OR_SKIP(tgf, "hand.tgf");
  DFM_DATA_OR_SKIP(qfile, "hand-pose.dmat");
  DFM_DATA_OR_SKIP(obj, "arm.obj");
  DFM_DATA_OR_SKIP(arm_tgf, "arm.tgf");
  gl::Context ctx;
  {
    const TetMesh tets = read_tet_mesh(meshfile);
    Rig rig;
    add_tgf_to_rig(rig, read_tgf(tgf), tgf);
    check_pose(ctx, tets.V, tet_boundary_faces(tets.T), rig, posed_hand(rig, qfile), 0, 1e-6);
  }
  {
    const TriMesh mesh = read_surface(obj);
    Rig rig;
    add_tgf_to_rig(rig, read_tgf(arm_tgf), arm_tgf);
    PoseParams params = rest_pose_params(rig);
    params.bone_rotation[1] = Eigen::Quaterniond(Eigen::AngleAxisd(0.6, Eigen::Vector3d(0, 0, 1)));
    params.bone_twist_stretch[2] = {2.5, 1.3};
    const Eigen::MatrixXd W = test::inverse_distance_bone_weights(mesh.V, rig);
    // Sparse weights as a bind gives: each vertex only its nearest bones (1 to 4, a few none).
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(W.rows(), W.cols());
    for (int i = 0; i < W.rows(); ++i) {
      const Influences top = top_influences(W.row(i), 1 + i % 4, true);
      if (i % 97 == 0) continue;  // no weight at all: stays at the origin (LBS), at rest (DQS)
      for (int j = 0; j < top.k(); ++j) S(i, top.index(0, j)) = top.weight(0, j);
    }
    const SkinBinding b = make_skin_binding(mesh.V, vertex_normals(mesh.V, mesh.F), S, rig, 0);
    check_binding(ctx, b, rig, params, -1, 1e-6);
  }
}

// Sparse rows of every length from 0 to 40 (most far past 8) over 60 handles: exercises the offsets.
TEST_CASE("GPU skinning with all weights: sparse rows of 0 to 40 influences", "[gl][skin]") {
  gl::Context ctx;
  const int n = 3000, h = 60;
  std::mt19937 g(7);
  std::uniform_real_distribution<double> u(0, 1);
  Eigen::MatrixXd V(n, 3), W = Eigen::MatrixXd::Zero(n, h);
  for (int i = 0; i < n; ++i) {
    V.row(i) << u(g), u(g), u(g);
    const int count = i % 41;
    for (int j = 0; j < count; ++j) W(i, (i * 11 + j * 7) % h) += u(g) + 0.05;
    if (count) W.row(i) /= W.row(i).sum();
  }
  Rig rig;
  rig.points.resize(h);
  Pose pose = identity_pose(h);
  for (int j = 0; j < h; ++j)
    pose.transforms[j] = Eigen::Translation3d(0.3 * u(g), 0.3 * u(g), 0.3 * u(g)) *
                         Eigen::AngleAxisd(2.0 * u(g), Eigen::Vector3d(u(g), u(g), u(g)).normalized());
  const SkinBinding b = make_skin_binding(V, V.rowwise().normalized(), W, rig, 0);
  gl::SkinPass pass(b);
  REQUIRE(pass.max_influences() == 40);
  REQUIRE(pass.num_entries() == (W.array() != 0).count());
  pass.set_pose(pose);
  for (SkinMethod m : {SkinMethod::LBS, SkinMethod::DQS, SkinMethod::STBS}) {
    INFO(skin_method_name(m));
    pass.run(m);
    const SkinResult gpu = pass.read_back_result(), cpu = skin(m, b, pose);
    const double err = (gpu.V - cpu.V).rowwise().norm().maxCoeff();
    WARN(skin_method_name(m) << " rows of 0-40: max |GPU - CPU| = " << err);
    REQUIRE(err <= 1e-5);
    REQUIRE((gpu.N - cpu.N).rowwise().norm().maxCoeff() <= 1e-4);
  }
}

TEST_CASE("GPU skinning: identity pose returns the rest mesh; many handles fit", "[gl][skin]") {
  gl::Context ctx;
  const int n = 2000, h = 3000;  // more handles than any uniform block would hold
  std::mt19937 g(1);
  std::uniform_real_distribution<double> u(0, 1);
  Eigen::MatrixXd V(n, 3), W = Eigen::MatrixXd::Zero(n, h);
  for (int i = 0; i < n; ++i) {
    V.row(i) << u(g), u(g), u(g);
    for (int j = 0; j < 4; ++j) W(i, (i * 7 + j * 13 + 5) % h) += u(g) + 0.1;
    W.row(i) /= W.row(i).sum();
  }
  Rig rig;
  rig.points.resize(h);
  const SkinBinding b = make_skin_binding(V, Eigen::MatrixXd(), W, rig, 4);
  gl::SkinPass pass(b);
  pass.set_pose(identity_pose(h));
  Pose moved = identity_pose(h);
  for (int j = 0; j < h; ++j) moved.transforms[j].translation() = Eigen::Vector3d(j, 0, 0);
  for (SkinMethod m : {SkinMethod::LBS, SkinMethod::DQS, SkinMethod::STBS}) {
    pass.set_pose(identity_pose(h));
    pass.run(m);
    REQUIRE((pass.read_back_result().V - V).cwiseAbs().maxCoeff() < 1e-6);
    pass.set_pose(moved);  // handle j moves by j along x: tests that high handle indices are read
    pass.run(m);
    REQUIRE((pass.read_back_result().V - skin(m, b, moved).V).cwiseAbs().maxCoeff() < 1e-5 * h);
  }
  REQUIRE_THROWS_AS(pass.set_pose(identity_pose(10)), Error);
}


// Additional handles (core/rig/additional_handles.h, Jacobson 2013 7.3.3) on the arm: three bumps of
// weight that do not partition unity, skinned linearly after every method. Their transforms: two
// general affines (as FAST solves them) and one zero (unsolved). The CPU skin is checked against the
// sum written here, the GPU against the CPU.
TEST_CASE("GPU skinning with additional weights: arm, every method", "[gl][skin]") {
  DFM_DATA_OR_SKIP(obj, "arm.obj");
  DFM_DATA_OR_SKIP(tgf, "arm.tgf");
  const TriMesh mesh = read_surface(obj);
  Rig rig;
  add_tgf_to_rig(rig, read_tgf(tgf), tgf);
  const Eigen::MatrixXd& V = mesh.V;
  const Eigen::MatrixXd W = test::inverse_distance_bone_weights(V, rig);
  const double diag = bbox_diagonal(V);
  Eigen::MatrixXd A(V.rows(), 3);
  for (int e = 0; e < 3; ++e) {
    const Eigen::RowVector3d c = V.row((e + 1) * V.rows() / 4);
    for (int i = 0; i < V.rows(); ++i) A(i, e) = std::exp(-(V.row(i) - c).squaredNorm() / std::pow(0.15 * diag, 2));
  }
  PoseParams params = rest_pose_params(rig);
  params.bone_rotation[1] = Eigen::Quaterniond(Eigen::AngleAxisd(0.6, Eigen::Vector3d(0, 0, 1)));
  params.bone_twist_stretch[2] = {1.5, 1.2};
  const int nh = num_handles(rig);
  Eigen::Affine3d S0 = Eigen::Affine3d::Identity(), S1 = Eigen::Affine3d::Identity();
  S0.matrix().topRows(3) << 0.2, -0.1, 0.05, 0.1 * diag, 0.03, 0.15, -0.02, -0.05 * diag, 0.0, 0.04, -0.1, 0.02 * diag;
  S1.matrix().topRows(3) << -0.1, 0.0, 0.2, 0.0, 0.05, 0.1, 0.0, 0.08 * diag, 0.1, -0.1, 0.05, -0.03 * diag;
  params.solved[nh] = S0;
  params.solved[nh + 1] = S1;  // nh + 2 unsolved: zero
  const Pose pose = skin_pose(rig, params, 3);
  REQUIRE(pose.size() == nh + 3);
  REQUIRE(pose.transforms[nh + 2].matrix().topRows(3).isZero());
  const auto stbs = stbs_handles(rig, params.bone_twist_stretch);
  const SkinBinding b = make_skin_binding(V, vertex_normals(V, mesh.F), W, rig, 0, {}, A);
  REQUIRE(b.additional == 3);
  const SkinBinding plain = make_skin_binding(V, Eigen::MatrixXd(), W, rig, 0);
  const Pose rig_pose = evaluate_pose(rig, params);
  // The additional term, written out: sum_e A_ie S_e v_i.
  Eigen::MatrixXd extra = Eigen::MatrixXd::Zero(V.rows(), 3);
  for (int i = 0; i < V.rows(); ++i)
    for (int e = 0; e < 3; ++e) extra.row(i) += A(i, e) * (pose.transforms[nh + e] * Eigen::Vector3d(V.row(i).transpose())).transpose();
  REQUIRE(extra.rowwise().norm().maxCoeff() > 0.01 * diag);  // the bumps really move the arm
  gl::Context ctx;
  gl::SkinPass pass(b);
  pass.set_pose(pose, stbs);  // one twist/stretch record per rig handle: the additional ones have none
  for (SkinMethod m : {SkinMethod::LBS, SkinMethod::DQS, SkinMethod::STBS, SkinMethod::STBS_DQS}) {
    INFO("method " << skin_method_name(m) << ", " << ctx.renderer());
    const SkinResult cpu = skin(m, b, pose, stbs);
    REQUIRE((cpu.V - (skin(m, plain, rig_pose, stbs).V + extra)).rowwise().norm().maxCoeff() < 1e-12 * diag);
    pass.run(m);
    const SkinResult gpu = pass.read_back_result();
    const double pos_err = (gpu.V - cpu.V).rowwise().norm().maxCoeff();
    WARN(skin_method_name(m) << " with 3 additional weights: max |GPU - CPU| = " << pos_err / diag << " of the diagonal");
    REQUIRE(pos_err <= 1e-5 * diag);
    REQUIRE((gpu.N - cpu.N).rowwise().norm().maxCoeff() <= 1e-4);
  }
}
