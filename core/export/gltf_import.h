#pragma once
// A small glTF 2.0 reader for what export_gltf writes: one skinned triangle mesh, its node hierarchy,
// its first animation, and an optional morph-target mesh. Written independently of the exporter (it
// only follows the glTF specification) so a round trip checks the export.
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace dfm {

struct GltfChannel {
  int node = -1;
  enum class Path { Translation, Rotation, Scale, Weights } path = Path::Translation;
  bool step = false;            // STEP interpolation
  bool cubic = false;           // CUBICSPLINE (else LINEAR): Hermite between keys with the tangents below
  std::vector<double> times;    // sampler input
  Eigen::MatrixXd values;       // one row per time (width 3, 4 (x,y,z,w) or #targets)
  Eigen::MatrixXd in_tangents, out_tangents;  // CUBICSPLINE: a_k and b_k, as values (else empty)
};

// Samples a CUBICSPLINE channel adds between its keys to GltfDocument::key_times (a scene's pose keys
// interpolate linearly between keys, so the curve is kept by sampling it).
constexpr int kCubicSamplesPerInterval = 4;

struct GltfNode {
  std::string name;
  int parent = -1;
  int mesh = -1, skin = -1;
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  bool has_matrix = false;
  Eigen::Matrix4d matrix = Eigen::Matrix4d::Identity();
  std::vector<double> weights;  // node.weights (morph weights overriding mesh.weights), or empty
  std::string deform_rig;       // extras.deform_rig: this program's rig as JSON text (gltf_rig_extras.h), or ""
};

struct GltfMeshData {
  Eigen::MatrixXd V, N;            // #V x 3
  Eigen::MatrixXi F;               // #F x 3
  Eigen::MatrixXi joints;          // #V x 4*sets (empty when unskinned)
  Eigen::MatrixXd weights;         // #V x 4*sets
  std::vector<Eigen::MatrixXd> targets;  // morph POSITION displacements, each #V x 3
  std::vector<double> default_weights;   // mesh.weights
};

struct GltfDocument {
  std::vector<GltfNode> nodes;
  int skinned_node = -1;                 // first node with mesh and skin
  GltfMeshData skinned;
  std::vector<int> joints;               // skin joint nodes
  std::vector<Eigen::Matrix4d> inverse_bind;
  int morph_node = -1;                   // first node whose mesh has morph targets
  GltfMeshData morph;
  std::vector<GltfChannel> channels;     // animation 0
  // Sorted union of every channel's input times, and kCubicSamplesPerInterval - 1 evenly spaced times
  // inside each interval of a CUBICSPLINE channel.
  std::vector<double> key_times() const;
};

// Loads .glb or .gltf (external .bin beside it). Throws dfm::Error naming the file and problem.
GltfDocument read_gltf(const std::string& path);

// Node TRS after applying animation 0 at time t (glTF sampling: clamped; LINEAR lerp / slerp, STEP, or
// CUBICSPLINE's Hermite curve, a rotation then normalized).
std::vector<GltfNode> gltf_animated_nodes(const GltfDocument& doc, double t);
// World matrices of every node.
std::vector<Eigen::Matrix4d> gltf_global_transforms(const std::vector<GltfNode>& nodes);
// Morph weights of a node's mesh at time t: its "weights" channel, else node.weights, else mesh.weights.
std::vector<double> gltf_morph_weights(const GltfDocument& doc, int node, const GltfMeshData& mesh, double t);
// Skinned positions at time t: v' = sum_i w_i * globalTransform(joint_i) * inverseBindMatrix_i * m(v), where
// m(v) = v + sum_t morphWeight_t * target_t (glTF morphs before skinning).
Eigen::MatrixXd gltf_skinned_positions(const GltfDocument& doc, double t);
// Morph mesh positions at time t: base + sum_i weight_i(t) * target_i.
Eigen::MatrixXd gltf_morphed_positions(const GltfDocument& doc, double t);

}  // namespace dfm
