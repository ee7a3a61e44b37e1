#include "core/export/gltf_pca.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <Eigen/QR>
#include <tiny_gltf.h>

#include "core/export/gltf_buffer.h"
#include "core/skin/skin.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace dfm {
namespace {

// Unit vertex normals; a vertex without one (no area around it) gets +z so glTF's unit-length rule holds.
Eigen::MatrixXd unit_rows(Eigen::MatrixXd N) {
  for (Eigen::Index v = 0; v < N.rows(); ++v) {
    const double len = N.row(v).norm();
    if (len > 1e-12 && std::isfinite(len)) N.row(v) /= len;
    else N.row(v) << 0, 0, 1;
  }
  return N;
}

// #V x 3 from a vertex-major 3#V vector.
Eigen::MatrixXd as_rows(const Eigen::VectorXd& x) {
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(x.data(), x.size() / 3, 3);
}
Eigen::RowVectorXd as_vector(const Eigen::MatrixXd& M) {
  const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> R = M;
  return Eigen::Map<const Eigen::RowVectorXd>(R.data(), R.size());
}

// The affine reparametrization of the coefficients into [0, 1] (see the header).
struct UnitWeights {
  Eigen::MatrixXd W;        // #frames x k in [0, 1]
  Eigen::MatrixXd targets;  // 3#V x k: s_j B_j
  Eigen::MatrixXd base;     // #V x 3: mean + sum_j lo_j B_j
};

UnitWeights unit_weights(const PcaAnimation& a) {
  const int k = a.num_bases(), n = a.num_frames();
  UnitWeights u;
  u.W = Eigen::MatrixXd::Zero(n, k);
  u.targets = Eigen::MatrixXd::Zero(a.bases.rows(), k);
  Eigen::VectorXd shift = Eigen::VectorXd::Zero(a.bases.rows());
  for (int j = 0; j < k; ++j) {
    const double lo = a.coefficients.col(j).minCoeff(), hi = a.coefficients.col(j).maxCoeff();
    shift += lo * a.bases.col(j);
    if (hi > lo) {
      u.targets.col(j) = (hi - lo) * a.bases.col(j);
      u.W.col(j) = (a.coefficients.col(j).array() - lo) / (hi - lo);
    }
  }
  u.base = a.mean + as_rows(shift);
  return u;
}

struct FittedNormals {
  Eigen::MatrixXd base;    // #V x 3 unit
  Eigen::MatrixXd deltas;  // k x 3#V
  double mean_deg = 0, max_deg = 0, fixed_mean_deg = 0;
};

// Least squares over the frames: [1 W] [c; D] ~ N (the unit normals of every reconstructed frame); the
// base normal is c made unit (the glTF base NORMAL must be), then D is refit with it fixed.
FittedNormals fit_normals(const PcaAnimation& a, const UnitWeights& u) {
  const int n = a.num_frames(), k = a.num_bases(), nv = a.num_vertices();
  Eigen::MatrixXd N(n, 3 * nv);
  for (int i = 0; i < n; ++i) N.row(i) = as_vector(unit_rows(vertex_normals(pca_aligned_frame(a, i), a.F)));
  Eigen::MatrixXd A(n, k + 1);
  A << Eigen::VectorXd::Ones(n), u.W;
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  FittedNormals f;
  f.base = unit_rows(as_rows(qr.solve(N).row(0).transpose()));
  const Eigen::RowVectorXd n0 = as_vector(f.base);
  const Eigen::MatrixXd rhs = N.rowwise() - n0;
  f.deltas = k > 0 ? Eigen::MatrixXd(u.W.colPivHouseholderQr().solve(rhs)) : Eigen::MatrixXd(0, 3 * nv);
  double sum = 0, sum_fixed = 0;
  for (int i = 0; i < n; ++i) {
    const Eigen::RowVectorXd blended = n0 + (k > 0 ? Eigen::RowVectorXd(u.W.row(i) * f.deltas) : Eigen::RowVectorXd::Zero(3 * nv));
    for (int v = 0; v < nv; ++v) {
      const Eigen::Vector3d want = N.row(i).segment<3>(3 * v).transpose();
      auto angle = [&](const Eigen::Vector3d& x) {
        return std::atan2(x.cross(want).norm(), x.dot(want)) * 180.0 / M_PI;
      };
      const double e = angle(blended.segment<3>(3 * v).transpose());
      sum += e;
      f.max_deg = std::max(f.max_deg, e);
      sum_fixed += angle(n0.segment<3>(3 * v).transpose());
    }
  }
  f.mean_deg = sum / (double(n) * nv);
  f.fixed_mean_deg = sum_fixed / (double(n) * nv);
  return f;
}

void check_animation(const PcaAnimation& a) {
  const int nv = a.num_vertices(), n = a.num_frames();
  if (nv == 0 || a.mean.cols() != 3 || n == 0) throw Error("glTF export: the animation has no vertices or no frames");
  if (a.F.rows() == 0 || a.F.cols() != 3) throw Error("glTF export: the animation has no triangles");
  if (a.F.minCoeff() < 0 || a.F.maxCoeff() >= nv) throw Error("glTF export: a triangle index is out of range");
  if (a.bases.rows() != 3 * nv || a.coefficients.cols() != a.num_bases() ||
      static_cast<int>(a.motion.size()) != n || static_cast<int>(a.times.size()) != n)
    throw Error("glTF export: bases, coefficients, motions and times do not match");
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(a.times[i]) || a.times[i] < 0 ||
        (i > 0 && !(static_cast<float>(a.times[i]) > static_cast<float>(a.times[i - 1]))))
      throw Error("glTF export: frame times must be >= 0 and strictly increasing in single precision (frame " +
                  std::to_string(i) + ")");
}

// The morphing mesh: base positions (and fitted normals), triangles, one target per basis.
tinygltf::Mesh pca_mesh(GltfBufferBuilder& bb, const PcaAnimation& a, const UnitWeights& u, const PcaGltfOptions& options,
                        PcaGltfReport& report) {
  const int k = a.num_bases();
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = bb.add_floats(rows_to_floats(u.base), 3, TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
  FittedNormals normals;
  if (options.normals) {
    normals = fit_normals(a, u);
    report.normal_mean_angle_deg = normals.mean_deg;
    report.normal_max_angle_deg = normals.max_deg;
    report.fixed_normal_mean_angle_deg = normals.fixed_mean_deg;
    prim.attributes["NORMAL"] = bb.add_floats(rows_to_floats(normals.base), 3, TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER, false);
  }
  std::vector<uint32_t> idx(a.F.size());
  for (Eigen::Index f = 0; f < a.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) idx[3 * f + c] = static_cast<uint32_t>(a.F(f, c));
  prim.indices = bb.add_ints(idx, 1, TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  tinygltf::Value::Array names;
  for (int j = 0; j < k; ++j) {
    std::map<std::string, int> target;
    target["POSITION"] = bb.add_floats(rows_to_floats(as_rows(u.targets.col(j))), 3, TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
    if (options.normals)
      target["NORMAL"] = bb.add_floats(rows_to_floats(as_rows(normals.deltas.row(j).transpose())), 3, TINYGLTF_TYPE_VEC3,
                                       TINYGLTF_TARGET_ARRAY_BUFFER, false);
    prim.targets.push_back(target);
    names.emplace_back("base " + std::to_string(j + 1));
  }
  tinygltf::Mesh mesh;
  mesh.name = options.name;
  mesh.primitives.push_back(prim);
  if (k > 0) {
    for (int j = 0; j < k; ++j) mesh.weights.push_back(u.W(0, j));
    tinygltf::Value::Object extras;
    extras["targetNames"] = tinygltf::Value(names);
    mesh.extras = tinygltf::Value(extras);
  }
  return mesh;
}

// Per frame, in single precision: time, rigid motion and morph weights.
struct FrameTracks {
  std::vector<float> times, translation, rotation, weights;
};

// Rotations as unit quaternions, each on the side of the previous one so slerp takes the short way.
FrameTracks frame_tracks(const PcaAnimation& a, const UnitWeights& u) {
  FrameTracks f;
  Eigen::Quaterniond prev = Eigen::Quaterniond::Identity();
  for (int i = 0; i < a.num_frames(); ++i) {
    f.times.push_back(static_cast<float>(a.times[i]));
    Eigen::Quaterniond q = a.motion[i].rotation.normalized();
    if (i > 0 && q.dot(prev) < 0) q.coeffs() = -q.coeffs();
    prev = q;
    for (double c : {q.x(), q.y(), q.z(), q.w()}) f.rotation.push_back(static_cast<float>(c));
    for (int c = 0; c < 3; ++c) f.translation.push_back(static_cast<float>(a.motion[i].translation[c]));
    for (int j = 0; j < a.num_bases(); ++j) f.weights.push_back(static_cast<float>(u.W(i, j)));
  }
  return f;
}

// One node holding mesh 0 at the first frame's motion, its scene, and the animation of its tracks.
void add_node_and_animation(tinygltf::Model& model, GltfBufferBuilder& bb, const FrameTracks& f, bool morphs,
                            const std::string& name) {
  tinygltf::Node node;
  node.name = name;
  node.mesh = 0;
  node.translation = {f.translation[0], f.translation[1], f.translation[2]};
  node.rotation = {f.rotation[0], f.rotation[1], f.rotation[2], f.rotation[3]};
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.name = name;
  scene.nodes = {0};
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  tinygltf::Animation anim;
  anim.name = name;
  const int input = bb.add_floats(f.times, 1, TINYGLTF_TYPE_SCALAR, 0, true);
  auto channel = [&](const std::string& target_path, const std::vector<float>& values, int type, int width) {
    add_linear_channel(anim, bb, 0, target_path, input, values, type, width);
  };
  if (morphs) channel("weights", f.weights, TINYGLTF_TYPE_SCALAR, 1);
  channel("translation", f.translation, TINYGLTF_TYPE_VEC3, 3);
  channel("rotation", f.rotation, TINYGLTF_TYPE_VEC4, 4);
  model.animations.push_back(anim);
}

}  // namespace

PcaGltfReport export_pca_gltf(const std::string& path, const PcaAnimation& a, const PcaGltfOptions& options) {
  const std::string ext = file_extension(path);
  if (ext != "glb" && ext != "gltf") throw Error(path + ": glTF export needs a .glb or .gltf file name");
  check_animation(a);
  PcaGltfReport report;
  report.vertices = a.num_vertices();
  report.triangles = static_cast<int>(a.F.rows());
  report.frames = a.num_frames();
  report.morph_targets = a.num_bases();
  const UnitWeights u = unit_weights(a);

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "deform (dfm PCA animation exporter, tinygltf)";
  GltfBufferBuilder bb(model);
  model.meshes.push_back(pca_mesh(bb, a, u, options, report));
  add_node_and_animation(model, bb, frame_tracks(a, u), a.num_bases() > 0, options.name);
  write_gltf_model(path, model);
  return report;
}

}  // namespace dfm
