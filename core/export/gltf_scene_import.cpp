#include "core/export/gltf_scene_import.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "core/export/gltf_import.h"
#include "core/rig/pose_params.h"
#include "core/scene/scene_import.h"
#include "core/util/error.h"

namespace dfm {

namespace {

struct Welded {
  TriMesh surface;
  Eigen::VectorXi to_welded;  // per file vertex
};

// File vertices at one position become one vertex (the first one's index order).
Welded weld(const GltfMeshData& m) {
  Welded w;
  std::map<std::array<double, 3>, int> at;
  w.to_welded.resize(m.V.rows());
  std::vector<int> first;
  for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
    const auto [it, fresh] = at.emplace(std::array<double, 3>{m.V(v, 0), m.V(v, 1), m.V(v, 2)}, static_cast<int>(first.size()));
    if (fresh) first.push_back(static_cast<int>(v));
    w.to_welded[v] = it->second;
  }
  w.surface.V.resize(static_cast<Eigen::Index>(first.size()), 3);
  for (size_t i = 0; i < first.size(); ++i) w.surface.V.row(static_cast<Eigen::Index>(i)) = m.V.row(first[i]);
  std::vector<Eigen::RowVector3i> faces;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const Eigen::RowVector3i t(w.to_welded[m.F(f, 0)], w.to_welded[m.F(f, 1)], w.to_welded[m.F(f, 2)]);
    if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) faces.push_back(t);
  }
  w.surface.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f) w.surface.F.row(static_cast<Eigen::Index>(f)) = faces[f];
  return w;
}

// #welded x #joints: every set's weights summed per joint, rows normalized.
Eigen::MatrixXd joint_weights(const GltfMeshData& m, const Welded& w, int joints, const std::string& path, int* most) {
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(w.surface.V.rows(), joints);
  std::vector<char> done(w.surface.V.rows(), 0);
  for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
    const int i = w.to_welded[v];
    if (done[i]) continue;
    done[i] = 1;
    for (Eigen::Index c = 0; c < m.joints.cols(); ++c) {
      const int j = m.joints(v, c);
      const double x = m.weights(v, c);
      if (x == 0) continue;
      if (j < 0 || j >= joints) throw file_error(path, 0, "vertex " + std::to_string(v) + " names joint " + std::to_string(j));
      if (!(x > 0 && x <= 1 + 1e-6)) throw file_error(path, 0, "vertex " + std::to_string(v) + " has weight " + std::to_string(x));
      W(i, j) += x;
    }
  }
  *most = 0;
  for (Eigen::Index i = 0; i < W.rows(); ++i) {
    const double s = W.row(i).sum();
    if (!(s > 0)) throw file_error(path, 0, "vertex " + std::to_string(i) + " (welded) has no weight");
    W.row(i) /= s;
    *most = std::max(*most, static_cast<int>((W.row(i).array() > 0).count()));
  }
  return W;
}

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

// The bones (issue 32's rule, in gltf_scene_import.h): heads at the bind positions, tails at the
// children's common head or along the joint's y axis.
Skeleton joint_skeleton(const GltfDocument& g, const std::vector<Eigen::Affine3d>& bind, const std::vector<int>& parent,
                        double diagonal, int* along_axis) {
  const int n = static_cast<int>(g.joints.size());
  const double eps = 1e-9 * diagonal;
  std::vector<Eigen::Vector3d> points;
  auto point = [&](const Eigen::Vector3d& p) {
    for (size_t i = 0; i < points.size(); ++i)
      if ((points[i] - p).norm() <= eps) return static_cast<int>(i);
    points.push_back(p);
    return static_cast<int>(points.size()) - 1;
  };
  std::vector<Eigen::Vector3d> head(n);
  for (int j = 0; j < n; ++j) head[j] = bind[j].translation();
  std::vector<std::vector<int>> children(n);
  for (int j = 0; j < n; ++j)
    if (parent[j] >= 0) children[parent[j]].push_back(j);
  Skeleton s;
  std::vector<double> length(n, 0);
  *along_axis = 0;
  for (int j = 0; j < n; ++j) {  // parents come first in a skin's joint order only by convention: lengths below
    Bone b;
    b.a = point(head[j]);
    b.parent = parent[j];
    b.name = g.nodes[g.joints[j]].name.empty() ? "joint_" + std::to_string(j) : g.nodes[g.joints[j]].name;
    const std::string ours = std::to_string(j) + ":";  // this program's export numbers its joints so
    if (b.name.size() > ours.size() && b.name.compare(0, ours.size(), ours) == 0) b.name.erase(0, ours.size());
    s.bones.push_back(b);
  }
  auto tail_of = [&](int j) -> Eigen::Vector3d {
    const std::vector<int>& c = children[j];
    bool common = !c.empty();
    for (int k : c) common = common && (head[k] - head[c[0]]).norm() <= eps;
    if (common && (head[c[0]] - head[j]).norm() > eps) return head[c[0]];
    ++*along_axis;
    double len = 0;
    for (int k : c) len += (head[k] - head[j]).norm() / c.size();
    if (!(len > eps) && parent[j] >= 0) len = (head[j] - head[parent[j]]).norm();
    if (!(len > eps)) len = 0.05 * diagonal;
    return head[j] + len * (bind[j].linear() * Eigen::Vector3d::UnitY()).normalized();
  };
  for (int j = 0; j < n; ++j) s.bones[j].b = point(tail_of(j));
  s.joints.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (size_t i = 0; i < points.size(); ++i) s.joints.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  return s;
}

// Per joint its joint matrix G_j(t) IB_j at time t.
std::vector<Eigen::Affine3d> joint_matrices(const GltfDocument& g, double t) {
  const std::vector<Eigen::Matrix4d> G = gltf_global_transforms(gltf_animated_nodes(g, t));
  std::vector<Eigen::Affine3d> T(g.joints.size());
  for (size_t j = 0; j < g.joints.size(); ++j) T[j].matrix() = G[g.joints[j]] * g.inverse_bind[j];
  return T;
}

// The editor's parameters that give exactly these joint matrices under forward kinematics: bone j's
// local transform, T_parent^-1 T_j, written as Translation(a + t) q Translation(-a) about its head a.
PoseParams key_params(const Rig& rig, const std::vector<Eigen::Affine3d>& T, const std::vector<int>& parent,
                      const std::string& path, double time) {
  PoseParams p = rest_pose_params(rig);
  for (size_t j = 0; j < T.size(); ++j) {
    const Eigen::Affine3d X = parent[j] >= 0 ? T[parent[j]].inverse() * T[j] : T[j];
    const Eigen::Matrix3d L = X.linear();
    if (!((L.transpose() * L - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-6 && L.determinant() > 0))
      throw file_error(path, 0, "joint " + std::to_string(j) + " scales or shears at t = " + std::to_string(time) +
                                    " s: only rotations and translations are imported");
    const Eigen::Quaterniond q(L);
    const Eigen::Vector3d a = rig.skeleton.joints.row(rig.skeleton.bones[j].a).transpose();
    p.bone_rotation[j] = q.normalized();
    p.bone_translation[j] = X.translation() - a + q.normalized() * a;
    if (p.bone_translation[j].norm() < 1e-12 * (1 + a.norm())) p.bone_translation[j].setZero();
  }
  return p;
}

}  // namespace

std::string GltfImportReport::text() const {
  std::ostringstream o;
  o << "mesh: " << file_vertices << " vertices in the file, " << vertices << " welded, " << triangles << " triangles; "
    << joints << " joints as bones (" << bones_along_axis << " ending along their joint's axis); up to " << influences
    << " influences a vertex";
  if (keys > 0) o << "; animation: " << keys << " keys over " << duration << " s";
  for (const std::string& s : skipped) o << "\nnot imported: " << s;
  return o.str();
}

SceneData import_gltf_scene(const std::string& path, GltfImportReport* report) {
  const GltfDocument g = read_gltf(path);
  if (g.skinned_node < 0 || g.joints.empty()) throw file_error(path, 0, "no skinned mesh (a node with a mesh and a skin)");
  check_skin(g, path);
  GltfImportReport r;
  if (g.morph_node >= 0 || !g.skinned.targets.empty()) r.skipped.push_back("morph targets (shape keys)");
  const Welded w = weld(g.skinned);
  r.file_vertices = static_cast<int>(g.skinned.V.rows());
  r.vertices = static_cast<int>(w.surface.V.rows());
  r.triangles = static_cast<int>(w.surface.F.rows());
  const int n = static_cast<int>(g.joints.size());
  r.joints = n;
  std::vector<Eigen::Affine3d> bind(n);
  for (int j = 0; j < n; ++j) {
    const Eigen::Matrix4d& IB = g.inverse_bind[j];
    if (!IB.allFinite() || !(std::abs(IB.topLeftCorner<3, 3>().determinant()) > 1e-12))
      throw file_error(path, 0, "joint " + std::to_string(j) + "'s inverse bind matrix is singular");
    bind[j].matrix() = IB.inverse();
  }
  const double diagonal = (w.surface.V.colwise().maxCoeff() - w.surface.V.colwise().minCoeff()).norm();
  const std::vector<int> parent = parent_joints(g);
  SceneData s;
  s.surface = w.surface;
  s.surface_path = path;
  s.rig.skeleton = joint_skeleton(g, bind, parent, diagonal, &r.bones_along_axis);
  s.pose = rest_pose_params(s.rig);
  s.weights = joint_weights(g.skinned, w, n, path, &r.influences);
  s.bind_settings.max_influences = 0;  // every influence the file has
  for (double t : g.key_times()) {
    SceneKey k;
    k.time = t;
    k.params = key_params(s.rig, joint_matrices(g, t), parent, path, t);
    s.keys.push_back(std::move(k));
  }
  r.keys = static_cast<int>(s.keys.size());
  r.duration = s.keys.empty() ? 0 : s.keys.back().time - s.keys.front().time;
  s.bind_stats.notes = {"imported from " + path + ": " + r.text()};
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
