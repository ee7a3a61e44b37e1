#pragma once
// The rig: every kind of handle a weight function can belong to.
//
// Handle (= weight column) order, used by bind, pose, files and the editor alike:
//   1. point handles (rig.points, in order),
//   2. bones (rig.skeleton.bones, in order),
//   3. cage vertices (cages in order, each cage's vertices in file order),
//   4. regions (painted vertex sets that move as one handle).
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/mesh/mesh.h"

namespace dfm {

struct PointHandle {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::string name;
};

// A bone joins joints a -> b. Its parent is the bone whose second joint is a (-1 for a root).
struct Bone {
  int a = -1;
  int b = -1;
  int parent = -1;
  std::string name;
};

struct Skeleton {
  Eigen::MatrixXd joints;  // #J x 3 rest positions
  std::vector<Bone> bones;
  int num_joints() const { return static_cast<int>(joints.rows()); }
  int num_bones() const { return static_cast<int>(bones.size()); }
};

// A cage is a triangle mesh (closed, open or partial); each of its vertices is a handle.
// Cage edges without faces may be given in `edges` (#E x 2) for partial cages.
struct Cage {
  TriMesh mesh;
  Eigen::MatrixXi edges;
  std::string name;
};

// A region: a set of surface vertex indices that moves as one handle.
struct Region {
  std::vector<int> vertices;
  std::string name;
};

struct Rig {
  std::vector<PointHandle> points;
  Skeleton skeleton;
  std::vector<Cage> cages;
  std::vector<Region> regions;
  std::vector<std::pair<int, int>> pseudo_edges;  // between point handles (indices into points)
};

enum class HandleKind { Point, Bone, CageVertex, Region };

struct HandleRef {
  HandleKind kind;
  int index;      // index within its kind (point, bone, region) or cage vertex within its cage
  int cage = -1;  // which cage, for CageVertex
};

int num_point_handles(const Rig& rig);
int num_cage_vertices(const Rig& rig);
int num_handles(const Rig& rig);
// The global handle (weight column) index -> what it is, and back.
HandleRef handle_ref(const Rig& rig, int handle);
int handle_index(const Rig& rig, const HandleRef& ref);
std::string handle_name(const Rig& rig, int handle);
const char* handle_kind_name(HandleKind kind);
// A handle by its number or its name, as scripts and the CLI take one: an integer is an index, any
// other word a name (handle_name's). Throws dfm::Error naming the word: out of range, a name two
// handles share, or no such name (with the closest names, by edit distance, listed).
int find_handle(const Rig& rig, const std::string& word);

// Fills Bone::parent from connectivity (parent of (a,b) is the bone whose second joint is a).
// Throws dfm::Error if the bones contain a cycle.
void compute_bone_parents(Skeleton& skeleton);
// Bone indices ordered so every parent precedes its children.
std::vector<int> bones_topological_order(const Skeleton& skeleton);

}  // namespace dfm
