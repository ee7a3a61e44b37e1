// The default scene in assets/: a closed, manifold, outward character with every handle inside it,
// small enough to commit, and exactly what tools/make_default_scene.cpp generates.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <unistd.h>

#include <Eigen/Geometry>

#include "core/anim/bake.h"
#include "core/mesh/io.h"
#include "core/mesh/mesh_info.h"
#include "core/scene/document.h"
#include "core/scene/key_surfaces.h"
#include "core/scene/script.h"

using namespace dfm;
namespace fs = std::filesystem;

namespace {
const std::string kAssets = DFM_ASSETS_DIR;

// Generalized winding number by summing signed solid angles (Van Oosterom & Strackee), brute force:
// ~1 inside a closed outward surface, ~0 outside. Independent of the bind module's BVH version.
double winding_number(const TriMesh& m, const Eigen::Vector3d& p) {
  double sum = 0;
  for (int f = 0; f < m.num_faces(); ++f) {
    const Eigen::Vector3d a = m.V.row(m.F(f, 0)).transpose() - p, b = m.V.row(m.F(f, 1)).transpose() - p,
                          c = m.V.row(m.F(f, 2)).transpose() - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double num = a.dot(b.cross(c));
    const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    sum += 2 * std::atan2(num, den);
  }
  return sum / (4 * M_PI);
}

// Distance from p to the nearest surface vertex (a cheap lower bound on clearance is not needed; this
// only guards against handles grazing the skin).
double nearest_vertex(const TriMesh& m, const Eigen::Vector3d& p) {
  return (m.V.rowwise() - p.transpose()).rowwise().norm().minCoeff();
}

void require_inside(const TriMesh& m, const Eigen::Vector3d& p, const std::string& what) {
  INFO(what << " at " << p.transpose());
  CHECK(winding_number(m, p) > 0.99);
  CHECK(nearest_vertex(m, p) > 0.02);
}
}  // namespace

TEST_CASE("the default scene is a closed, manifold, outward character of a few thousand vertices") {
  Document d;
  d.load_scene(kAssets + "/default.scene.json");
  const TriMesh& m = d.surface();
  CHECK(m.num_vertices() >= 3000);
  CHECK(m.num_vertices() <= 8000);
  CHECK(is_closed(m.F));
  CHECK(boundary_edge_count(m.F) == 0);
  CHECK(non_manifold_edge_count(m.F) == 0);
  CHECK(inconsistent_edge_count(m.F) == 0);
  CHECK(connected_component_count(m.F) == 1);
  CHECK(unreferenced_vertex_count(m.num_vertices(), m.F) == 0);
  CHECK(degenerate_face_count(m.V, m.F, 1e-10) == 0);
  CHECK(duplicate_vertex_count(m.V, 1e-6) == 0);
  CHECK(signed_volume(m.V, m.F) > 0.5);
  // Euler characteristic of a sphere: V - E + F = 2 (E = 3F/2 on a closed surface).
  CHECK(m.num_vertices() - 3 * m.num_faces() / 2 + m.num_faces() == 2);
  // The plain mesh file holds the same surface.
  const TriMesh obj = read_surface(kAssets + "/default.obj");
  REQUIRE(obj.num_vertices() == m.num_vertices());
  CHECK(obj.F == m.F);
  CHECK((obj.V - m.V).cwiseAbs().maxCoeff() < 1e-5);
}

TEST_CASE("the default rig shows every handle type, all inside the character") {
  Document d;
  d.load_scene(kAssets + "/default.scene.json");
  const Rig& rig = d.rig();
  const TriMesh& m = d.surface();
  CHECK(rig.points.size() >= 2);
  CHECK(rig.skeleton.num_bones() >= 3);
  REQUIRE(rig.cages.size() == 1);
  CHECK(boundary_edge_count(rig.cages[0].mesh.F) > 0);  // a partial (open) cage
  for (const PointHandle& p : rig.points) require_inside(m, p.position, "point " + p.name);
  for (const Bone& b : rig.skeleton.bones)
    for (double t = 0; t <= 1.0; t += 0.125) {
      const Eigen::Vector3d p = (1 - t) * rig.skeleton.joints.row(b.a).transpose() + t * rig.skeleton.joints.row(b.b).transpose();
      require_inside(m, p, "bone " + b.name);
    }
  const TriMesh& cage = rig.cages[0].mesh;
  for (int v = 0; v < cage.num_vertices(); ++v) require_inside(m, cage.V.row(v).transpose(), "cage vertex");
  for (int f = 0; f < cage.num_faces(); ++f)
    require_inside(m, (cage.V.row(cage.F(f, 0)) + cage.V.row(cage.F(f, 1)) + cage.V.row(cage.F(f, 2))).transpose() / 3.0,
                   "cage face");
  // Handles must not touch each other (a bind needs disjoint boundary conditions).
  for (const PointHandle& p : rig.points)
    for (int v = 0; v < cage.num_vertices(); ++v) CHECK((p.position - cage.V.row(v).transpose()).norm() > 0.05);
  // The tgf and cage files hold the same rig.
  const TgfData tgf = read_tgf(kAssets + "/default.tgf");
  CHECK(tgf.edges.rows() == rig.skeleton.num_bones());
  CHECK(read_surface(kAssets + "/default-cage.obj").num_vertices() == cage.num_vertices());
}

TEST_CASE("the committed default scene is small and is what the generator makes") {
  std::uintmax_t total = 0;
  for (const auto& e : fs::directory_iterator(kAssets))
    if (e.path().filename().string().rfind("default", 0) == 0) total += e.file_size();
  CHECK(total < 1024 * 1024);

  const fs::path tmp = fs::temp_directory_path() / ("dfm_default_scene_" + std::to_string(::getpid()));
  const std::string cmd = std::string("\"") + DFM_MAKE_DEFAULT_SCENE + "\" \"" + tmp.string() + "\" > /dev/null";
  REQUIRE(std::system(cmd.c_str()) == 0);
  Document fresh, committed;
  fresh.load_scene((tmp / "default.scene.json").string());
  committed.load_scene(kAssets + "/default.scene.json");
  fs::remove_all(tmp);
  REQUIRE(fresh.surface().num_vertices() == committed.surface().num_vertices());
  CHECK(fresh.surface().F == committed.surface().F);
  CHECK((fresh.surface().V - committed.surface().V).cwiseAbs().maxCoeff() < 1e-9);
  CHECK(fresh.num_handles() == committed.num_handles());
  CHECK(fresh.rig().skeleton.joints == committed.rig().skeleton.joints);
}

TEST_CASE("the default scene binds, and a scripted animation slice at a key equals hand-computed LBS") {
  Document d;
  d.load_scene(kAssets + "/default.scene.json");
  const fs::path tmp = fs::temp_directory_path() / ("dfm_default_bind_" + std::to_string(::getpid()));
  fs::create_directories(tmp);
  const std::string out = (tmp / "mid.obj").string();
  // Handles: 0,1 ears, 2 belly (points), 3.. bones (3 = spine, 5 = left upper arm).
  run_script(d,
             parse_script("bind\n"
                          "set-key 0\n"
                          "select 5\nrotate 45 0 0 1\n"
                          "select 0\ntranslate 0 0.1 0\n"
                          "set-key 1\n"
                          "select 3\nrotate -20 0 0 1\n"
                          "set-key 2\n"
                          "set-time 1\n"
                          "save-posed " + out + "\n",
                          "acceptance.txt"),
             "acceptance.txt");
  REQUIRE(d.has_weights());
  const Eigen::MatrixXd& W = d.weights();
  CHECK((W.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-6);
  CHECK(W.minCoeff() > -1e-6);
  REQUIRE(d.keys().size() == 3);
  // LBS by hand with the middle key's pose (t = 1 is a layer: the slice is that layer exactly).
  const Pose pose = d.key_poses()[1];
  const TriMesh& rest = d.surface();
  Eigen::MatrixXd expect = Eigen::MatrixXd::Zero(rest.num_vertices(), 3);
  for (int i = 0; i < rest.num_vertices(); ++i)
    for (int j = 0; j < pose.size(); ++j)
      expect.row(i) += W(i, j) * (pose.transforms[j] * Eigen::Vector3d(rest.V.row(i).transpose())).transpose();
  const TriMesh got = read_surface(out);
  fs::remove_all(tmp);
  REQUIRE(got.num_vertices() == rest.num_vertices());
  CHECK((got.V - expect).cwiseAbs().maxCoeff() < 1e-5);
  // The pose actually moved the mesh.
  CHECK((expect - rest.V).cwiseAbs().maxCoeff() > 0.05);
}

// Issue 38 (1): between keys of one connectivity a saved frame is the artist's mesh, not the prisms'
// exact slice (which splits every triangle into four): the teddy's vertices in its order, each where
// t crosses its own time edge, with its triangles.
TEST_CASE("frames between pose keys are the teddy's mesh: save-posed, save-frames, the CLI's sequence") {
  Document d;
  d.load_scene(kAssets + "/default.scene.json");
  const fs::path tmp = fs::temp_directory_path() / ("dfm_default_frames_" + std::to_string(::getpid()));
  fs::create_directories(tmp);
  const std::string mid = (tmp / "mid.obj").string(), prefix = (tmp / "f").string();
  run_script(d,
             parse_script("bind\nset-key 0\nselect 5\nrotate 45 0 0 1\nset-key 1\nset-time 0.5\nsave-posed " + mid +
                              "\nsave-frames " + prefix + " 5\n",
                          "frames.txt"),
             "frames.txt");
  const TriMesh& rest = d.surface();
  REQUIRE(rest.num_vertices() == 4720);
  REQUIRE(rest.num_faces() == 9436);
  REQUIRE(d.method() == SkinMethod::LBS);
  const TriMesh got = read_surface(mid);
  REQUIRE(got.num_vertices() == rest.num_vertices());
  REQUIRE(got.F == rest.F);

  // The reference: the two baked layers around t = 0.5, and each vertex on the straight segment
  // between its two copies at the fraction the time gives. At time t the upper arm and what hangs from
  // it have turned 45 t degrees about z through the arm's first joint (the keys' bone rotation
  // interpolated in its own frame), everything else is at rest; skinned by LBS written out here.
  std::vector<double> layer_times = bake_times(pose_key_track(d), d.inbetweens());
  const auto hi = std::upper_bound(layer_times.begin(), layer_times.end(), 0.5);
  REQUIRE(hi != layer_times.begin());
  REQUIRE(hi != layer_times.end());
  const double t0 = *(hi - 1), t1 = *hi;
  REQUIRE(t0 < 0.5);
  const Eigen::MatrixXd& W = d.weights();
  const Skeleton& sk = d.rig().skeleton;
  const int np = static_cast<int>(d.rig().points.size()), arm = 5 - np;
  REQUIRE(sk.bones[arm].name == "l_upper_arm");
  const Eigen::Vector3d shoulder = sk.joints.row(sk.bones[arm].a).transpose();
  auto turns = [&](int bone) {
    for (int b = bone; b >= 0; b = sk.bones[b].parent)
      if (b == arm) return true;
    return false;
  };
  auto lbs = [&](double t) {
    const Eigen::Affine3d R = Eigen::Translation3d(shoulder) *
                              Eigen::AngleAxisd(t * M_PI / 4, Eigen::Vector3d::UnitZ()) * Eigen::Translation3d(-shoulder);
    Eigen::MatrixXd P = Eigen::MatrixXd::Zero(rest.num_vertices(), 3);
    for (int i = 0; i < rest.num_vertices(); ++i)
      for (int j = 0; j < W.cols(); ++j) {
        const bool turned = j >= np && j - np < sk.num_bones() && turns(j - np);
        const Eigen::Vector3d v = rest.V.row(i).transpose();
        P.row(i) += W(i, j) * (turned ? Eigen::Vector3d(R * v) : v).transpose();
      }
    return P;
  };
  const Eigen::MatrixXd P0 = lbs(t0), P1 = lbs(t1);
  const double u = (0.5 - t0) / (t1 - t0);
  const Eigen::MatrixXd expect = P0 + u * (P1 - P0);
  // Within rounding (the skinning here sums in another order than the bake's).
  CHECK((got.V - expect).cwiseAbs().maxCoeff() < 1e-12);
  // The frame moved: the arm is between its keys, not at either.
  CHECK((got.V - P0).cwiseAbs().maxCoeff() > 1e-3);

  // Every frame of the sequence is the teddy's mesh: at t = 0 the rest pose, at 1 the posed key.
  for (int i = 0; i < 5; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "f%04d.obj", i);
    const TriMesh f = read_surface((tmp / name).string());
    CHECK(f.num_vertices() == 4720);
    CHECK(f.F == rest.F);
    if (i == 0) CHECK((f.V - lbs(0.0)).cwiseAbs().maxCoeff() < 1e-9);
    if (i == 4) CHECK((f.V - lbs(1.0)).cwiseAbs().maxCoeff() < 1e-9);
  }
  fs::remove_all(tmp);
}
