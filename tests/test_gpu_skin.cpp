// GPU skinning (render/skin_pass) against the double-precision CPU reference, on the real driver.
#include <random>

#include <catch2/catch.hpp>

#include "core/mesh/io.h"
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

// Posed arm with a bent elbow, a twisted and stretched forearm and a translated root: exercises
// every term of every method.
static void check_arm_pose(gl::Context& ctx, int k) {
  DFM_DATA_OR_SKIP(obj, "arm.obj");
  DFM_DATA_OR_SKIP(tgf, "arm.tgf");
  const TriMesh mesh = read_surface(obj);
  Rig rig;
  add_tgf_to_rig(rig, read_tgf(tgf), tgf);
  const Eigen::MatrixXd W = test::inverse_distance_bone_weights(mesh.V, rig);
  const SkinBinding b = make_skin_binding(mesh.V, vertex_normals(mesh.V, mesh.F), W, rig, k);
  PoseParams params = rest_pose_params(rig);
  params.bone_translation[0] = Eigen::Vector3d(0.1, -0.2, 0.05);
  params.bone_rotation[1] = Eigen::Quaterniond(Eigen::AngleAxisd(0.6, Eigen::Vector3d(0, 0, 1)));
  params.bone_rotation[3] = Eigen::Quaterniond(Eigen::AngleAxisd(-0.8, Eigen::Vector3d(0, 1, 0)));
  params.bone_twist_stretch[2] = {2.5, 1.3};
  const Pose pose = evaluate_pose(rig, params);
  const auto stbs = stbs_handles(rig, params.bone_twist_stretch);

  gl::SkinPass pass(b);
  REQUIRE(pass.k() == k);
  pass.set_pose(pose, stbs);
  const double diag = bbox_diagonal(mesh.V);
  for (SkinMethod m : {SkinMethod::LBS, SkinMethod::DQS, SkinMethod::STBS}) {
    INFO("method " << skin_method_name(m) << ", k = " << k << ", " << ctx.renderer());
    pass.run(m);
    const SkinResult gpu = pass.read_back_result();
    const SkinResult cpu = skin(m, b, pose, stbs);
    const double pos_err = (gpu.V - cpu.V).rowwise().norm().maxCoeff();
    const double nrm_err = (gpu.N - cpu.N).rowwise().norm().maxCoeff();
    WARN(skin_method_name(m) << " k=" << k << ": max |GPU - CPU| = " << pos_err / diag
                             << " of the bbox diagonal; normals " << nrm_err);
    {
      Eigen::Index worst;
      (gpu.V - cpu.V).rowwise().norm().maxCoeff(&worst);
      WARN("worst " << worst << " gpu " << gpu.V.row(worst) << " cpu " << cpu.V.row(worst) << " rest " << mesh.V.row(worst)
                    << " idx " << b.influences.index.row(worst) << " w " << b.influences.weight.row(worst));
      int bad = 0;
      for (int i = 0; i < gpu.V.rows(); ++i) bad += (gpu.V.row(i) - cpu.V.row(i)).norm() > 1e-5 * diag;
      WARN("bad " << bad);
    }
    REQUIRE(pos_err <= 1e-5 * diag);
    REQUIRE(nrm_err <= 1e-4);
    // The pose really moved the mesh (the comparison is not trivially of two rest meshes).
    REQUIRE((cpu.V - mesh.V).rowwise().norm().maxCoeff() > 0.05 * diag);
  }
}

TEST_CASE("GPU skinning equals the CPU reference for every method, k = 4 and 8", "[gl][skin]") {
  gl::Context ctx;
  check_arm_pose(ctx, 4);
  check_arm_pose(ctx, 8);
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

TEST_CASE("debug rot", "[.debug]") {
  gl::Context ctx;
  Eigen::MatrixXd V(2, 3);
  V << 1, 0, 0, 0, 2, 0;
  Rig rig;
  rig.points.resize(2);
  Eigen::MatrixXd W(2, 2);
  W << 1, 0, 0, 1;
  const SkinBinding b = make_skin_binding(V, Eigen::MatrixXd(), W, rig, 4);
  gl::SkinPass pass(b);
  Pose p = identity_pose(2);
  p.transforms[0] = Eigen::Affine3d(Eigen::AngleAxisd(1.5707963, Eigen::Vector3d::UnitZ()));
  p.transforms[1].translation() << 0, 0, 5;
  pass.set_pose(p);
  pass.run(SkinMethod::LBS);
  WARN(pass.read_back_result().V);
  WARN(skin(SkinMethod::LBS, b, p).V);
}
