// TGF <-> Rig. A TGF edge flagged as a bone becomes a skeleton bone; a cage edge joins cage vertices of
// one partial cage; joints on neither become point handles, and pseudo-edges between point handles
// become rig.pseudo_edges. The skeleton keeps only the joints its bones use (in file order), so
// rig -> TGF -> rig is the identity.
#include "core/rig/rig_io.h"

#include <array>

#include "core/util/error.h"

namespace dfm {

void add_tgf_to_rig(Rig& rig, const TgfData& tgf, const std::string& source) {
  const int nj = static_cast<int>(tgf.joints.rows()), ne = static_cast<int>(tgf.edges.rows());
  if (tgf.joints.cols() != 3 && nj > 0) throw Error(source + ": joints must have 3 columns");
  if (tgf.edges.cols() != 2 && ne > 0) throw Error(source + ": edges must have 2 columns");
  if (tgf.flags.rows() != ne || (ne > 0 && tgf.flags.cols() != 3))
    throw Error(source + ": edge flags must be #edges x 3");
  enum Role { None, BoneJoint, CageJoint };
  std::vector<int> role(nj, None);
  for (int e = 0; e < ne; ++e)
    for (int c = 0; c < 2; ++c) {
      int j = tgf.edges(e, c);
      if (j < 0 || j >= nj)
        throw Error(source + ": edge " + std::to_string(e + 1) + " joint " + std::to_string(j + 1) + " out of range");
      if (tgf.flags(e, 0)) role[j] = BoneJoint;
      else if (tgf.flags(e, 2) && role[j] == None) role[j] = CageJoint;
    }
  // New indices: skeleton joints, point handles and cage vertices, each in file order.
  std::vector<int> to_joint(nj, -1), to_point(nj, -1), to_cage(nj, -1);
  const int j0 = rig.skeleton.num_joints();
  int nb = 0, np = 0, nc = 0;
  for (int j = 0; j < nj; ++j) {
    if (role[j] == BoneJoint) to_joint[j] = j0 + nb++;
    else if (role[j] == CageJoint) to_cage[j] = nc++;
    else to_point[j] = static_cast<int>(rig.points.size()) + np++;
  }
  rig.skeleton.joints.conservativeResize(j0 + nb, 3);
  Cage cage;
  cage.name = source + " cage";
  cage.mesh.V.resize(nc, 3);
  for (int j = 0; j < nj; ++j) {
    if (to_joint[j] >= 0) rig.skeleton.joints.row(to_joint[j]) = tgf.joints.row(j);
    if (to_cage[j] >= 0) cage.mesh.V.row(to_cage[j]) = tgf.joints.row(j);
    if (to_point[j] >= 0) {
      PointHandle p;
      p.position = tgf.joints.row(j).transpose();
      p.name = "point " + std::to_string(to_point[j]);
      rig.points.push_back(p);
    }
  }
  std::vector<std::pair<int, int>> cage_edges;
  for (int e = 0; e < ne; ++e) {
    const int a = tgf.edges(e, 0), b = tgf.edges(e, 1);
    if (tgf.flags(e, 0)) {
      Bone bone;
      bone.a = to_joint[a];
      bone.b = to_joint[b];
      bone.name = "bone " + std::to_string(rig.skeleton.num_bones());
      rig.skeleton.bones.push_back(bone);
    } else if (tgf.flags(e, 1)) {
      if (to_point[a] < 0 || to_point[b] < 0)
        throw Error(source + ": pseudo-edge " + std::to_string(e + 1) + " (" + std::to_string(a + 1) + ", " +
                    std::to_string(b + 1) + ") must join two point handles, but a joint lies on a bone or cage edge");
      rig.pseudo_edges.emplace_back(to_point[a], to_point[b]);
    } else if (tgf.flags(e, 2)) {
      if (to_cage[a] < 0 || to_cage[b] < 0)
        throw Error(source + ": cage edge " + std::to_string(e + 1) + " touches a bone joint");
      cage_edges.emplace_back(to_cage[a], to_cage[b]);
    }
  }
  if (nc > 0) {
    cage.edges.resize(cage_edges.size(), 2);
    for (size_t i = 0; i < cage_edges.size(); ++i) cage.edges.row(i) << cage_edges[i].first, cage_edges[i].second;
    rig.cages.push_back(cage);
  }
  compute_bone_parents(rig.skeleton);
}

TgfData rig_to_tgf(const Rig& rig) {
  // Joints: skeleton joints, then point handles, then the vertices of cages given by edges (face-only
  // cages are meshes, not TGF content, and are left out).
  const int nj = rig.skeleton.num_joints(), np = static_cast<int>(rig.points.size());
  int nc = 0;
  for (const Cage& c : rig.cages)
    if (c.edges.rows() > 0 && c.mesh.F.rows() == 0) nc += c.mesh.num_vertices();
  TgfData t;
  t.joints.resize(nj + np + nc, 3);
  if (nj > 0) t.joints.topRows(nj) = rig.skeleton.joints;
  for (int i = 0; i < np; ++i) t.joints.row(nj + i) = rig.points[i].position.transpose();
  std::vector<std::array<int, 5>> edges;
  for (const Bone& b : rig.skeleton.bones) edges.push_back({b.a, b.b, 1, 0, 0});
  for (auto& pe : rig.pseudo_edges) edges.push_back({nj + pe.first, nj + pe.second, 0, 1, 0});
  int base = nj + np;
  for (const Cage& c : rig.cages) {
    if (!(c.edges.rows() > 0 && c.mesh.F.rows() == 0)) continue;
    t.joints.middleRows(base, c.mesh.num_vertices()) = c.mesh.V;
    for (int e = 0; e < c.edges.rows(); ++e) edges.push_back({base + c.edges(e, 0), base + c.edges(e, 1), 0, 0, 1});
    base += c.mesh.num_vertices();
  }
  t.edges.resize(edges.size(), 2);
  t.flags.resize(edges.size(), 3);
  for (size_t e = 0; e < edges.size(); ++e) {
    t.edges.row(e) << edges[e][0], edges[e][1];
    t.flags.row(e) << edges[e][2], edges[e][3], edges[e][4];
  }
  return t;
}

void add_points_file_to_rig(Rig& rig, const std::string& path) {
  const Eigen::MatrixXd P = read_points(path);
  if (P.rows() == 0) throw file_error(path, 0, "holds no points (expected one 'x y z' a line)");
  for (int i = 0; i < P.rows(); ++i) rig.points.push_back({P.row(i).transpose(), "point " + std::to_string(i + 1)});
}

}  // namespace dfm
