#pragma once
// Reading a file through Assimp for the FBX, Collada and BVH importers (assimp_scene_import.h,
// bvh_motion.h): failures as dfm::Error naming the file, the node tree as a table, and the first
// animation sampled as Assimp defines its channels (positions and scales linear, rotations slerped,
// held before the first key and after the last). Internal to core/export: it shows Assimp's types.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <assimp/Importer.hpp>
#include <assimp/scene.h>

namespace dfm {

struct AssimpFile {
  std::unique_ptr<Assimp::Importer> importer;  // owns `scene`
  const aiScene* scene = nullptr;
};

// Reads `path` with Assimp (triangulated, validated); `format` is what Assimp must have read it as
// (its SourceAsset_Format begins with it: "Autodesk FBX", "Collada", "BVH"). Throws dfm::Error naming
// the file and Assimp's complaint, or "not a FORMAT file".
AssimpFile read_with_assimp(const std::string& path, const std::string& format);

// The node tree depth first (a parent before its children).
struct AssimpNodes {
  std::vector<const aiNode*> node;
  std::vector<int> parent;             // -1 for the root
  std::map<std::string, int> by_name;  // the first node of each name
  int find(const std::string& name) const;  // -1 if none
};
AssimpNodes node_table(const aiScene* scene);

Eigen::Affine3d to_affine(const aiMatrix4x4& m);

// Per node, its first child that is a bare leaf (no mesh, no children) and no joint, or -1: where a
// leaf joint's bone ends (FBX's added *_end nodes, BVH's End Sites; import_skeleton uses it only for
// joints without joint children). `joint_of`: per node its joint, or -1.
std::vector<int> end_nodes(const AssimpNodes& nodes, const std::vector<int>& joint_of);

// Per node its global transform at `ticks` of `anim` (nullptr: the file's own node transforms).
std::vector<Eigen::Affine3d> global_transforms(const AssimpNodes& nodes, const aiAnimation* anim, double ticks);

// The animation's key times in ticks, every channel's together, sorted, each once.
std::vector<double> key_ticks(const aiAnimation* anim);
// Its ticks per second (25 where the file does not say, as Assimp's viewer plays it).
double ticks_per_second(const aiAnimation* anim);

}  // namespace dfm
