#include "core/export/assimp_scene_import.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/export/assimp_read.h"
#include "core/export/bvh_motion.h"
#include "core/scene/scene_import.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace dfm {

namespace {

// FBX's GlobalSettings as a linear map into y up, z front, x right, in metres; identity scale if the
// file names no unit (Assimp then gives none either).
Eigen::Affine3d fbx_frame(const aiScene* sc, const std::string& path) {
  int up = 1, up_sign = 1, front = 2, front_sign = 1, coord = 0, coord_sign = 1;
  float unit = 100;  // centimetres per unit; 100: metres already
  if (const aiMetadata* md = sc->mMetaData) {
    md->Get("UpAxis", up), md->Get("UpAxisSign", up_sign), md->Get("FrontAxis", front), md->Get("FrontAxisSign", front_sign);
    md->Get("CoordAxis", coord), md->Get("CoordAxisSign", coord_sign), md->Get("UnitScaleFactor", unit);
  }
  const bool axes_ok = up >= 0 && up < 3 && front >= 0 && front < 3 && coord >= 0 && coord < 3 && up != front &&
                       up != coord && front != coord && std::abs(up_sign) == 1 && std::abs(front_sign) == 1 &&
                       std::abs(coord_sign) == 1;
  if (!axes_ok) throw file_error(path, 0, "its GlobalSettings name no usable axes");
  if (!(std::isfinite(unit) && unit > 0)) throw file_error(path, 0, "its UnitScaleFactor is not a positive number");
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();  // rows: the file's right, up and front axes
  M(0, coord) = coord_sign;
  M(1, up) = up_sign;
  M(2, front) = front_sign;
  Eigen::Affine3d C = Eigen::Affine3d::Identity();
  C.linear() = (unit / 100.0) * M;
  return C;
}

struct SkinnedMesh {
  const aiMesh* mesh;
};

// Each mesh with bones that a node shows, once; the count of meshes without bones.
std::vector<SkinnedMesh> skinned_meshes(const aiScene* sc, const AssimpNodes& nodes, int* unskinned) {
  std::vector<SkinnedMesh> out;
  std::vector<char> seen(sc->mNumMeshes, 0);
  *unskinned = 0;
  for (size_t i = 0; i < nodes.node.size(); ++i)
    for (unsigned k = 0; k < nodes.node[i]->mNumMeshes; ++k) {
      const unsigned m = nodes.node[i]->mMeshes[k];
      if (m >= sc->mNumMeshes || seen[m]++) continue;
      if (sc->mMeshes[m]->mNumBones > 0) out.push_back({sc->mMeshes[m]});
      else ++*unskinned;
    }
  return out;
}

}  // namespace

SceneData import_assimp_scene(const std::string& path, RigImportReport* report) {
  const std::string ext = file_extension(path);
  if (ext != "fbx" && ext != "dae") throw Error(path + ": not an FBX (.fbx) or Collada (.dae) file");
  const AssimpFile f = read_with_assimp(path, ext == "fbx" ? "Autodesk FBX" : "Collada");
  const aiScene* sc = f.scene;
  const AssimpNodes nodes = node_table(sc);
  const Eigen::Affine3d C = ext == "fbx" ? fbx_frame(sc, path) : Eigen::Affine3d::Identity();
  const std::vector<Eigen::Affine3d> rest = global_transforms(nodes, nullptr, 0);
  RigImportReport r;
  int unskinned = 0;
  const std::vector<SkinnedMesh> meshes = skinned_meshes(sc, nodes, &unskinned);
  if (meshes.empty()) throw file_error(path, 0, "no skinned mesh (a mesh with bones)");
  if (unskinned > 0) r.skipped.push_back(std::to_string(unskinned) + " mesh(es) without bones");
  r.meshes = static_cast<int>(meshes.size());

  // Joints: the nodes the bones name, in the tree's order; each one's bind frame from its first bone.
  // A mesh's frame: Assimp skins G_j(t) offset_j v, without the mesh node's transform (which its
  // Collada import sets to the up-axis turn the vertices already have), so the rest pose, G_j offset_j v
  // at the nodes' own transforms, puts the mesh at M = C G_b offset_b for its first bone b.
  std::map<int, Eigen::Affine3d> bind_of;
  std::vector<Eigen::Affine3d> mesh_frame;
  for (const SkinnedMesh& m : meshes)
    for (unsigned b = 0; b < m.mesh->mNumBones; ++b) {
      const aiBone* bone = m.mesh->mBones[b];
      const int node = nodes.find(bone->mName.C_Str());
      if (node < 0) throw file_error(path, 0, std::string("bone '") + bone->mName.C_Str() + "' names no node");
      const Eigen::Affine3d offset = to_affine(bone->mOffsetMatrix);
      if (!offset.matrix().allFinite() || !(std::abs(offset.linear().determinant()) > 1e-12))
        throw file_error(path, 0, std::string("bone '") + bone->mName.C_Str() + "'s offset matrix is singular");
      if (b == 0) mesh_frame.push_back(C * rest[node] * offset);
      bind_of.emplace(node, mesh_frame.back() * offset.inverse());
    }
  std::map<int, int> joint_of;  // node -> joint
  std::vector<int> joint_node;
  for (const auto& [node, bind] : bind_of) {  // map order = the tree's depth-first order
    joint_of[node] = static_cast<int>(joint_node.size());
    joint_node.push_back(node);
  }
  const int n = static_cast<int>(joint_node.size());
  std::vector<ImportJoint> joints(n);
  for (int j = 0; j < n; ++j) {
    const int node = joint_node[j];
    joints[j].name = nodes.node[node]->mName.C_Str();
    joints[j].bind = bind_of[node];
    for (int a = nodes.parent[node]; a >= 0 && joints[j].parent < 0; a = nodes.parent[a])
      if (joint_of.count(a)) joints[j].parent = joint_of[a];
  }
  // A leaf joint's first child node that is no joint: where its bone ends (FBX's *_end), in the bind.
  for (size_t i = 0; i < nodes.node.size(); ++i) {
    const int p = nodes.parent[i];
    if (p < 0 || joint_of.count(static_cast<int>(i)) || !joint_of.count(p)) continue;
    if (nodes.node[i]->mNumMeshes > 0 || nodes.node[i]->mNumChildren > 0) continue;  // an end node is a bare leaf
    ImportJoint& J = joints[joint_of[p]];
    if (!J.end) J.end = J.bind * ((rest[p].inverse() * rest[i]).translation());
  }
  for (int j = 0; j < n; ++j)  // a joint with joint children ends at them (import_skeleton), never at an end node
    if (joints[j].parent >= 0) joints[joints[j].parent].end.reset();

  // The meshes at their nodes in the output frame, one vertex list, and every bone's weights.
  Eigen::Index nv = 0, nf = 0;
  for (const SkinnedMesh& m : meshes) nv += m.mesh->mNumVertices, nf += m.mesh->mNumFaces;
  Eigen::MatrixXd V(nv, 3);
  Eigen::MatrixXi F(nf, 3);
  std::vector<Influence> influences;
  const bool mirrored = C.linear().determinant() < 0;  // a left-handed file: faces turn to stay outward
  Eigen::Index v0 = 0, f_count = 0;
  for (size_t mi = 0; mi < meshes.size(); ++mi) {
    const SkinnedMesh& m = meshes[mi];
    const Eigen::Affine3d& X = mesh_frame[mi];
    for (unsigned v = 0; v < m.mesh->mNumVertices; ++v) {
      const aiVector3D& p = m.mesh->mVertices[v];
      V.row(v0 + v) = (X * Eigen::Vector3d(p.x, p.y, p.z)).transpose();
    }
    for (unsigned k = 0; k < m.mesh->mNumFaces; ++k) {
      const aiFace& face = m.mesh->mFaces[k];
      if (face.mNumIndices != 3) continue;  // points and lines
      for (int c = 0; c < 3; ++c) F(f_count, mirrored ? 2 - c : c) = static_cast<int>(v0 + face.mIndices[c]);
      ++f_count;
    }
    for (unsigned b = 0; b < m.mesh->mNumBones; ++b) {
      const aiBone* bone = m.mesh->mBones[b];
      const int j = joint_of[nodes.find(bone->mName.C_Str())];
      for (unsigned k = 0; k < bone->mNumWeights; ++k) {
        const aiVertexWeight& w = bone->mWeights[k];
        const int vertex = w.mVertexId < m.mesh->mNumVertices ? static_cast<int>(v0 + w.mVertexId) : -1;
        influences.push_back({vertex, j, w.mWeight});
      }
    }
    if (m.mesh->mNumAnimMeshes > 0 && std::find(r.skipped.begin(), r.skipped.end(), "morph targets (shape keys)") == r.skipped.end())
      r.skipped.push_back("morph targets (shape keys)");
    v0 += m.mesh->mNumVertices;
  }
  F.conservativeResize(f_count, 3);
  if (!V.allFinite()) throw file_error(path, 0, "a vertex position is not finite");
  const WeldedMesh w = weld_by_position(V, F);
  r.file_vertices = static_cast<int>(nv);
  SceneData s = imported_scene(w, joints, welded_weights(influences, w, n, path, &r.influences), path, &r);

  if (sc->mNumAnimations > 0) {
    const aiAnimation* anim = sc->mAnimations[0];
    if (sc->mNumAnimations > 1) r.skipped.push_back(std::to_string(sc->mNumAnimations - 1) + " more animation(s)");
    int unnamed = 0;
    for (unsigned c = 0; c < anim->mNumChannels; ++c) unnamed += nodes.find(anim->mChannels[c]->mNodeName.C_Str()) < 0;
    if (unnamed > 0) r.skipped.push_back(std::to_string(unnamed) + " animation channel(s) naming no node");
    const double tps = ticks_per_second(anim);
    std::vector<Eigen::Affine3d> bind_inverse(n);
    for (int j = 0; j < n; ++j) bind_inverse[j] = joints[j].bind.inverse();
    for (double ticks : key_ticks(anim)) {
      const std::vector<Eigen::Affine3d> G = global_transforms(nodes, anim, ticks);
      std::vector<Eigen::Affine3d> T(n);
      for (int j = 0; j < n; ++j) T[j] = C * G[joint_node[j]] * bind_inverse[j];
      SceneKey k;
      k.time = ticks / tps;
      if (!std::isfinite(k.time)) throw file_error(path, 0, "an animation key's time is not finite");
      k.params = key_params(s.rig, T, path, k.time);
      s.keys.push_back(std::move(k));
    }
  }
  finish_import(s, path, &r);
  if (report) *report = r;
  return s;
}

void register_assimp_scene_importers() {
  const SceneImporter import = [](const std::string& path, std::string& report) {
    RigImportReport r;
    SceneData s = import_assimp_scene(path, &r);
    report = r.text();
    return s;
  };
  register_scene_importer("fbx", import);
  register_scene_importer("dae", import);
  register_bvh_importers();
}

}  // namespace dfm
