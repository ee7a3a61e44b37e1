#pragma once
// The fixed scene the scene-file fuzzer mutates: one small SceneData using every part of the format
// (surface, tets, points, pseudo-edge, bones, cage, region, weights, mask, pose, keys). Its sidecar
// (x.scene.bin) is written once and kept fixed; the fuzzer mutates the JSON only, so array refs
// (offset/rows/cols/type) are fuzzed against real bytes. The seeds in tests/fuzz/corpus/scene/ are
// this scene's JSON (and variants); test_io_scene replays them with the same sidecar.
// Built from plain data (no Document) so the fuzzer links without the bind module.
#include <string>

#include "core/rig/pose_params.h"
#include "core/scene/document.h"
#include "core/scene/scene_file.h"

namespace dfm::fuzz {

inline SceneData fixed_scene() {
  SceneData s;
  s.surface.V.resize(6, 3);
  s.surface.V << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
  s.surface.F.resize(8, 3);
  s.surface.F << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  s.surface_path = "octa.obj";
  s.tets.V = s.surface.V;
  s.tets.T.resize(1, 4);
  s.tets.T << 0, 2, 4, 5;
  s.tets.F.resize(1, 3);
  s.tets.F << 0, 2, 4;
  s.surface_to_tet = Eigen::VectorXi::LinSpaced(6, 0, 5);
  s.rig.points.push_back({Eigen::Vector3d(0.1, 0.2, 0.3), "ear"});
  s.rig.points.push_back({Eigen::Vector3d(-0.1, 0.0, 0.1), "belly"});
  s.rig.pseudo_edges.push_back({0, 1});
  s.rig.skeleton.joints.resize(3, 3);
  s.rig.skeleton.joints << 0, -0.5, 0, 0, 0, 0, 0, 0.5, 0.1;
  s.rig.skeleton.bones.push_back({0, 1, -1, "b0"});
  s.rig.skeleton.bones.push_back({1, 2, -1, "b1"});
  compute_bone_parents(s.rig.skeleton);
  Cage c;
  c.name = "cage";
  c.mesh.V = 0.2 * s.surface.V;
  c.mesh.F = s.surface.F.topRows(4);
  c.edges.resize(1, 2);
  c.edges << 0, 5;
  s.rig.cages.push_back(c);
  s.rig.regions.push_back({{1, 4}, "cheek"});
  const int nh = num_handles(s.rig);
  s.weights = Eigen::MatrixXd::Constant(6, nh, 1.0 / nh);
  s.mask = Eigen::VectorXd::LinSpaced(6, 0, 1);
  s.pose = rest_pose_params(s.rig);
  s.pose.bone_rotation[1] = Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()));
  SceneKey k0{0.0, s.pose}, k1{1.5, rest_pose_params(s.rig)};
  s.keys = {k0, k1};
  s.bind_stats.notes = {"fixture"};
  s.selection.handles = {0, 2};
  s.selection.joint = 1;
  return s;
}

}  // namespace dfm::fuzz
