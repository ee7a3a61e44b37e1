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

// The file's joints: the nodes the bones name, in the tree's order, each one's bind frame from its
// first bone. A mesh's frame: Assimp skins G_j(t) offset_j v, without the mesh node's transform (which
// its Collada import sets to the up-axis turn the vertices already have), so the rest pose, G_j
// offset_j v at the nodes' own transforms, puts the mesh at M = C G_b offset_b for its first bone b.
struct FileJoints {
  std::vector<ImportJoint> joints;
  std::vector<int> node;              // per joint
  std::map<int, int> of_node;         // node -> joint
  std::vector<Eigen::Affine3d> mesh;  // per skinned mesh, M
};

FileJoints file_joints(const std::vector<SkinnedMesh>& meshes, const AssimpNodes& nodes, const std::vector<Eigen::Affine3d>& rest,
                       const Eigen::Affine3d& C, const std::string& path) {
  FileJoints fj;
  std::map<int, Eigen::Affine3d> bind_of;
  for (const SkinnedMesh& m : meshes)
    for (unsigned b = 0; b < m.mesh->mNumBones; ++b) {
      const aiBone* bone = m.mesh->mBones[b];
      const int node = nodes.find(bone->mName.C_Str());
      if (node < 0) throw file_error(path, 0, std::string("bone '") + bone->mName.C_Str() + "' names no node");
      const Eigen::Affine3d offset = to_affine(bone->mOffsetMatrix);
      if (!offset.matrix().allFinite() || !(std::abs(offset.linear().determinant()) > 1e-12))
        throw file_error(path, 0, std::string("bone '") + bone->mName.C_Str() + "'s offset matrix is singular");
      if (b == 0) fj.mesh.push_back(C * rest[node] * offset);
      bind_of.emplace(node, fj.mesh.back() * offset.inverse());
    }
  for (const auto& [node, bind] : bind_of) {  // map order = the tree's depth-first order
    fj.of_node[node] = static_cast<int>(fj.node.size());
    fj.node.push_back(node);
    ImportJoint J;
    J.name = nodes.node[node]->mName.C_Str();
    J.bind = bind;
    fj.joints.push_back(J);
  }
  for (size_t j = 0; j < fj.joints.size(); ++j)
    for (int a = nodes.parent[fj.node[j]]; a >= 0 && fj.joints[j].parent < 0; a = nodes.parent[a])
      if (fj.of_node.count(a)) fj.joints[j].parent = fj.of_node[a];
  // A leaf joint's end node, carried into the bind.
  std::vector<int> joint_of(nodes.node.size(), -1);
  for (const auto& [node, j] : fj.of_node) joint_of[node] = j;
  const std::vector<int> end = end_nodes(nodes, joint_of);
  for (size_t j = 0; j < fj.joints.size(); ++j) {
    const int p = fj.node[j];
    if (end[p] < 0) continue;
    const Eigen::Vector3d e = fj.joints[j].bind * ((rest[p].inverse() * rest[end[p]]).translation());
    if (e.allFinite()) fj.joints[j].end = e;
  }
  return fj;
}

// The skinned meshes in the output frame as one vertex list, and every bone's weights on it.
struct FileMesh {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  std::vector<Influence> influences;
  bool morphs = false;
};

FileMesh file_mesh(const std::vector<SkinnedMesh>& meshes, const FileJoints& fj, const AssimpNodes& nodes, const Eigen::Affine3d& C) {
  FileMesh out;
  Eigen::Index nv = 0, nf = 0;
  for (const SkinnedMesh& m : meshes) nv += m.mesh->mNumVertices, nf += m.mesh->mNumFaces;
  out.V.resize(nv, 3);
  out.F.resize(nf, 3);
  const bool mirrored = C.linear().determinant() < 0;  // a left-handed file: faces turn to stay outward
  Eigen::Index v0 = 0, f_count = 0;
  for (size_t mi = 0; mi < meshes.size(); ++mi) {
    const aiMesh* m = meshes[mi].mesh;
    for (unsigned v = 0; v < m->mNumVertices; ++v) {
      const aiVector3D& p = m->mVertices[v];
      out.V.row(v0 + v) = (fj.mesh[mi] * Eigen::Vector3d(p.x, p.y, p.z)).transpose();
    }
    for (unsigned k = 0; k < m->mNumFaces; ++k) {
      const aiFace& face = m->mFaces[k];
      if (face.mNumIndices != 3) continue;  // points and lines
      for (int c = 0; c < 3; ++c) out.F(f_count, mirrored ? 2 - c : c) = static_cast<int>(v0 + face.mIndices[c]);
      ++f_count;
    }
    for (unsigned b = 0; b < m->mNumBones; ++b) {
      const aiBone* bone = m->mBones[b];
      const int j = fj.of_node.at(nodes.find(bone->mName.C_Str()));
      for (unsigned k = 0; k < bone->mNumWeights; ++k) {
        const aiVertexWeight& w = bone->mWeights[k];
        const int vertex = w.mVertexId < m->mNumVertices ? static_cast<int>(v0 + w.mVertexId) : -1;  // -1: refused by name
        out.influences.push_back({vertex, j, w.mWeight});
      }
    }
    out.morphs = out.morphs || m->mNumAnimMeshes > 0;
    v0 += m->mNumVertices;
  }
  out.F.conservativeResize(f_count, 3);
  return out;
}

// The first animation as keys: at each key time, the joint matrices C G_j(t) bind_j^-1.
std::vector<SceneKey> animation_keys(const aiScene* sc, const AssimpNodes& nodes, const FileJoints& fj, const Eigen::Affine3d& C,
                                     const Rig& rig, const std::string& path, RigImportReport* r) {
  std::vector<SceneKey> keys;
  if (sc->mNumAnimations == 0) return keys;
  const aiAnimation* anim = sc->mAnimations[0];
  if (sc->mNumAnimations > 1) r->skipped.push_back(std::to_string(sc->mNumAnimations - 1) + " more animation(s)");
  int unnamed = 0;
  for (unsigned c = 0; c < anim->mNumChannels; ++c) unnamed += nodes.find(anim->mChannels[c]->mNodeName.C_Str()) < 0;
  if (unnamed > 0) r->skipped.push_back(std::to_string(unnamed) + " animation channel(s) naming no node");
  const size_t n = fj.joints.size();
  std::vector<Eigen::Affine3d> bind_inverse(n);
  for (size_t j = 0; j < n; ++j) bind_inverse[j] = fj.joints[j].bind.inverse();
  const double tps = ticks_per_second(anim);
  for (double ticks : key_ticks(anim)) {
    const std::vector<Eigen::Affine3d> G = global_transforms(nodes, anim, ticks);
    std::vector<Eigen::Affine3d> T(n);
    for (size_t j = 0; j < n; ++j) T[j] = C * G[fj.node[j]] * bind_inverse[j];
    SceneKey k;
    k.time = ticks / tps;
    if (!std::isfinite(k.time)) throw file_error(path, 0, "an animation key's time is not finite");
    k.params = key_params(rig, T, path, k.time);
    keys.push_back(std::move(k));
  }
  return keys;
}

}  // namespace

SceneData import_assimp_scene(const std::string& path, RigImportReport* report) {
  const std::string ext = file_extension(path);
  if (ext != "fbx" && ext != "dae") throw Error(path + ": not an FBX (.fbx) or Collada (.dae) file");
  const AssimpFile f = read_with_assimp(path, ext == "fbx" ? "Autodesk FBX" : "Collada");
  const AssimpNodes nodes = node_table(f.scene);
  const Eigen::Affine3d C = ext == "fbx" ? fbx_frame(f.scene, path) : Eigen::Affine3d::Identity();
  const std::vector<Eigen::Affine3d> rest = global_transforms(nodes, nullptr, 0);
  RigImportReport r;
  int unskinned = 0;
  const std::vector<SkinnedMesh> meshes = skinned_meshes(f.scene, nodes, &unskinned);
  if (meshes.empty()) throw file_error(path, 0, "no skinned mesh (a mesh with bones)");
  if (unskinned > 0) r.skipped.push_back(std::to_string(unskinned) + " mesh(es) without bones");
  r.meshes = static_cast<int>(meshes.size());
  const FileJoints fj = file_joints(meshes, nodes, rest, C, path);
  const FileMesh fm = file_mesh(meshes, fj, nodes, C);
  if (fm.morphs) r.skipped.push_back("morph targets (shape keys)");
  if (!fm.V.allFinite()) throw file_error(path, 0, "a vertex position is not finite");
  const WeldedMesh w = weld_by_position(fm.V, fm.F);
  r.file_vertices = static_cast<int>(fm.V.rows());
  const int n = static_cast<int>(fj.joints.size());
  SceneData s = imported_scene(w, fj.joints, welded_weights(fm.influences, w, n, path, &r.influences), path, &r);
  s.keys = animation_keys(f.scene, nodes, fj, C, s.rig, path, &r);
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
