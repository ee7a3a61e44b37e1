// STBS endpoint weights from the bind (Jacobson 2013, 6.2.3): Eq. 6.7 against a closed form, the joint
// constraints of a bone's samples, and on the bound arm and hand the properties of 6.2.2: in [0, 1],
// 0 at a bone's first joint and 1 at its second, increasing along the bone; STBS at rest twist and
// stretch is LBS bit for bit with them.
#include <catch2/catch.hpp>

#include "core/bind/bind.h"
#include "core/bind/endpoint_weights.h"
#include "core/mesh/io.h"
#include "core/rig/rig_io.h"
#include "core/skin/skin.h"
#include "tests/test_support.h"

using namespace dfm;

namespace {

Rig two_bones() {
  Rig rig;
  rig.skeleton.joints.resize(3, 3);
  rig.skeleton.joints << 0, 0, 0, 2, 0, 0, 2, 1, 0;
  rig.skeleton.bones = {{0, 1, -1, "a"}, {1, 2, 0, "b"}};
  return rig;
}

// At the volume vertices nearest to ten points spaced along each bone (its samples): 0 at the start,
// 1 at the end, increasing; every value in [0, 1].
void check_along_bones(const BindVolume& vol, const Rig& rig, const Eigen::MatrixXd& E) {
  REQUIRE(E.rows() == vol.tets.num_vertices());
  REQUIRE(E.cols() == rig.skeleton.num_bones());
  CHECK(E.minCoeff() >= 0);
  CHECK(E.maxCoeff() <= 1);
  for (int i = 0; i < rig.skeleton.num_bones(); ++i) {
    INFO("bone " << i);
    const Eigen::RowVector3d a = rig.skeleton.joints.row(rig.skeleton.bones[i].a);
    const Eigen::RowVector3d b = rig.skeleton.joints.row(rig.skeleton.bones[i].b);
    double last = -1;
    for (int k = 0; k <= 9; ++k) {
      const Eigen::RowVector3d p = a + (b - a) * (k / 9.0);
      Eigen::Index v = 0;
      (vol.tets.V.rowwise() - p).rowwise().squaredNorm().minCoeff(&v);
      if (k == 0) CHECK(E(v, i) < 1e-6);
      if (k == 9) CHECK(E(v, i) > 1 - 1e-6);
      CHECK(E(v, i) >= last - 1e-9);
      last = E(v, i);
    }
  }
}

}  // namespace

TEST_CASE("endpoint weights: Eq. 6.7 from joint weights, clamped to [0, 1]", "[bind][stbs]") {
  const Rig rig = two_bones();
  Eigen::MatrixXd J(3, 3);
  J << 1, 0, 0,  // at joint 0
      0.2, 0.5, 0.3,   // somewhere in between
      0, 0, 1;         // at joint 2
  const Eigen::MatrixXd E = endpoint_weights_from_joints(rig.skeleton, J);
  REQUIRE(E.rows() == 3);
  REQUIRE(E.cols() == 2);
  CHECK(E(0, 0) == 0.0);                         // (1 - 1 + 0) / 2
  CHECK(E(1, 0) == Approx(0.5 * (0.8 + 0.5)));  // (1 - j_0 + j_1) / 2
  CHECK(E(1, 1) == Approx(0.5 * (0.5 + 0.3)));  // (1 - j_1 + j_2) / 2
  CHECK(E(2, 1) == 1.0);
}

TEST_CASE("endpoint weights: a bone's samples split between its joints by where they lie on it", "[bind][stbs]") {
  const Rig rig = two_bones();
  BindVolume vol;
  Rig with_point = rig;  // a point handle first: its column comes before the bones'
  with_point.points.push_back({Eigen::Vector3d(5, 5, 5), "p"});
  vol.tets.V.resize(6, 3);
  vol.tets.V << 0, 0, 0, 0.5, 0, 0, 2, 0, 0, 2, 0.25, 0, 9, 9, 9, 5, 5, 5;
  vol.b.resize(6);
  vol.b << 0, 1, 2, 3, 4, 5;
  vol.bc = Eigen::MatrixXd::Zero(6, 3);
  vol.bc.col(1) << 1, 1, 0.5, 0, 0.5, 0;  // the shared joint split between the bones; row 4 half the point's
  vol.bc.col(2) << 0, 0, 0.5, 1, 0, 0;
  vol.bc.col(0) << 0, 0, 0, 0, 0.5, 1;
  const JointConstraints c = joint_constraints(vol, with_point);
  REQUIRE(c.b.size() == 4);  // the point's rows are left free
  Eigen::MatrixXd want(4, 3);
  want << 1, 0, 0, 0.75, 0.25, 0, 0, 1, 0, 0, 0.75, 0.25;
  CHECK((c.bc - want).cwiseAbs().maxCoeff() < 1e-15);
  CHECK(c.b == Eigen::Vector4i(0, 1, 2, 3));
}

TEST_CASE("endpoint weights from the bind: the arm and the hand, along each bone; STBS at rest is LBS", "[bind][stbs][data]") {
  DFM_DATA_OR_SKIP(arm, "arm.obj");
  DFM_DATA_OR_SKIP(arm_tgf, "arm.tgf");
  DFM_DATA_OR_SKIP(hand, "hand.mesh");
  DFM_DATA_OR_SKIP(hand_tgf, "hand.tgf");
  for (const auto& [mesh, tgf] : {std::pair{arm, arm_tgf}, std::pair{hand, hand_tgf}}) {
    INFO(mesh);
    Rig rig;
    add_tgf_to_rig(rig, read_tgf(tgf), tgf);
    const bool tets = is_tet_mesh_path(mesh);
    const TriMesh surface = tets ? TriMesh{} : read_surface(mesh);
    const BindResult r = tets ? bind_tet_mesh(read_tet_mesh(mesh), rig) : bind_surface(surface, rig);
    REQUIRE(r.endpoint_weights.rows() == r.weights.rows());
    REQUIRE(r.endpoint_weights.cols() == rig.skeleton.num_bones());
    CHECK(r.endpoint_weights.minCoeff() >= 0);
    CHECK(r.endpoint_weights.maxCoeff() <= 1);
    CHECK(r.report.endpoint_seconds > 0);
    check_along_bones(r.volume, rig, bind_endpoint_weights(r.volume, rig, {}));
    // Zero twist, unit stretch: STBS with these endpoint weights is LBS, bit for bit.
    const Eigen::MatrixXd V = tets ? r.volume.tets.V : surface.V;
    const Eigen::MatrixXd& W = tets ? r.tet_weights : r.weights;
    const Eigen::MatrixXd E = tets ? bind_endpoint_weights(r.volume, rig, {}) : r.endpoint_weights;
    const SkinBinding b = make_skin_binding(V, Eigen::MatrixXd(), W, rig, 0, E);
    PoseParams p = rest_pose_params(rig);
    for (auto& q : p.bone_rotation) q = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, 1, 0.4).normalized()));
    const Pose pose = evaluate_pose(rig, p);
    CHECK(skin(SkinMethod::STBS, b, pose, stbs_handles(rig, p.bone_twist_stretch)).V == skin(SkinMethod::LBS, b, pose).V);
  }
}
