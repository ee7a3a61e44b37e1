#include "core/export/assimp_read.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include <assimp/postprocess.h>

#include "core/util/error.h"

namespace dfm {

AssimpFile read_with_assimp(const std::string& path, const std::string& format) {
  AssimpFile f;
  f.importer = std::make_unique<Assimp::Importer>();
  Assimp::Importer& im = *f.importer;
  // One node per FBX node: pivots folded into its transform, not split into helper nodes.
  im.SetPropertyBool(AI_CONFIG_IMPORT_FBX_PRESERVE_PIVOTS, false);
  // Collada nodes by their names (Blender's bone names), not their ids (armature_bone).
  im.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_USE_COLLADA_NAMES, true);
  try {
    f.scene = im.ReadFile(path, aiProcess_Triangulate | aiProcess_ValidateDataStructure);
  } catch (const std::exception& e) {
    throw Error(path + ": " + e.what());
  }
  if (!f.scene) throw Error(path + ": " + (im.GetErrorString()[0] ? im.GetErrorString() : "Assimp could not read it"));
  aiString read_as;
  if (!f.scene->mMetaData || !f.scene->mMetaData->Get("SourceAsset_Format", read_as) ||
      std::string(read_as.C_Str()).rfind(format, 0) != 0)
    throw Error(path + ": not a " + format + " file (Assimp read it as " + (read_as.length ? read_as.C_Str() : "something else") + ")");
  if (!f.scene->mRootNode) throw Error(path + ": no nodes");
  return f;
}

int AssimpNodes::find(const std::string& name) const {
  const auto it = by_name.find(name);
  return it == by_name.end() ? -1 : it->second;
}

AssimpNodes node_table(const aiScene* scene) {
  AssimpNodes t;
  std::function<void(const aiNode*, int)> walk = [&](const aiNode* n, int parent) {
    const int i = static_cast<int>(t.node.size());
    t.node.push_back(n);
    t.parent.push_back(parent);
    t.by_name.emplace(n->mName.C_Str(), i);
    for (unsigned c = 0; c < n->mNumChildren; ++c) walk(n->mChildren[c], i);
  };
  walk(scene->mRootNode, -1);
  return t;
}

Eigen::Affine3d to_affine(const aiMatrix4x4& m) {
  Eigen::Affine3d a = Eigen::Affine3d::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) a.matrix()(r, c) = m[r][c];
  return a;
}

std::vector<int> end_nodes(const AssimpNodes& nodes, const std::vector<int>& joint_of) {
  std::vector<int> end(nodes.node.size(), -1);
  for (size_t i = 0; i < nodes.node.size(); ++i) {
    const int p = nodes.parent[i];
    if (p < 0 || joint_of[i] >= 0 || joint_of[p] < 0 || end[p] >= 0) continue;
    if (nodes.node[i]->mNumMeshes == 0 && nodes.node[i]->mNumChildren == 0) end[p] = static_cast<int>(i);
  }
  return end;
}

namespace {

// The bracketing keys of `ticks` and the fraction between them (held outside the keys).
template <class Key>
void bracket(const Key* keys, unsigned n, double ticks, unsigned* i, unsigned* k, double* u) {
  *i = *k = 0;
  *u = 0;
  if (n == 0 || ticks <= keys[0].mTime) return;
  if (ticks >= keys[n - 1].mTime) {
    *i = *k = n - 1;
    return;
  }
  unsigned hi = 1;
  while (keys[hi].mTime < ticks) ++hi;
  *i = hi - 1;
  *k = hi;
  const double span = keys[hi].mTime - keys[hi - 1].mTime;
  *u = span > 0 ? (ticks - keys[hi - 1].mTime) / span : 0;
}

Eigen::Vector3d vec(const aiVector3D& v) { return Eigen::Vector3d(v.x, v.y, v.z); }

Eigen::Vector3d lerp_key(const aiVectorKey* keys, unsigned n, double ticks) {
  unsigned i, k;
  double u;
  bracket(keys, n, ticks, &i, &k, &u);
  return (1 - u) * vec(keys[i].mValue) + u * vec(keys[k].mValue);
}

Eigen::Quaterniond slerp_key(const aiQuatKey* keys, unsigned n, double ticks) {
  unsigned i, k;
  double u;
  bracket(keys, n, ticks, &i, &k, &u);
  const Eigen::Quaterniond a(keys[i].mValue.w, keys[i].mValue.x, keys[i].mValue.y, keys[i].mValue.z);
  const Eigen::Quaterniond b(keys[k].mValue.w, keys[k].mValue.x, keys[k].mValue.y, keys[k].mValue.z);
  return a.normalized().slerp(u, b.normalized());
}

// A channel's local transform at `ticks`; what it does not key comes from the node's own transform.
Eigen::Affine3d channel_local(const aiNodeAnim* c, const aiNode* node, double ticks) {
  aiVector3D s0, p0;
  aiQuaternion r0;
  node->mTransformation.Decompose(s0, r0, p0);
  const Eigen::Vector3d p = c->mNumPositionKeys ? lerp_key(c->mPositionKeys, c->mNumPositionKeys, ticks) : vec(p0);
  const Eigen::Quaterniond r = c->mNumRotationKeys ? slerp_key(c->mRotationKeys, c->mNumRotationKeys, ticks)
                                                   : Eigen::Quaterniond(r0.w, r0.x, r0.y, r0.z).normalized();
  const Eigen::Vector3d s = c->mNumScalingKeys ? lerp_key(c->mScalingKeys, c->mNumScalingKeys, ticks) : vec(s0);
  Eigen::Affine3d a = Eigen::Affine3d::Identity();
  a.translate(p).rotate(r).scale(s);
  return a;
}

}  // namespace

std::vector<Eigen::Affine3d> global_transforms(const AssimpNodes& nodes, const aiAnimation* anim, double ticks) {
  const size_t n = nodes.node.size();
  std::vector<const aiNodeAnim*> channel(n, nullptr);
  if (anim)
    for (unsigned c = 0; c < anim->mNumChannels; ++c) {
      const int i = nodes.find(anim->mChannels[c]->mNodeName.C_Str());
      if (i >= 0 && !channel[i]) channel[i] = anim->mChannels[c];
    }
  std::vector<Eigen::Affine3d> G(n);
  for (size_t i = 0; i < n; ++i) {  // parents come first
    const Eigen::Affine3d local = channel[i] ? channel_local(channel[i], nodes.node[i], ticks) : to_affine(nodes.node[i]->mTransformation);
    G[i] = nodes.parent[i] >= 0 ? G[nodes.parent[i]] * local : local;
  }
  return G;
}

std::vector<double> key_ticks(const aiAnimation* anim) {
  std::vector<double> t;
  for (unsigned c = 0; c < anim->mNumChannels; ++c) {
    const aiNodeAnim* a = anim->mChannels[c];
    for (unsigned k = 0; k < a->mNumPositionKeys; ++k) t.push_back(a->mPositionKeys[k].mTime);
    for (unsigned k = 0; k < a->mNumRotationKeys; ++k) t.push_back(a->mRotationKeys[k].mTime);
    for (unsigned k = 0; k < a->mNumScalingKeys; ++k) t.push_back(a->mScalingKeys[k].mTime);
  }
  std::sort(t.begin(), t.end());
  // Channels may write one time a float's rounding apart (Collada's milliseconds).
  t.erase(std::unique(t.begin(), t.end(), [](double a, double b) { return b - a <= 1e-6 * std::max(1.0, std::abs(b)); }), t.end());
  return t;
}

double ticks_per_second(const aiAnimation* anim) {
  // Assimp writes 0 when the file does not say; its own viewer then plays 25 ticks a second.
  return anim->mTicksPerSecond > 0 ? anim->mTicksPerSecond : 25.0;
}

}  // namespace dfm
