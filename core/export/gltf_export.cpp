#include "core/export/gltf_export.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include <tiny_gltf.h>

#include "core/export/gltf_buffer.h"
#include "core/export/gltf_rig_extras.h"
#include "core/export/prune.h"
#include "core/export/trs.h"
#include "core/skin/lbs.h"
#include "core/skin/skin.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace dfm {
namespace {

constexpr double kShearTolerance = 1e-6;

// Rest position of each handle's joint node (its rest global transform is a pure translation).
std::vector<Eigen::Vector3d> handle_rest_positions(const Rig& rig, const Eigen::MatrixXd& surface_V) {
  std::vector<Eigen::Vector3d> pos;
  for (const auto& p : rig.points) pos.push_back(p.position);
  for (const auto& b : rig.skeleton.bones) pos.push_back(rig.skeleton.joints.row(b.a).transpose());
  for (const auto& c : rig.cages)
    for (int i = 0; i < c.mesh.V.rows(); ++i) pos.push_back(c.mesh.V.row(i).transpose());
  for (const auto& r : rig.regions) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int v : r.vertices) {
      if (v < 0 || v >= surface_V.rows()) throw Error("region '" + r.name + "' names a vertex outside the surface");
      c += surface_V.row(v).transpose();
    }
    if (!r.vertices.empty()) c /= static_cast<double>(r.vertices.size());
    pos.push_back(c);
  }
  return pos;
}

struct JointLayout {
  std::vector<Eigen::Vector3d> rest;  // per handle
  std::vector<int> parent;            // per handle: parent handle, -1 = the "rig" node
};

JointLayout joint_layout(const Rig& rig, const Eigen::MatrixXd& surface_V) {
  JointLayout L;
  L.rest = handle_rest_positions(rig, surface_V);
  L.parent.assign(L.rest.size(), -1);
  const int first_bone = num_point_handles(rig);
  for (int b = 0; b < rig.skeleton.num_bones(); ++b) {
    const int p = rig.skeleton.bones[b].parent;
    if (p >= rig.skeleton.num_bones()) throw Error("bone " + std::to_string(b) + " has an invalid parent");
    if (p >= 0) L.parent[first_bone + b] = first_bone + p;
  }
  return L;
}

// Local TRS of every joint node for a pose: global_h = T_h * Translation(rest_h), local = global_parent^-1 * global_h.
std::vector<TrsFit> local_transforms(const JointLayout& L, const Pose& pose) {
  const int n = static_cast<int>(L.rest.size());
  std::vector<Eigen::Affine3d> global(n);
  for (int h = 0; h < n; ++h) global[h] = pose.transforms[h] * Eigen::Translation3d(L.rest[h]);
  std::vector<TrsFit> out(n);
  for (int h = 0; h < n; ++h) {
    const Eigen::Affine3d local = L.parent[h] < 0 ? global[h] : global[L.parent[h]].inverse() * global[h];
    out[h] = decompose_trs(local);
  }
  return out;
}

void check_pose(const Pose& pose, int handles, const std::string& what) {
  if (pose.size() != handles)
    throw Error(what + " has " + std::to_string(pose.size()) + " transforms, the rig has " + std::to_string(handles) +
                " handles");
  for (const auto& T : pose.transforms)
    if (!T.matrix().allFinite()) throw Error(what + " has a non-finite transform");
}

// Float weights whose float sum is as close to 1 as float allows (the validator sums the stored floats).
std::vector<float> float_weights_row(const Eigen::RowVectorXd& w) {
  std::vector<float> f(w.size());
  for (int j = 0; j < w.size(); ++j) f[j] = static_cast<float>(w[j]);
  const int big = static_cast<int>(std::max_element(f.begin(), f.end()) - f.begin());
  for (int it = 0; it < 3; ++it) {
    double s = 0;
    for (float x : f) s += x;
    f[big] = static_cast<float>(f[big] + (1.0 - s));
  }
  return f;
}

// Rest-space offsets d that make the stored pruned skin reproduce `target` at `pose`:
//   sum_j w_j T_j (p + d) = x   =>   d = L^-1 (x - sum_j w_j T_j p),  L = sum_j w_j linear(T_j).
// Vf: the file's (float) rest positions; weights: the stored (float) weights in influence order.
Eigen::MatrixXd residual_offsets(const Eigen::MatrixXd& Vf, const Influences& inf, const Eigen::MatrixXd& weights,
                                 const Pose& pose, const Eigen::MatrixXd& target) {
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(Vf.rows(), 3);
  for (int v = 0; v < Vf.rows(); ++v) {
    Eigen::Matrix<double, 3, 4> A = Eigen::Matrix<double, 3, 4>::Zero();
    for (int j = 0; j < inf.k(); ++j)
      if (weights(v, j) != 0) A += weights(v, j) * pose.transforms[inf.index(v, j)].matrix().topRows<3>();
    const Eigen::Vector3d p = Vf.row(v).transpose();
    const Eigen::Vector3d miss = target.row(v).transpose() - (A.leftCols<3>() * p + A.col(3));
    const Eigen::Vector3d d = A.leftCols<3>().colPivHouseholderQr().solve(miss);
    // A collapsed blend (no inverse) cannot be corrected in rest space: leave that vertex as skinned.
    if (d.allFinite() && (A.leftCols<3>() * d - miss).norm() <= 1e-9 * (1.0 + miss.norm())) D.row(v) = d.transpose();
  }
  return D;
}

struct NodeTrsSink {
  double max_shear = 0;
  int sheared = 0;
  std::vector<std::string> names;
  void add(const TrsFit& fit, const std::string& node) {
    max_shear = std::max(max_shear, fit.shear);
    if (fit.shear > kShearTolerance) {
      ++sheared;
      if (names.size() < 5 && std::find(names.begin(), names.end(), node) == names.end()) names.push_back(node);
    }
  }
};

void set_node_trs(tinygltf::Node& node, const Trs& t) {
  node.translation = {t.translation.x(), t.translation.y(), t.translation.z()};
  const Eigen::Quaterniond q = t.rotation.normalized();
  node.rotation = {q.x(), q.y(), q.z(), q.w()};
  node.scale = {t.scale.x(), t.scale.y(), t.scale.z()};
}

// Throws for input the file could not represent consistently.
void check_input(const std::string& path, const GltfExportInput& in, const GltfExportOptions& options) {
  const std::string ext = file_extension(path);
  if (ext != "glb" && ext != "gltf") throw Error(path + ": glTF export needs a .glb or .gltf file name");
  if (options.influences != 4 && options.influences != 8)
    throw Error("glTF export: influences must be 4 or 8, got " + std::to_string(options.influences));
  const TriMesh& S = in.surface;
  const int nv = S.num_vertices(), nh = num_handles(in.rig);
  if (nv == 0 || S.num_faces() == 0) throw Error("glTF export: the surface has no triangles");
  if (S.V.cols() != 3 || S.F.cols() != 3) throw Error("glTF export: the surface must be #V x 3 and #F x 3");
  if (S.F.minCoeff() < 0 || S.F.maxCoeff() >= nv) throw Error("glTF export: a face index is out of range");
  if (nh == 0) throw Error("glTF export: the rig has no handles");
  if (nh > 65535) throw Error("glTF export: more than 65535 handles");
  if (in.weights.rows() != nv || in.weights.cols() != nh)
    throw Error("glTF export: weights are " + std::to_string(in.weights.rows()) + " x " +
                std::to_string(in.weights.cols()) + ", expected " + std::to_string(nv) + " x " + std::to_string(nh) +
                " (surface vertices x handles)");
  if (in.current.size()) check_pose(in.current, nh, "the current pose");
  for (size_t k = 0; k < in.keys.size(); ++k) {
    check_pose(in.keys[k].pose, nh, "key " + std::to_string(k));
    if (!std::isfinite(in.keys[k].time) || in.keys[k].time < 0 || (k > 0 && in.keys[k].time <= in.keys[k - 1].time))
      throw Error("glTF export: key times must be finite, >= 0 and strictly increasing (key " + std::to_string(k) + ")");
  }
  if (!in.exact.empty() && in.exact.size() != in.keys.size() + 1)
    throw Error("glTF export: exact surfaces must be one per key plus the current pose");
  for (const Eigen::MatrixXd& X : in.exact)
    if (X.rows() != nv || X.cols() != 3 || !X.allFinite()) throw Error("glTF export: an exact surface is not #V x 3 finite");
  if (in.morph_frames.size() != in.morph_times.size())
    throw Error("glTF export: morph frames and morph times differ in count");
  for (size_t i = 0; i < in.morph_frames.size(); ++i) {
    if (in.morph_frames[i].rows() != nv || in.morph_frames[i].cols() != 3)
      throw Error("glTF export: morph frame " + std::to_string(i) + " is not #V x 3");
    if (!std::isfinite(in.morph_times[i]) || in.morph_times[i] < 0 || (i > 0 && in.morph_times[i] <= in.morph_times[i - 1]))
      throw Error("glTF export: morph times must be finite, >= 0 and strictly increasing");
  }
}

// What the file should show at key k (-1: the current pose), posed by `pose`.
Eigen::MatrixXd shown_surface(const GltfExportInput& in, const Pose& pose, int key) {
  if (!in.exact.empty()) return in.exact[key < 0 ? in.keys.size() : static_cast<size_t>(key)];
  return lbs(in.surface.V, in.weights, pose);
}

// The kept influences (refit if asked) and what pruning costs over every pose that will be shown.
Influences pruned_influences(const GltfExportInput& in, const GltfExportOptions& options, const Pose& current,
                             GltfExportReport& report) {
  const TriMesh& S = in.surface;
  Influences inf = prune_for_export(in.weights, options.influences);
  if (options.refit) {
    std::vector<Pose> shown = {current};
    for (const auto& k : in.keys) shown.push_back(k.pose);
    report.refit_vertices = refit_influences(inf, S.V, in.weights, shown);
  }
  const Eigen::MatrixXd Wp = influences_to_dense(inf, num_handles(in.rig));
  auto prune_error = [&](const Pose& pose, int key) {
    return (shown_surface(in, pose, key) - lbs(S.V, Wp, pose)).rowwise().norm().maxCoeff();
  };
  report.max_prune_error = prune_error(current, -1);
  for (size_t k = 0; k < in.keys.size(); ++k) {
    const double e = prune_error(in.keys[k].pose, static_cast<int>(k));
    if (e > report.max_prune_error) report.max_prune_error = e, report.max_prune_error_key = static_cast<int>(k);
  }
  return inf;
}

// The rest mesh's shared accessors: positions, unit normals, triangle indices.
struct MeshAccessors {
  int position = -1, normal = -1, indices = -1;
  Eigen::MatrixXd unit_normals;
};

MeshAccessors add_rest_mesh(GltfBufferBuilder& bb, const TriMesh& S) {
  const int nv = S.num_vertices();
  MeshAccessors a;
  a.unit_normals = S.N.rows() == nv && S.N.cols() == 3 ? S.N : vertex_normals(S.V, S.F);
  for (int v = 0; v < nv; ++v) {
    const double len = a.unit_normals.row(v).norm();
    if (len > 0 && std::isfinite(len)) a.unit_normals.row(v) /= len;
    else a.unit_normals.row(v) << 0, 0, 1;
  }
  a.position = bb.add_floats(rows_to_floats(S.V), 3, TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
  a.normal = bb.add_floats(rows_to_floats(a.unit_normals), 3, TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER, false);
  std::vector<uint32_t> idx(S.F.size());
  for (int f = 0; f < S.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) idx[3 * f + k] = static_cast<uint32_t>(S.F(f, k));
  a.indices = bb.add_ints(idx, 1, TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                          TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  return a;
}

tinygltf::Primitive mesh_primitive(const MeshAccessors& a) {
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.indices = a.indices;
  prim.attributes["POSITION"] = a.position;
  prim.attributes["NORMAL"] = a.normal;
  return prim;
}

// JOINTS_s / WEIGHTS_s sets of four. Returns the weights as the file holds them (float), for the residuals.
Eigen::MatrixXd add_skin_attributes(GltfBufferBuilder& bb, tinygltf::Primitive& prim, const Influences& inf,
                                    int influences, int nh) {
  const int nv = static_cast<int>(inf.weight.rows()), sets = influences / 4;
  std::vector<std::vector<float>> wsets(sets, std::vector<float>(4 * nv));
  Eigen::MatrixXd stored_w(nv, influences);
  for (int v = 0; v < nv; ++v) {
    const std::vector<float> row = float_weights_row(inf.weight.row(v));
    for (int j = 0; j < influences; ++j) wsets[j / 4][4 * v + j % 4] = row[j], stored_w(v, j) = row[j];
  }
  for (int s = 0; s < sets; ++s) {
    int jacc;
    if (nh <= 256) {
      std::vector<uint8_t> j(4 * nv);
      for (int v = 0; v < nv; ++v)
        for (int c = 0; c < 4; ++c) j[4 * v + c] = static_cast<uint8_t>(inf.index(v, 4 * s + c));
      jacc = bb.add_ints(j, 4, TINYGLTF_TYPE_VEC4, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TARGET_ARRAY_BUFFER);
    } else {
      std::vector<uint16_t> j(4 * nv);
      for (int v = 0; v < nv; ++v)
        for (int c = 0; c < 4; ++c) j[4 * v + c] = static_cast<uint16_t>(inf.index(v, 4 * s + c));
      jacc = bb.add_ints(j, 4, TINYGLTF_TYPE_VEC4, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TARGET_ARRAY_BUFFER);
    }
    prim.attributes["JOINTS_" + std::to_string(s)] = jacc;
    prim.attributes["WEIGHTS_" + std::to_string(s)] =
        bb.add_floats(wsets[s], 4, TINYGLTF_TYPE_VEC4, TINYGLTF_TARGET_ARRAY_BUFFER, false);
  }
  return stored_w;
}

// Residual morph targets: one per key, then the current pose unless it is one of the keys; the target
// shown at rest is the current pose's.
struct ResidualTargets {
  std::vector<int> key;  // per target: key index, or -1 for the current pose
  int current = -1;
};

ResidualTargets add_residual_targets(GltfBufferBuilder& bb, tinygltf::Primitive& prim, const GltfExportInput& in,
                                     const GltfExportOptions& options, const Influences& inf,
                                     const Eigen::MatrixXd& stored_w, const Pose& current, GltfExportReport& report) {
  ResidualTargets r;
  const double tol = options.residual_morph_tolerance;
  if (!(tol > 0 && report.max_prune_error > tol * report.bbox_diagonal)) return r;
  for (size_t k = 0; k < in.keys.size(); ++k) {
    r.key.push_back(static_cast<int>(k));
    if (r.current < 0 && in.keys[k].pose.transforms.size() == current.transforms.size() &&
        std::equal(current.transforms.begin(), current.transforms.end(), in.keys[k].pose.transforms.begin(),
                   [](const Eigen::Affine3d& a, const Eigen::Affine3d& b) { return a.matrix() == b.matrix(); }))
      r.current = static_cast<int>(k);
  }
  if (r.current < 0) r.current = static_cast<int>(r.key.size()), r.key.push_back(-1);
  const TriMesh& S = in.surface;
  const Eigen::MatrixXd Vf = S.V.cast<float>().cast<double>();
  for (int key : r.key) {
    const Pose& pose = key < 0 ? current : in.keys[key].pose;
    const Eigen::MatrixXd D = residual_offsets(Vf, inf, stored_w, pose, shown_surface(in, pose, key));
    std::map<std::string, int> target;
    target["POSITION"] = bb.add_floats(rows_to_floats(D), 3, TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
    prim.targets.push_back(target);
  }
  report.residual_targets = static_cast<int>(r.key.size());
  std::ostringstream note;
  note << options.influences << " influences miss " << (in.exact.empty() ? "LBS with all weights" : "the document's surface")
       << " by up to " << report.max_prune_error << " ("
       << report.max_prune_error / report.bbox_diagonal << " of the bbox diagonal): the misses at the "
       << (in.keys.empty() ? "current pose" : "keys") << " are stored as " << r.key.size()
       << " residual morph target(s) of the skinned mesh";
  report.notes.push_back(note.str());
  return r;
}

// Nodes: 0 = skinned mesh, 1 = "rig", 2 + h = handle h's joint (at the current pose), and the skin.
// Returns the joint nodes' names.
std::vector<std::string> add_rig(tinygltf::Model& model, GltfBufferBuilder& bb, const GltfExportInput& in,
                                 const JointLayout& layout, const Pose& current, NodeTrsSink& shear) {
  const int nh = num_handles(in.rig);
  tinygltf::Node mesh_node;
  mesh_node.name = in.name;
  mesh_node.mesh = 0;
  mesh_node.skin = 0;
  model.nodes.push_back(mesh_node);
  tinygltf::Node rig_node;
  rig_node.name = "rig";
  // The rig itself, so that an import of this file gets the same handles back (gltf_rig_extras.h).
  rig_node.extras = tinygltf::Value(tinygltf::Value::Object{{"deform_rig", tinygltf::Value(rig_extras_json(in.rig))}});
  model.nodes.push_back(rig_node);
  const std::vector<TrsFit> cur = local_transforms(layout, current);
  std::vector<std::string> names(nh);
  for (int h = 0; h < nh; ++h) {
    tinygltf::Node n;
    names[h] = std::to_string(h) + ":" + handle_name(in.rig, h);
    n.name = names[h];
    set_node_trs(n, cur[h].trs);
    shear.add(cur[h], names[h]);
    model.nodes.push_back(n);
  }
  for (int h = 0; h < nh; ++h) {
    const int parent_node = layout.parent[h] < 0 ? 1 : 2 + layout.parent[h];
    model.nodes[parent_node].children.push_back(2 + h);
  }
  tinygltf::Skin skin;
  skin.name = in.name + "-skin";
  skin.skeleton = 1;
  std::vector<float> ibm(16 * nh);
  for (int h = 0; h < nh; ++h) {
    skin.joints.push_back(2 + h);
    const Eigen::Matrix4d M = Eigen::Affine3d(Eigen::Translation3d(-layout.rest[h])).matrix();
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) ibm[16 * h + 4 * c + r] = static_cast<float>(M(r, c));  // column-major
  }
  skin.inverseBindMatrices = bb.add_floats(ibm, 16, TINYGLTF_TYPE_MAT4, 0, false);
  model.skins.push_back(skin);
  tinygltf::Scene scene;
  scene.name = "skinned";
  scene.nodes = {0, 1};
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  return names;
}

// The keys as TRS channels of the joint nodes, and (with residual targets) at key k only target k.
void add_key_channels(tinygltf::Animation& anim, GltfBufferBuilder& bb, const GltfExportInput& in,
                      const JointLayout& layout, const std::vector<std::string>& names, int residual_targets,
                      NodeTrsSink& shear) {
  if (in.keys.empty()) return;
  const int nh = num_handles(in.rig), nk = static_cast<int>(in.keys.size());
  std::vector<float> times;
  for (const auto& k : in.keys) times.push_back(static_cast<float>(k.time));
  for (size_t k = 1; k < times.size(); ++k)
    if (!(times[k] > times[k - 1])) throw Error("glTF export: key times collide in single precision");
  const int input = bb.add_floats(times, 1, TINYGLTF_TYPE_SCALAR, 0, true);
  std::vector<std::vector<TrsFit>> locals(nk);
  for (int k = 0; k < nk; ++k) {
    locals[k] = local_transforms(layout, in.keys[k].pose);
    for (int h = 0; h < nh; ++h) shear.add(locals[k][h], names[h]);
  }
  for (int h = 0; h < nh; ++h) {
    std::vector<float> t, r, s;
    Eigen::Quaterniond prev = Eigen::Quaterniond::Identity();
    for (int k = 0; k < nk; ++k) {
      const Trs& x = locals[k][h].trs;
      for (int c = 0; c < 3; ++c) t.push_back(static_cast<float>(x.translation[c]));
      for (int c = 0; c < 3; ++c) s.push_back(static_cast<float>(x.scale[c]));
      // q and -q are the same rotation; pick the one nearer the previous key so slerp takes the short way.
      Eigen::Quaterniond q = x.rotation.normalized();
      if (k > 0 && q.dot(prev) < 0) q.coeffs() = -q.coeffs();
      prev = q;
      for (double c : {q.x(), q.y(), q.z(), q.w()}) r.push_back(static_cast<float>(c));
    }
    add_linear_channel(anim, bb, 2 + h, "translation", input, t, TINYGLTF_TYPE_VEC3, 3);
    add_linear_channel(anim, bb, 2 + h, "rotation", input, r, TINYGLTF_TYPE_VEC4, 4);
    add_linear_channel(anim, bb, 2 + h, "scale", input, s, TINYGLTF_TYPE_VEC3, 3);
  }
  if (residual_targets > 0) {
    std::vector<float> w(nk * residual_targets, 0.0f);
    for (int k = 0; k < nk; ++k) w[k * residual_targets + k] = 1.0f;
    add_linear_channel(anim, bb, 0, "weights", input, w, TINYGLTF_TYPE_SCALAR, 1);
  }
}

// Baked frames: an unskinned copy of the mesh in its own scene, one morph target per frame, and at frame
// i's time only target i.
void add_baked_frames(tinygltf::Model& model, tinygltf::Animation& anim, GltfBufferBuilder& bb,
                      const GltfExportInput& in, const MeshAccessors& acc) {
  if (in.morph_frames.empty()) return;
  const TriMesh& S = in.surface;
  const int nf = static_cast<int>(in.morph_frames.size());
  tinygltf::Primitive bp = mesh_primitive(acc);
  for (int i = 0; i < nf; ++i) {
    const Eigen::MatrixXd dV = in.morph_frames[i] - S.V;
    const Eigen::MatrixXd dN = vertex_normals(in.morph_frames[i], S.F) - acc.unit_normals;
    std::map<std::string, int> target;
    target["POSITION"] = bb.add_floats(rows_to_floats(dV), 3, TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
    target["NORMAL"] = bb.add_floats(rows_to_floats(dN), 3, TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER, false);
    bp.targets.push_back(target);
  }
  tinygltf::Mesh bm;
  bm.name = in.name + "-baked";
  bm.primitives.push_back(bp);
  bm.weights.assign(nf, 0.0);
  model.meshes.push_back(bm);
  tinygltf::Node bn;
  bn.name = in.name + "-baked";
  bn.mesh = static_cast<int>(model.meshes.size()) - 1;
  model.nodes.push_back(bn);
  tinygltf::Scene bs;
  bs.name = "baked";
  bs.nodes = {static_cast<int>(model.nodes.size()) - 1};
  model.scenes.push_back(bs);
  std::vector<float> times, w(nf * nf, 0.0f);
  for (int i = 0; i < nf; ++i) times.push_back(static_cast<float>(in.morph_times[i]));
  for (size_t k = 1; k < times.size(); ++k)
    if (!(times[k] > times[k - 1])) throw Error("glTF export: morph times collide in single precision");
  for (int i = 0; i < nf; ++i) w[i * nf + i] = 1.0f;
  const int input = bb.add_floats(times, 1, TINYGLTF_TYPE_SCALAR, 0, true);
  add_linear_channel(anim, bb, bs.nodes[0], "weights", input, w, TINYGLTF_TYPE_SCALAR, 1);
}

void report_shear(const NodeTrsSink& shear, GltfExportReport& report) {
  report.max_shear = shear.max_shear;
  report.sheared_transforms = shear.sheared;
  if (shear.sheared == 0) return;
  std::string list;
  for (const auto& n : shear.names) list += (list.empty() ? "" : ", ") + n;
  report.notes.push_back(std::to_string(shear.sheared) +
                         " joint transform(s) have shear a glTF TRS cannot express (max relative residual " +
                         std::to_string(shear.max_shear) + "), e.g. " + list);
}

}  // namespace

GltfExportReport export_gltf(const std::string& path, const GltfExportInput& in, const GltfExportOptions& options) {
  check_input(path, in, options);
  const TriMesh& S = in.surface;
  const int nh = num_handles(in.rig);
  const Pose current = in.current.size() ? in.current : identity_pose(nh);
  GltfExportReport report;
  report.vertices = S.num_vertices();
  report.triangles = S.num_faces();
  report.joints = nh;
  report.influences = options.influences;
  report.keys = static_cast<int>(in.keys.size());
  report.morph_targets = static_cast<int>(in.morph_frames.size());
  report.bbox_diagonal = (S.V.colwise().maxCoeff() - S.V.colwise().minCoeff()).norm();
  const Influences inf = pruned_influences(in, options, current, report);

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "deform (dfm glTF exporter, tinygltf)";
  GltfBufferBuilder bb(model);
  const MeshAccessors acc = add_rest_mesh(bb, S);
  tinygltf::Primitive prim = mesh_primitive(acc);
  const Eigen::MatrixXd stored_w = add_skin_attributes(bb, prim, inf, options.influences, nh);
  const ResidualTargets residual = add_residual_targets(bb, prim, in, options, inf, stored_w, current, report);
  tinygltf::Mesh mesh;
  mesh.name = in.name;
  mesh.primitives.push_back(prim);
  if (!residual.key.empty()) {
    mesh.weights.assign(residual.key.size(), 0.0);
    mesh.weights[residual.current] = 1.0;
  }
  model.meshes.push_back(mesh);

  const JointLayout layout = joint_layout(in.rig, S.V);
  NodeTrsSink shear;
  const std::vector<std::string> names = add_rig(model, bb, in, layout, current, shear);
  tinygltf::Animation anim;
  anim.name = "keys";
  add_key_channels(anim, bb, in, layout, names, static_cast<int>(residual.key.size()), shear);
  add_baked_frames(model, anim, bb, in, acc);
  if (!anim.channels.empty()) model.animations.push_back(anim);
  report_shear(shear, report);
  write_gltf_model(path, model);
  return report;
}

}  // namespace dfm
