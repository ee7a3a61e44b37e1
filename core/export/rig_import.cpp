#include "core/export/rig_import.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>

#include "core/util/error.h"

namespace dfm {

std::string RigImportReport::text() const {
  std::ostringstream o;
  if (meshes == 0) o << "no mesh; ";
  else if (meshes > 1) o << "mesh: " << meshes << " skinned meshes, ";
  else o << "mesh: ";
  if (meshes > 0) o << file_vertices << " vertices in the file, " << vertices << " welded, " << triangles << " triangles; ";
  if (rig_from_extras) {
    o << joints << " joints as this program's own handles (the rig its export stored)";
  } else {
    o << joints << " joints as bones (" << bones_along_axis << " ending along their joint's axis";
    if (bones_to_end > 0) o << ", " << bones_to_end << " at the file's end node";
    o << ")";
  }
  if (meshes > 0) o << "; up to " << influences << " influences a vertex";
  if (keys > 0) o << "; animation: " << keys << " keys over " << duration << " s";
  for (const std::string& s : skipped) o << "\nnot imported: " << s;
  return o.str();
}

WeldedMesh weld_by_position(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  WeldedMesh w;
  std::map<std::array<double, 3>, int> at;
  w.to_welded.resize(V.rows());
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    const auto [it, fresh] = at.emplace(std::array<double, 3>{V(v, 0), V(v, 1), V(v, 2)}, static_cast<int>(w.first.size()));
    if (fresh) w.first.push_back(static_cast<int>(v));
    w.to_welded[v] = it->second;
  }
  w.surface.V.resize(static_cast<Eigen::Index>(w.first.size()), 3);
  for (size_t i = 0; i < w.first.size(); ++i) w.surface.V.row(static_cast<Eigen::Index>(i)) = V.row(w.first[i]);
  std::vector<Eigen::RowVector3i> faces;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::RowVector3i t(w.to_welded[F(f, 0)], w.to_welded[F(f, 1)], w.to_welded[F(f, 2)]);
    if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) faces.push_back(t);
  }
  w.surface.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f) w.surface.F.row(static_cast<Eigen::Index>(f)) = faces[f];
  return w;
}

Eigen::MatrixXd welded_weights(const std::vector<Influence>& influences, const WeldedMesh& w, int joints,
                               const std::string& path, int* most) {
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(w.surface.V.rows(), joints);
  for (const Influence& x : influences) {
    if (x.vertex < 0 || x.vertex >= w.to_welded.size())
      throw file_error(path, 0, "a weight names vertex " + std::to_string(x.vertex) + ", which does not exist");
    if (x.weight == 0) continue;
    const int i = w.to_welded[x.vertex];
    if (w.first[i] != x.vertex) continue;  // a split copy: its first file vertex speaks for it
    if (x.joint < 0 || x.joint >= joints)
      throw file_error(path, 0, "vertex " + std::to_string(x.vertex) + " names joint " + std::to_string(x.joint));
    if (!(x.weight > 0 && x.weight <= 1 + 1e-6))
      throw file_error(path, 0, "vertex " + std::to_string(x.vertex) + " has weight " + std::to_string(x.weight));
    W(i, x.joint) += x.weight;
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

namespace {

// Scene files are JSON, which holds UTF-8 only: a byte that starts no valid UTF-8 sequence (a Latin-1
// name in an old file, junk) becomes '?'.
std::string utf8_name(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    const size_t len = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
    bool ok = len > 0 && i + len <= s.size();
    for (size_t k = 1; ok && k < len; ++k) ok = (static_cast<unsigned char>(s[i + k]) >> 6) == 0x2;
    if (ok && len == 2) ok = c >= 0xC2;  // no overlong forms
    if (ok && len == 3) {
      const unsigned char d = static_cast<unsigned char>(s[i + 1]);
      ok = !(c == 0xE0 && d < 0xA0) && !(c == 0xED && d >= 0xA0);  // overlong, surrogates
    }
    if (ok && len == 4) {
      const unsigned char d = static_cast<unsigned char>(s[i + 1]);
      ok = !(c == 0xF0 && d < 0x90) && !(c == 0xF4 && d >= 0x90) && c <= 0xF4;
    }
    if (ok) out.append(s, i, len), i += len;
    else out += '?', ++i;
  }
  return out;
}

}  // namespace

Skeleton import_skeleton(const std::vector<ImportJoint>& joints, double diagonal, RigImportReport* report) {
  const int n = static_cast<int>(joints.size());
  // Heads from a file's float matrices: one joint's children start within its rounding of one point.
  const double eps = 1e-6 * diagonal;
  std::vector<Eigen::Vector3d> points;
  auto point = [&](const Eigen::Vector3d& p) {
    for (size_t i = 0; i < points.size(); ++i)
      if ((points[i] - p).norm() <= eps) return static_cast<int>(i);
    points.push_back(p);
    return static_cast<int>(points.size()) - 1;
  };
  std::vector<Eigen::Vector3d> head(n);
  std::vector<std::vector<int>> children(n);
  for (int j = 0; j < n; ++j) {
    head[j] = joints[j].bind.translation();
    if (joints[j].parent >= 0) children[joints[j].parent].push_back(j);
  }
  Skeleton s;
  for (int j = 0; j < n; ++j) {  // parents need not come first: tails below, once every head is known
    Bone b;
    b.a = point(head[j]);
    b.parent = joints[j].parent;
    b.name = joints[j].name.empty() ? "joint_" + std::to_string(j) : utf8_name(joints[j].name);
    s.bones.push_back(b);
  }
  auto tail_of = [&](int j) -> Eigen::Vector3d {
    const std::vector<int>& c = children[j];
    bool common = !c.empty();
    for (int k : c) common = common && (head[k] - head[c[0]]).norm() <= eps;
    if (common && (head[c[0]] - head[j]).norm() > eps) return head[c[0]];
    if (c.empty() && joints[j].end && (*joints[j].end - head[j]).norm() > eps) {
      ++report->bones_to_end;
      return *joints[j].end;
    }
    ++report->bones_along_axis;
    double len = 0;
    for (int k : c) len += (head[k] - head[j]).norm() / c.size();
    const int p = joints[j].parent;
    if (!(len > eps) && p >= 0) len = (head[j] - head[p]).norm();
    if (!(len > eps)) len = 0.05 * diagonal;
    return head[j] + len * (joints[j].bind.linear() * Eigen::Vector3d::UnitY()).normalized();
  };
  for (int j = 0; j < n; ++j) s.bones[j].b = point(tail_of(j));
  s.joints.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (size_t i = 0; i < points.size(); ++i) s.joints.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  return s;
}

PoseParams key_params(const Rig& rig, const std::vector<Eigen::Affine3d>& T, const std::string& path, double time) {
  PoseParams p = rest_pose_params(rig);
  for (size_t j = 0; j < T.size(); ++j) {
    const int parent = rig.skeleton.bones[j].parent;
    const Eigen::Affine3d X = parent >= 0 ? T[parent].inverse() * T[j] : T[j];
    const Eigen::Matrix3d L = X.linear();
    if (!((L.transpose() * L - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-6 && L.determinant() > 0))
      throw file_error(path, 0, "joint " + std::to_string(j) + " scales or shears at t = " + std::to_string(time) +
                                    " s: only rotations and translations are imported");
    const Eigen::Quaterniond q = Eigen::Quaterniond(L).normalized();
    const Eigen::Vector3d a = rig.skeleton.joints.row(rig.skeleton.bones[j].a).transpose();
    p.bone_rotation[j] = q;
    p.bone_translation[j] = X.translation() - a + q * a;
    if (p.bone_translation[j].norm() < 1e-12 * (1 + a.norm())) p.bone_translation[j].setZero();
  }
  return p;
}

SceneData imported_scene(const WeldedMesh& w, const std::vector<ImportJoint>& joints, Eigen::MatrixXd weights,
                         const std::string& path, RigImportReport* report) {
  report->vertices = static_cast<int>(w.surface.V.rows());
  report->triangles = static_cast<int>(w.surface.F.rows());
  report->joints = static_cast<int>(joints.size());
  const double diagonal = (w.surface.V.colwise().maxCoeff() - w.surface.V.colwise().minCoeff()).norm();
  SceneData s;
  s.surface = w.surface;
  s.surface_path = path;
  s.rig.skeleton = import_skeleton(joints, diagonal, report);
  s.pose = rest_pose_params(s.rig);
  s.weights = std::move(weights);
  s.bind_settings.max_influences = 0;  // every influence the file has
  return s;
}

void finish_import(SceneData& s, const std::string& path, RigImportReport* report) {
  report->keys = static_cast<int>(s.keys.size());
  report->duration = s.keys.empty() ? 0 : s.keys.back().time - s.keys.front().time;
  s.bind_stats.notes = {"imported from " + path + ": " + report->text()};
}

}  // namespace dfm
