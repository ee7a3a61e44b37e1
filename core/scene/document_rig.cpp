// Document commands on the surface, the rig and the painted mask and regions (document.h).
#include "core/scene/document.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "core/mesh/io.h"
#include "core/mesh/mesh_info.h"
#include "core/rig/handle_deletion.h"
#include "core/rig/rig_io.h"
#include "core/scene/document_parts.h"
#include "core/util/error.h"

namespace dfm {

using document_detail::check_finite;

// ---- edits: surface and rig ------------------------------------------------------------------------

namespace {

// A surface file, or a tet mesh and its boundary surface. Throws dfm::Error naming the file.
struct MeshFile {
  TriMesh surface;
  TetMesh tets;
  Eigen::VectorXi surface_to_tet;
};

MeshFile read_mesh_file(const std::string& path) {
  MeshFile m;
  if (is_tet_mesh_path(path)) {
    m.tets = read_tet_mesh(path);
    if (m.tets.num_tets() == 0) throw file_error(path, 0, "tet mesh has no tetrahedra");
    m.surface = tet_boundary_surface(m.tets, &m.surface_to_tet);
    return m;
  }
  m.surface = read_surface(path);
  if (m.surface.num_faces() == 0) throw file_error(path, 0, "mesh has no triangles");
  if (m.surface.F.minCoeff() < 0 || m.surface.F.maxCoeff() >= m.surface.num_vertices())
    throw file_error(path, 0, "face index out of range");
  if (!m.surface.V.allFinite()) throw file_error(path, 0, "vertex position is not finite");
  return m;
}

}  // namespace

void Document::open_mesh(const std::string& path) {
  MeshFile m = read_mesh_file(path);  // throws before anything changes
  SceneData d;
  d.surface = std::move(m.surface);
  d.surface_path = path;
  d.tets = std::move(m.tets);
  d.surface_to_tet = std::move(m.surface_to_tet);
  d.pose = fit_pose_params(d.rig, {});
  start_document(std::move(d), "");
}

void Document::replace_surface(const std::string& path) {
  MeshFile m = read_mesh_file(path);
  install_surface(std::move(m.surface), path, std::move(m.tets), std::move(m.surface_to_tet));
}

void Document::set_surface(const TriMesh& surface, const std::string& source_name) {
  if (surface.num_faces() > 0 && (surface.F.minCoeff() < 0 || surface.F.maxCoeff() >= surface.num_vertices()))
    throw Error(source_name + ": face index out of range");
  if (!surface.V.allFinite()) throw Error(source_name + ": vertex position is not finite");
  install_surface(surface, source_name, TetMesh{}, Eigen::VectorXi());
}

void Document::install_surface(TriMesh surface, const std::string& path, TetMesh tets, Eigen::VectorXi surface_to_tet) {
  const bool bound = s_.weights.size() > 0;
  execute("replace surface " + std::filesystem::path(path).filename().string(),
          kSurface | kRig | kPose | kKeys | kWeights | kMask, "", [&](SceneData& s) {
            s.surface = std::move(surface);
            s.surface_path = path;
            s.tets = std::move(tets);
            s.surface_to_tet = std::move(surface_to_tet);
            s.weights.resize(0, 0);
            s.replaced_weights.resize(0, 0);
            s.endpoint_weights.resize(0, 0);
            s.additional_weights.resize(0, 0);
            s.bind_stats = {};
            s.mask.resize(0);
            s.rig.regions.clear();
            s.pose = fit_pose_params(s.rig, std::move(s.pose));
            for (SceneKey& k : s.keys) k.params = fit_pose_params(s.rig, std::move(k.params));
            weights_note_ = bound ? "surface replaced: weights cleared, bind again" : "not bound yet";
          });
}

void Document::load_skeleton(const std::string& path) {
  const TgfData tgf = read_tgf(path);
  Rig probe = s_.rig;
  add_tgf_to_rig(probe, tgf, path);  // validates before the undo step is recorded
  rig_edit("load skeleton " + std::filesystem::path(path).filename().string(), "",
           [&](SceneData& s) { s.rig = std::move(probe); });
}

void Document::load_cage(const std::string& path) {
  Cage c;
  c.mesh = read_surface(path);
  if (c.mesh.num_vertices() == 0) throw file_error(path, 0, "cage has no vertices");
  c.name = std::filesystem::path(path).stem().string();
  add_cage(c);
}

void Document::add_cage(const Cage& cage) {
  if (!cage.mesh.V.allFinite()) throw Error("cage '" + cage.name + "': vertex position is not finite");
  const int n = cage.mesh.num_vertices();
  if (cage.mesh.num_faces() > 0 && (cage.mesh.F.minCoeff() < 0 || cage.mesh.F.maxCoeff() >= n))
    throw Error("cage '" + cage.name + "': face index out of range");
  if (cage.edges.size() > 0 && (cage.edges.minCoeff() < 0 || cage.edges.maxCoeff() >= n))
    throw Error("cage '" + cage.name + "': edge index out of range");
  // New cage vertices go after the existing ones, so their pose entries append at the end.
  const int before = num_cage_vertices(s_.rig);
  rig_edit("add cage", "", [&](SceneData& s) {
    s.rig.cages.push_back(cage);
    auto fix = [&](PoseParams& p) {
      p.cage_translation.resize(before, Eigen::Vector3d::Zero());
      p.cage_translation.insert(p.cage_translation.end(), n, Eigen::Vector3d::Zero());
    };
    fix(s.pose);
    for (SceneKey& k : s.keys) fix(k.params);
  });
}

int Document::add_point(const Eigen::Vector3d& p, const std::string& name) {
  check_finite(p, "point handle position");
  const int idx = num_point_handles(s_.rig);
  rig_edit("add point", "", [&](SceneData& s) { s.rig.points.push_back({p, name}); });
  s_.selection = Selection{{idx}, -1};
  return idx;
}

void Document::move_point(int point, const Eigen::Vector3d& p) {
  if (point < 0 || point >= num_point_handles(s_.rig)) throw Error("no point handle " + std::to_string(point));
  check_finite(p, "point handle position");
  rig_edit("move point", "move point " + std::to_string(point),
           [&](SceneData& s) { s.rig.points[point].position = p; });
}

int Document::add_bone_chain(const std::vector<Eigen::Vector3d>& joints, int parent_joint) {
  const int nj = s_.rig.skeleton.num_joints();
  if (parent_joint >= nj) throw Error("no joint " + std::to_string(parent_joint));
  const int needed = parent_joint >= 0 ? 1 : 2;
  if (static_cast<int>(joints.size()) < needed)
    throw Error("a bone chain needs at least " + std::to_string(needed) + " joint position(s)");
  for (const auto& j : joints) check_finite(j, "joint position");
  const int first_bone = s_.rig.skeleton.num_bones();
  // New bones are appended; existing bone pose entries keep their indices.
  rig_edit("add bones", "", [&](SceneData& s) {
    Skeleton& sk = s.rig.skeleton;
    Eigen::MatrixXd J(nj + joints.size(), 3);
    if (nj) J.topRows(nj) = sk.joints;
    for (size_t i = 0; i < joints.size(); ++i) J.row(nj + i) = joints[i].transpose();
    sk.joints = J;
    int prev = parent_joint;
    for (size_t i = 0; i < joints.size(); ++i) {
      const int cur = nj + static_cast<int>(i);
      if (prev >= 0) sk.bones.push_back({prev, cur, -1, ""});
      prev = cur;
    }
    compute_bone_parents(sk);
  });
  s_.selection = Selection{{num_point_handles(s_.rig) + first_bone}, -1};
  return first_bone;
}

void Document::move_joint(int joint, const Eigen::Vector3d& p) {
  if (joint < 0 || joint >= s_.rig.skeleton.num_joints()) throw Error("no joint " + std::to_string(joint));
  check_finite(p, "joint position");
  rig_edit("move joint", "move joint " + std::to_string(joint),
           [&](SceneData& s) { s.rig.skeleton.joints.row(joint) = p.transpose(); });
}

void Document::move_cage_vertex(int cage, int vertex, const Eigen::Vector3d& p) {
  if (cage < 0 || cage >= static_cast<int>(s_.rig.cages.size())) throw Error("no cage " + std::to_string(cage));
  if (vertex < 0 || vertex >= s_.rig.cages[cage].mesh.num_vertices())
    throw Error("cage " + std::to_string(cage) + " has no vertex " + std::to_string(vertex));
  check_finite(p, "cage vertex position");
  rig_edit("move cage vertex", "move cage vertex " + std::to_string(cage) + " " + std::to_string(vertex),
           [&](SceneData& s) { s.rig.cages[cage].mesh.V.row(vertex) = p.transpose(); });
}

void Document::delete_handles(std::vector<int> handles) {
  const HandleDeletion d = plan_handle_deletion(s_.rig, handles);
  if (d.empty()) return;
  rig_edit("delete handles", "", [&](SceneData& s) {
    dfm::delete_handles(s.rig, d);
    dfm::delete_handles(s.pose, d);
    for (SceneKey& k : s.keys) dfm::delete_handles(k.params, d);
  });
  s_.selection = Selection{};
}

void Document::rename_handle(int handle, const std::string& name) {
  const HandleRef r = handle_ref(s_.rig, handle);
  // A rename changes no geometry: it must not invalidate the weights.
  execute("rename", kRig, "", [&](SceneData& s) {
    switch (r.kind) {
      case HandleKind::Point: s.rig.points[r.index].name = name; break;
      case HandleKind::Bone: s.rig.skeleton.bones[r.index].name = name; break;
      case HandleKind::CageVertex: s.rig.cages[r.cage].name = name; break;
      case HandleKind::Region: s.rig.regions[r.index].name = name; break;
    }
  });
}

void Document::add_pseudo_edge(int a, int b) {
  const int np = num_point_handles(s_.rig);
  if (a < 0 || b < 0 || a >= np || b >= np || a == b)
    throw Error("a pseudo-edge needs two different point handles (got " + std::to_string(a) + ", " +
                std::to_string(b) + ")");
  for (auto [x, y] : s_.rig.pseudo_edges)
    if ((x == a && y == b) || (x == b && y == a)) return;
  // Pseudo-edges only change rotation inference at pose time, not the weights.
  execute("add pseudo-edge", kRig, "", [&](SceneData& s) { s.rig.pseudo_edges.push_back({a, b}); });
}

void Document::remove_pseudo_edge(int a, int b) {
  auto& pe = s_.rig.pseudo_edges;
  auto it = std::find_if(pe.begin(), pe.end(), [&](auto e) {
    return (e.first == a && e.second == b) || (e.first == b && e.second == a);
  });
  if (it == pe.end()) throw Error("no pseudo-edge between points " + std::to_string(a) + " and " + std::to_string(b));
  const long at = it - pe.begin();
  execute("remove pseudo-edge", kRig, "", [&](SceneData& s) { s.rig.pseudo_edges.erase(s.rig.pseudo_edges.begin() + at); });
}

// ---- painting -------------------------------------------------------------------------------------

void Document::paint_mask(const std::vector<int>& vertices, const std::vector<double>& values) {
  const int nv = s_.surface.num_vertices();
  if (vertices.size() != values.size()) throw Error("paint mask: vertex and value counts differ");
  for (int v : vertices)
    if (v < 0 || v >= nv) throw Error("paint mask: no surface vertex " + std::to_string(v));
  for (double x : values)
    if (!std::isfinite(x)) throw Error("paint mask: value is not finite");
  if (vertices.empty()) return;
  execute("paint mask", kMask, "paint mask", [&](SceneData& s) {
    if (s.mask.size() != nv) s.mask = Eigen::VectorXd::Zero(nv);
    for (size_t i = 0; i < vertices.size(); ++i) s.mask[vertices[i]] = std::clamp(values[i], 0.0, 1.0);
  });
}

int Document::add_region(const std::string& name) {
  const int idx = static_cast<int>(s_.rig.regions.size());
  rig_edit("add region", "", [&](SceneData& s) { s.rig.regions.push_back({{}, name}); });
  s_.selection = Selection{{handle_index(s_.rig, {HandleKind::Region, idx})}, -1};
  return idx;
}

void Document::paint_region(int region, const std::vector<int>& vertices, bool erase) {
  if (region < 0 || region >= static_cast<int>(s_.rig.regions.size()))
    throw Error("no region " + std::to_string(region));
  const int nv = s_.surface.num_vertices();
  for (int v : vertices)
    if (v < 0 || v >= nv) throw Error("paint region: no surface vertex " + std::to_string(v));
  std::set<int> set(s_.rig.regions[region].vertices.begin(), s_.rig.regions[region].vertices.end());
  const size_t before = set.size();
  for (int v : vertices) erase ? (void)set.erase(v) : (void)set.insert(v);
  if (set.size() == before) return;  // nothing changed: keep the weights
  rig_edit(erase ? "erase region" : "paint region", "paint region " + std::to_string(region),
           [&](SceneData& s) { s.rig.regions[region].vertices.assign(set.begin(), set.end()); });
}

}  // namespace dfm
