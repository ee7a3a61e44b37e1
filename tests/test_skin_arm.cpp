// The candy-wrapper test on ../shared/data/arm.obj: twist the forearm bone 180 degrees about its
// axis and measure how much volume is left around the elbow under LBS, DQS and STBS.
#include <cstdio>
#include <cstdlib>

#include <catch2/catch.hpp>

#include "core/mesh/io.h"
#include "core/rig/pose_params.h"
#include "core/rig/rig_io.h"
#include "core/skin/skin.h"
#include "tests/skin_test_weights.h"
#include "tests/test_support.h"

using namespace dfm;
using Eigen::Vector3d;

// Area of the closed mesh's cross-section by the plane through c with unit normal u, counting only
// the part within `radius` of c. Divergence theorem in the plane: area = sum over section segments of
// |segment| * ((midpoint - c) . outward in-plane normal) / 2, the outward normal being the projected
// triangle normal (so this needs a consistently outward-oriented mesh, not a closed section polygon).
static double section_area(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Vector3d& c, const Vector3d& u,
                           double radius) {
  double area = 0;
  for (int f = 0; f < F.rows(); ++f) {
    Vector3d p[3];
    double d[3];
    for (int j = 0; j < 3; ++j) {
      p[j] = V.row(F(f, j)).transpose();
      d[j] = (p[j] - c).dot(u);
    }
    Vector3d pts[2];
    int n = 0;
    for (int j = 0; j < 3 && n < 2; ++j) {
      const int k = (j + 1) % 3;
      if ((d[j] < 0) != (d[k] < 0)) pts[n++] = p[j] + (d[j] / (d[j] - d[k])) * (p[k] - p[j]);
    }
    if (n != 2) continue;
    const Vector3d m = 0.5 * (pts[0] + pts[1]);
    if ((m - c).norm() > radius) continue;
    Vector3d nf = (p[1] - p[0]).cross(p[2] - p[0]);
    nf -= nf.dot(u) * u;
    if (nf.norm() == 0) continue;
    area += 0.5 * (pts[1] - pts[0]).norm() * (m - c).dot(nf.normalized());
  }
  return area;
}

// Volume of the slab |(x - c) . u| <= half_width near c, by the midpoint rule over sections.
static double slab_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Vector3d& c, const Vector3d& u,
                          double half_width, double radius) {
  const int slices = 60;
  const double h = 2 * half_width / slices;
  double vol = 0;
  for (int s = 0; s < slices; ++s) vol += h * section_area(V, F, c + (-half_width + (s + 0.5) * h) * u, u, radius);
  return vol;
}

static double mesh_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  double v = 0;
  for (int f = 0; f < F.rows(); ++f)
    v += Vector3d(V.row(F(f, 0))).dot(Vector3d(V.row(F(f, 1))).cross(Vector3d(V.row(F(f, 2))))) / 6.0;
  return v;
}

TEST_CASE("section_area: a unit cube's cross-section is 1", "[skin][arm]") {
  Eigen::MatrixXd V(8, 3);
  V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  Eigen::MatrixXi F(12, 3);
  F << 0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7;
  REQUIRE(mesh_volume(V, F) == Approx(1.0));
  REQUIRE(section_area(V, F, Vector3d(0.5, 0.5, 0.3), Vector3d(0, 0, 1), 10) == Approx(1.0));
  REQUIRE(section_area(V, F, Vector3d(0.5, 0.5, 0.3), Vector3d(1, 0, 1).normalized(), 10) ==
          Approx(0.8 * std::sqrt(2.0)));  // the plane x + z = 0.8 cuts a 0.8*sqrt(2) x 1 rectangle
  REQUIRE(slab_volume(V, F, Vector3d(0.5, 0.5, 0.5), Vector3d(0, 1, 0), 0.25, 10) == Approx(0.5));
}

TEST_CASE("arm twisted 180 degrees: DQS and STBS keep the elbow's volume, LBS collapses it", "[skin][arm][data]") {
  DFM_DATA_OR_SKIP(obj, "arm.obj");
  DFM_DATA_OR_SKIP(tgf, "arm.tgf");
  const TriMesh mesh = read_surface(obj);
  Rig rig;
  add_tgf_to_rig(rig, read_tgf(tgf), tgf);
  REQUIRE(rig.skeleton.num_bones() == 4);
  // Smooth test weights by default; DFM_ARM_WEIGHTS=W.dmat (e.g. from `deform bind arm.obj --skeleton
  // arm.tgf`) measures real BBW weights instead.
  const char* wfile = std::getenv("DFM_ARM_WEIGHTS");
  const Eigen::MatrixXd W = wfile ? read_dmat(wfile) : test::inverse_distance_bone_weights(mesh.V, rig);
  std::printf("arm weights: %s\n", wfile ? wfile : "inverse-distance test weights");
  const SkinBinding b = make_skin_binding(mesh.V, Eigen::MatrixXd(), W, rig, 0);

  // Twist the forearm (bone 2: elbow -> wrist) by 180 degrees about its own axis.
  const int forearm = 2;
  PoseParams params = rest_pose_params(rig);
  params.bone_twist_stretch[forearm].twist = 3.14159265358979323846;
  const Pose pose = evaluate_pose(rig, params);
  const auto stbs = stbs_handles(rig, params.bone_twist_stretch);

  const Bone& fb = rig.skeleton.bones[forearm];
  const Vector3d elbow = rig.skeleton.joints.row(fb.a).transpose();
  const Vector3d wrist = rig.skeleton.joints.row(fb.b).transpose();
  const Vector3d axis = (wrist - elbow).normalized();
  const double half = 0.2 * (wrist - elbow).norm(), radius = 0.5 * (wrist - elbow).norm();
  const double rest = slab_volume(mesh.V, mesh.F, elbow, axis, half, radius);
  REQUIRE(rest > 0);
  const double full_rest = mesh_volume(mesh.V, mesh.F);
  double ratio[3];
  for (SkinMethod m : {SkinMethod::LBS, SkinMethod::DQS, SkinMethod::STBS}) {
    const Eigen::MatrixXd U = skin(m, b, pose, stbs).V;
    ratio[static_cast<int>(m)] = slab_volume(U, mesh.F, elbow, axis, half, radius) / rest;
    std::printf("arm twist 180: %-4s elbow-region volume ratio %.3f, whole-mesh volume ratio %.3f\n",
                skin_method_name(m), ratio[static_cast<int>(m)], mesh_volume(U, mesh.F) / full_rest);
  }
  CHECK(ratio[0] < 0.6);   // LBS: the candy wrapper
  CHECK(ratio[1] >= 0.8);  // DQS
  CHECK(ratio[2] >= 0.8);  // STBS
}
