#include "core/export/bvh_motion.h"

#include <cmath>
#include <functional>
#include <sstream>

#include <Eigen/SVD>

#include "core/export/assimp_read.h"
#include "core/export/rig_import.h"
#include "core/scene/scene_import.h"
#include "core/util/error.h"

namespace dfm {

namespace {

// The similarity x -> s R x + t taking points P to Q best in least squares (Umeyama 1991), or a
// translation when the points do not span a plane.
Eigen::Affine3d fit_similarity(const std::vector<Eigen::Vector3d>& P, const std::vector<Eigen::Vector3d>& Q, double* scale) {
  const size_t m = P.size();
  Eigen::Vector3d mp = Eigen::Vector3d::Zero(), mq = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < m; ++i) mp += P[i] / m, mq += Q[i] / m;
  Eigen::Matrix3d sigma = Eigen::Matrix3d::Zero();
  double var = 0;
  for (size_t i = 0; i < m; ++i) {
    sigma += (Q[i] - mq) * (P[i] - mp).transpose() / m;
    var += (P[i] - mp).squaredNorm() / m;
  }
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(sigma, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Affine3d A = Eigen::Affine3d::Identity();
  *scale = 1;
  const Eigen::Vector3d d = svd.singularValues();
  if (m < 3 || !(var > 0) || !(d[1] > 1e-9 * d[0])) {
    A.translation() = mq - mp;
    return A;
  }
  Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0) S(2, 2) = -1;
  const Eigen::Matrix3d R = svd.matrixU() * S * svd.matrixV().transpose();
  *scale = (d.asDiagonal() * S).trace() / var;
  A.linear() = *scale * R;
  A.translation() = mq - A.linear() * mp;
  return A;
}

}  // namespace

std::string BvhReport::text() const {
  auto list = [](const std::vector<std::string>& v) {
    std::string s;
    for (const std::string& x : v) s += (s.empty() ? "" : " ") + x;
    return s.empty() ? std::string("none") : s;
  };
  std::ostringstream o;
  o << "motion: " << keys << " keys over " << duration << " s onto " << matched.size() << " bones by name; the BVH's rest joints"
    << " scaled by " << scale << " onto the bones' heads, " << residual << " of the rig's size apart (rms)"
    << "\nmatched: " << list(matched) << "\nBVH joints without a bone: " << list(bvh_only)
    << "\nbones without a BVH joint (held at rest under their parent): " << list(scene_only);
  return o.str();
}

std::vector<SceneKey> bvh_motion_keys(const SceneData& scene, const std::string& path, BvhReport* report) {
  const AssimpFile f = read_with_assimp(path, "BVH");
  if (f.scene->mNumAnimations == 0) throw file_error(path, 0, "no motion");
  const aiAnimation* anim = f.scene->mAnimations[0];
  const AssimpNodes nodes = node_table(f.scene);
  const Skeleton& sk = scene.rig.skeleton;
  const int nb = sk.num_bones();
  BvhReport r;
  // A BVH joint is a node with a channel (End Sites have none).
  std::vector<int> bvh_node_of_bone(nb, -1);
  std::vector<char> used(nodes.node.size(), 0);
  for (int b = 0; b < nb; ++b) {
    const int n = nodes.find(sk.bones[b].name);
    bool animated = false;
    for (unsigned c = 0; c < anim->mNumChannels && n >= 0; ++c) animated |= nodes.find(anim->mChannels[c]->mNodeName.C_Str()) == n;
    if (animated) {
      bvh_node_of_bone[b] = n;
      used[n] = 1;
      r.matched.push_back(sk.bones[b].name);
    } else {
      r.scene_only.push_back(sk.bones[b].name);
    }
  }
  for (unsigned c = 0; c < anim->mNumChannels; ++c) {
    const int n = nodes.find(anim->mChannels[c]->mNodeName.C_Str());
    if (n < 0 || !used[n]) r.bvh_only.push_back(anim->mChannels[c]->mNodeName.C_Str());
  }
  if (r.matched.empty()) throw file_error(path, 0, "no BVH joint is named after a bone of the scene");

  const std::vector<Eigen::Affine3d> rest = global_transforms(nodes, nullptr, 0);
  std::vector<Eigen::Vector3d> P, Q;
  for (int b = 0; b < nb; ++b)
    if (bvh_node_of_bone[b] >= 0) {
      P.push_back(rest[bvh_node_of_bone[b]].translation());
      Q.push_back(sk.joints.row(sk.bones[b].a).transpose());
    }
  const Eigen::Affine3d A = fit_similarity(P, Q, &r.scale);
  const double size = (sk.joints.colwise().maxCoeff() - sk.joints.colwise().minCoeff()).norm();
  for (size_t i = 0; i < P.size(); ++i) r.residual += (A * P[i] - Q[i]).squaredNorm() / P.size();
  r.residual = size > 0 ? std::sqrt(r.residual) / size : 0;
  const Eigen::Affine3d A_inv = A.inverse();

  std::vector<SceneKey> keys;
  const double tps = ticks_per_second(anim);
  for (double ticks : key_ticks(anim)) {
    const std::vector<Eigen::Affine3d> G = global_transforms(nodes, anim, ticks);
    std::vector<Eigen::Affine3d> T(nb);
    std::vector<char> done(nb, 0);
    std::function<const Eigen::Affine3d&(int)> joint_matrix = [&](int b) -> const Eigen::Affine3d& {
      if (!done[b]) {
        done[b] = 1;  // set first: a looping parent chain ends at identity instead of recursing
        const int k = bvh_node_of_bone[b], p = sk.bones[b].parent;
        T[b] = Eigen::Affine3d::Identity();
        if (k >= 0) T[b] = A * G[k] * rest[k].inverse() * A_inv;
        else if (p >= 0 && p < nb) T[b] = joint_matrix(p);
      }
      return T[b];
    };
    for (int b = 0; b < nb; ++b) joint_matrix(b);
    SceneKey key;
    key.time = ticks / tps;
    key.params = key_params(scene.rig, T, path, key.time);
    keys.push_back(std::move(key));
  }
  r.keys = static_cast<int>(keys.size());
  r.duration = keys.empty() ? 0 : keys.back().time - keys.front().time;
  if (report) *report = r;
  return keys;
}

void apply_bvh_motion(SceneData& scene, const std::string& path, BvhReport* report) {
  std::vector<SceneKey> keys = bvh_motion_keys(scene, path, report);
  scene.keys = std::move(keys);
  scene.pose = rest_pose_params(scene.rig);
}

SceneData import_bvh_skeleton(const std::string& path, RigImportReport* report) {
  const AssimpFile f = read_with_assimp(path, "BVH");
  if (f.scene->mNumAnimations == 0) throw file_error(path, 0, "no motion");
  const aiAnimation* anim = f.scene->mAnimations[0];
  const AssimpNodes nodes = node_table(f.scene);
  const std::vector<Eigen::Affine3d> rest = global_transforms(nodes, nullptr, 0);
  // Joints: the nodes with a channel (End Sites have none), in the tree's order.
  std::vector<int> joint_of(nodes.node.size(), -1), joint_node;
  for (size_t i = 0; i < nodes.node.size(); ++i)
    for (unsigned c = 0; c < anim->mNumChannels; ++c)
      if (nodes.find(anim->mChannels[c]->mNodeName.C_Str()) == static_cast<int>(i) && joint_of[i] < 0) {
        joint_of[i] = static_cast<int>(joint_node.size());
        joint_node.push_back(static_cast<int>(i));
      }
  if (joint_node.empty()) throw file_error(path, 0, "no joint has motion");
  const int n = static_cast<int>(joint_node.size());
  std::vector<ImportJoint> joints(n);
  Eigen::MatrixXd heads(n, 3);
  for (int j = 0; j < n; ++j) {
    const int node = joint_node[j];
    joints[j].name = nodes.node[node]->mName.C_Str();
    joints[j].bind = Eigen::Translation3d(rest[node].translation()) * Eigen::Affine3d::Identity();  // BVH axes: the file's
    for (int a = nodes.parent[node]; a >= 0 && joints[j].parent < 0; a = nodes.parent[a]) joints[j].parent = joint_of[a];
    heads.row(j) = rest[node].translation().transpose();
  }
  const std::vector<int> end = end_nodes(nodes, joint_of);  // End Sites
  for (int j = 0; j < n; ++j)
    if (end[joint_node[j]] >= 0) joints[j].end = rest[end[joint_node[j]]].translation();
  RigImportReport r;
  r.meshes = 0;
  r.joints = n;
  double diagonal = (heads.colwise().maxCoeff() - heads.colwise().minCoeff()).norm();
  if (!(diagonal > 0)) diagonal = 1;
  SceneData s;
  s.surface_path = path;
  s.rig.skeleton = import_skeleton(joints, diagonal, &r);
  s.pose = rest_pose_params(s.rig);
  const double tps = ticks_per_second(anim);
  for (double ticks : key_ticks(anim)) {
    const std::vector<Eigen::Affine3d> G = global_transforms(nodes, anim, ticks);
    std::vector<Eigen::Affine3d> T(n);
    for (int j = 0; j < n; ++j) T[j] = G[joint_node[j]] * rest[joint_node[j]].inverse();
    SceneKey k;
    k.time = ticks / tps;
    k.params = key_params(s.rig, T, path, k.time);
    s.keys.push_back(std::move(k));
  }
  r.skipped.push_back("no mesh: a BVH file is a skeleton and its motion (bind a surface, or load-motion onto a rigged scene)");
  finish_import(s, path, &r);
  if (report) *report = r;
  return s;
}

void register_bvh_importers() {
  register_motion_importer("bvh", [](const SceneData& scene, const std::string& path, std::string& report) {
    BvhReport r;
    std::vector<SceneKey> keys = bvh_motion_keys(scene, path, &r);
    report = r.text();
    return keys;
  });
  register_scene_importer("bvh", [](const std::string& path, std::string& report) {
    RigImportReport r;
    SceneData s = import_bvh_skeleton(path, &r);
    report = r.text();
    return s;
  });
}

}  // namespace dfm
