#include "core/export/gltf_scene_import.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "core/export/gltf_import.h"
#include "core/export/gltf_rig_extras.h"
#include "core/export/rig_import.h"
#include "core/rig/pose_params.h"
#include "core/scene/scene_import.h"
#include "core/util/error.h"

namespace dfm {

namespace {

// The skin's joints name nodes that exist, once each, each with an inverse bind matrix, and no node's
// ancestry loops.
void check_skin(const GltfDocument& g, const std::string& path) {
  const int nn = static_cast<int>(g.nodes.size());
  if (g.inverse_bind.size() != g.joints.size()) throw file_error(path, 0, "the skin's inverse bind matrices do not match its joints");
  std::vector<char> used(nn, 0);
  for (int n : g.joints) {
    if (n < 0 || n >= nn) throw file_error(path, 0, "a skin joint names node " + std::to_string(n) + ", which does not exist");
    if (used[n]++) throw file_error(path, 0, "node " + std::to_string(n) + " is a joint twice");
  }
  for (int i = 0; i < nn; ++i) {
    int steps = 0;
    for (int n = g.nodes[i].parent; n >= 0; n = g.nodes[n].parent)
      if (n >= nn || ++steps > nn) throw file_error(path, 0, "the node hierarchy has a loop or a bad parent");
  }
}

// Per joint, the nearest ancestor node that is a joint (its index in the skin), or -1.
std::vector<int> parent_joints(const GltfDocument& g) {
  std::map<int, int> joint_of;
  for (size_t j = 0; j < g.joints.size(); ++j) joint_of[g.joints[j]] = static_cast<int>(j);
  std::vector<int> parent(g.joints.size(), -1);
  for (size_t j = 0; j < g.joints.size(); ++j)
    for (int n = g.nodes[g.joints[j]].parent; n >= 0; n = g.nodes[n].parent)
      if (joint_of.count(n)) {
        parent[j] = joint_of[n];
        break;
      }
  return parent;
}

// Per joint its joint matrix G_j(t) IB_j at time t.
std::vector<Eigen::Affine3d> joint_matrices(const GltfDocument& g, double t) {
  const std::vector<Eigen::Matrix4d> G = gltf_global_transforms(gltf_animated_nodes(g, t));
  std::vector<Eigen::Affine3d> T(g.joints.size());
  for (size_t j = 0; j < g.joints.size(); ++j) T[j].matrix() = G[g.joints[j]] * g.inverse_bind[j];
  return T;
}

// This program's rig, from the extras its export writes on the skin's root joints' parent
// (gltf_rig_extras.h), when it has one handle per joint; else none (bones are made from the joints).
std::optional<Rig> extras_rig(const GltfDocument& g, int surface_vertices, const std::string& path) {
  for (int j : g.joints) {
    const int p = g.nodes[j].parent;
    if (p < 0 || g.nodes[p].deform_rig.empty()) continue;
    Rig rig = rig_from_extras_json(g.nodes[p].deform_rig, surface_vertices, path);
    if (num_handles(rig) != static_cast<int>(g.joints.size())) return std::nullopt;
    return rig;
  }
  return std::nullopt;
}

bool is_rotation(const Eigen::Matrix3d& L) {
  return (L.transpose() * L - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-6 && L.determinant() > 0;
}

// The key's parameters for every kind of handle of an extras rig, from the joint matrices A (one per
// handle, rig.h order): bones by forward kinematics (key_params), points by a translation and turn about
// the point, cage vertices by a translation, regions by their affine; a transform those fields cannot
// hold (a point that scales, a cage vertex that turns) as the handle's solved transform, which replaces
// them.
PoseParams extras_key_params(const Rig& rig, const std::vector<Eigen::Affine3d>& A, const std::string& path, double t) {
  const int np = num_point_handles(rig), nb = rig.skeleton.num_bones();
  PoseParams p = key_params(rig, std::vector<Eigen::Affine3d>(A.begin() + np, A.begin() + np + nb), path, t);
  for (int h = 0; h < static_cast<int>(A.size()); ++h) {
    const HandleRef r = handle_ref(rig, h);
    if (r.kind == HandleKind::Bone) continue;
    const Eigen::Matrix3d L = A[h].linear();
    if (r.kind == HandleKind::Region) {
      p.region_transform[r.index] = A[h];
    } else if (r.kind == HandleKind::Point && is_rotation(L)) {
      const Eigen::Vector3d x = rig.points[r.index].position;
      p.point_translation[r.index] = A[h] * x - x;
      p.point_rotation[r.index] = Eigen::Quaterniond(L).normalized();
    } else if (r.kind == HandleKind::CageVertex && (L - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-6) {
      int first = 0;
      for (int c = 0; c < r.cage; ++c) first += static_cast<int>(rig.cages[c].mesh.V.rows());
      p.cage_translation[first + r.index] = A[h].translation();
    } else {
      p.solved[h] = A[h];
    }
  }
  return p;
}

}  // namespace

SceneData import_gltf_scene(const std::string& path, GltfImportReport* report) {
  const GltfDocument g = read_gltf(path);
  if (g.skinned_node < 0 || g.joints.empty()) throw file_error(path, 0, "no skinned mesh (a node with a mesh and a skin)");
  check_skin(g, path);
  GltfImportReport r;
  if (g.morph_node >= 0 || !g.skinned.targets.empty()) r.skipped.push_back("morph targets (shape keys)");
  const WeldedMesh w = weld_by_position(g.skinned.V, g.skinned.F);
  r.file_vertices = static_cast<int>(g.skinned.V.rows());
  const int n = static_cast<int>(g.joints.size());
  const std::vector<int> parent = parent_joints(g);
  std::vector<ImportJoint> joints(n);
  for (int j = 0; j < n; ++j) {
    const Eigen::Matrix4d& IB = g.inverse_bind[j];
    if (!IB.allFinite() || !(std::abs(IB.topLeftCorner<3, 3>().determinant()) > 1e-12))
      throw file_error(path, 0, "joint " + std::to_string(j) + "'s inverse bind matrix is singular");
    joints[j].bind.matrix() = IB.inverse();
    joints[j].parent = parent[j];
    joints[j].name = g.nodes[g.joints[j]].name;
    const std::string ours = std::to_string(j) + ":";  // this program's export numbers its joints so
    if (joints[j].name.size() > ours.size() && joints[j].name.compare(0, ours.size(), ours) == 0) joints[j].name.erase(0, ours.size());
  }
  std::vector<Influence> influences;
  for (Eigen::Index v = 0; v < g.skinned.V.rows(); ++v)
    for (Eigen::Index c = 0; c < g.skinned.joints.cols(); ++c)
      influences.push_back({static_cast<int>(v), g.skinned.joints(v, c), g.skinned.weights(v, c)});
  SceneData s = imported_scene(w, joints, welded_weights(influences, w, n, path, &r.influences), path, &r);
  const std::optional<Rig> ours = extras_rig(g, static_cast<int>(s.surface.V.rows()), path);
  if (ours) {  // this program's export: its own handles back, in the joints' (= handles') order
    s.rig = *ours;
    s.pose = rest_pose_params(s.rig);
    r.rig_from_extras = true;
  }
  for (double t : g.key_times()) {
    SceneKey k;
    k.time = t;
    k.params = ours ? extras_key_params(s.rig, joint_matrices(g, t), path, t) : key_params(s.rig, joint_matrices(g, t), path, t);
    s.keys.push_back(std::move(k));
  }
  finish_import(s, path, &r);
  if (report) *report = r;
  return s;
}

void register_gltf_scene_importer() {
  const SceneImporter import = [](const std::string& path, std::string& report) {
    GltfImportReport r;
    SceneData s = import_gltf_scene(path, &r);
    report = r.text();
    return s;
  };
  register_scene_importer("glb", import);
  register_scene_importer("gltf", import);
}

}  // namespace dfm
