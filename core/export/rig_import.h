#pragma once
// What every rigged-file import shares (glTF, FBX, Collada, BVH; issue 32), so each rule lives once:
// welding the file's split vertices, its weights on the welded mesh, the bone-making rule and the pose
// keys that reproduce the file's joint matrices under the editor's forward kinematics.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/mesh/mesh.h"
#include "core/rig/pose_params.h"
#include "core/rig/rig.h"
#include "core/scene/document.h"

namespace dfm {

// What an import brought in, for the CLI and the notes panel.
struct RigImportReport {
  int meshes = 1, file_vertices = 0, vertices = 0, triangles = 0;
  int joints = 0, bones_along_axis = 0;  // bones whose end came from the joint's axis, not its children
  int bones_to_end = 0;                  // leaf bones ending at the file's end node (FBX *_end, BVH End Site)
  int influences = 0;                    // most nonzero weights on one vertex
  int keys = 0;
  double duration = 0;                   // seconds
  bool rig_from_extras = false;          // this program's own rig, from its glTF export's extras
  std::vector<std::string> skipped;
  std::string text() const;              // a few lines
};

// File vertices at one position become one vertex (numbered in the order of their first file vertex).
struct WeldedMesh {
  TriMesh surface;
  Eigen::VectorXi to_welded;  // per file vertex
  std::vector<int> first;     // per welded vertex, its first file vertex
};
WeldedMesh weld_by_position(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// One weight of the file: file vertex, joint, value.
struct Influence {
  int vertex, joint;
  double weight;
};
// #welded x joints: each welded vertex takes its first file vertex's influences, summed per joint, rows
// normalized. Throws naming the file: a joint or vertex out of range, a weight outside (0, 1], a vertex
// with no weight. *most: the most nonzero weights on one vertex.
Eigen::MatrixXd welded_weights(const std::vector<Influence>& influences, const WeldedMesh& w, int joints,
                               const std::string& path, int* most);

// A joint of the file at bind time: its frame (bind.translation() is the head), parent joint (-1: a
// root) and, for a leaf, the position of the file's end node if it has one.
struct ImportJoint {
  std::string name;
  int parent = -1;
  Eigen::Affine3d bind = Eigen::Affine3d::Identity();
  std::optional<Eigen::Vector3d> end;
};

// One bone per joint, from its head to its children's common head; a leaf with an end node to it;
// otherwise (several children apart, or a leaf without one) along the joint's own y axis (Blender's
// bone axis), as long as the mean distance to its children, else its parent bone, else 5% of
// `diagonal`. Points within 1e-6 of `diagonal` (float rounding) are one joint. A name's bytes that are
// not UTF-8 become '?' (scene files are JSON); an empty name is joint_N. The counts of axis and end tails go to the report.
Skeleton import_skeleton(const std::vector<ImportJoint>& joints, double diagonal, RigImportReport* report);

// The editor's parameters that give exactly the joint matrices T (posed = T_j rest, one per bone)
// under forward kinematics: bone j's local transform, T_parent^-1 T_j, as Translation(a + t) q
// Translation(-a) about its head a. A scale or shear is refused, naming the file and the time.
PoseParams key_params(const Rig& rig, const std::vector<Eigen::Affine3d>& T, const std::string& path, double time);

// A bound scene of the welded mesh, one bone per joint (import_skeleton) and the file's weights
// (every influence kept: the bind's limit is off), at rest, without keys. Fills the report's mesh
// and joint counts.
SceneData imported_scene(const WeldedMesh& w, const std::vector<ImportJoint>& joints, Eigen::MatrixXd weights,
                         const std::string& path, RigImportReport* report);
// After the keys are in: the report's keys and duration, and the notes panel's line.
void finish_import(SceneData& s, const std::string& path, RigImportReport* report);

}  // namespace dfm
