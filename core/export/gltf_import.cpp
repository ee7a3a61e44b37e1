#include "core/export/gltf_import.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include <tiny_gltf.h>

#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace dfm {
namespace {

// Any accessor as doubles, one row per element (normalized integers mapped to [0,1]).
Eigen::MatrixXd read_accessor(const tinygltf::Model& m, int index, const std::string& path) {
  if (index < 0 || index >= static_cast<int>(m.accessors.size())) throw file_error(path, 0, "accessor index out of range");
  const tinygltf::Accessor& a = m.accessors[index];
  const int width = tinygltf::GetNumComponentsInType(a.type);
  const int csize = tinygltf::GetComponentSizeInBytes(a.componentType);
  if (width <= 0 || csize <= 0) throw file_error(path, 0, "accessor " + std::to_string(index) + " has an unknown type");
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(a.count, width);
  if (a.bufferView < 0) return out;  // all zeros by the spec (no sparse support needed here)
  if (a.sparse.isSparse) throw file_error(path, 0, "sparse accessors are not supported");
  const tinygltf::BufferView& v = m.bufferViews.at(a.bufferView);
  const tinygltf::Buffer& b = m.buffers.at(v.buffer);
  const size_t stride = v.byteStride ? v.byteStride : static_cast<size_t>(width * csize);
  const size_t start = v.byteOffset + a.byteOffset;
  if (a.count > 0 && start + stride * (a.count - 1) + width * csize > b.data.size())
    throw file_error(path, 0, "accessor " + std::to_string(index) + " runs past its buffer");
  for (size_t i = 0; i < a.count; ++i)
    for (int c = 0; c < width; ++c) {
      const unsigned char* p = b.data.data() + start + i * stride + c * csize;
      double x = 0;
      switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); x = f; break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: x = *p; if (a.normalized) x /= 255.0; break;
        case TINYGLTF_COMPONENT_TYPE_BYTE: x = static_cast<int8_t>(*p); if (a.normalized) x = std::max(x / 127.0, -1.0); break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t s; std::memcpy(&s, p, 2); x = s; if (a.normalized) x /= 65535.0; break; }
        case TINYGLTF_COMPONENT_TYPE_SHORT: { int16_t s; std::memcpy(&s, p, 2); x = s; if (a.normalized) x = std::max(x / 32767.0, -1.0); break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t u; std::memcpy(&u, p, 4); x = u; break; }
        default: throw file_error(path, 0, "accessor " + std::to_string(index) + ": unsupported component type");
      }
      out(i, c) = x;
    }
  return out;
}

GltfMeshData read_mesh(const tinygltf::Model& m, int mesh_index, const std::string& path) {
  const tinygltf::Mesh& mesh = m.meshes.at(mesh_index);
  if (mesh.primitives.size() != 1) throw file_error(path, 0, "mesh '" + mesh.name + "' must have exactly one primitive");
  const tinygltf::Primitive& p = mesh.primitives[0];
  if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != -1) throw file_error(path, 0, "only triangle meshes are read");
  GltfMeshData d;
  auto attr = [&](const std::string& name) { auto it = p.attributes.find(name); return it == p.attributes.end() ? -1 : it->second; };
  if (attr("POSITION") < 0) throw file_error(path, 0, "mesh '" + mesh.name + "' has no POSITION");
  d.V = read_accessor(m, attr("POSITION"), path);
  if (d.V.cols() != 3 || !d.V.allFinite()) throw file_error(path, 0, "mesh '" + mesh.name + "': POSITION must be finite VEC3");
  if (attr("NORMAL") >= 0) d.N = read_accessor(m, attr("NORMAL"), path);
  if (d.N.size() && (d.N.rows() != d.V.rows() || d.N.cols() != 3)) throw file_error(path, 0, "NORMAL does not match POSITION");
  const Eigen::MatrixXd idx = p.indices >= 0 ? read_accessor(m, p.indices, path) : Eigen::MatrixXd();
  const long n_idx = p.indices >= 0 ? idx.rows() : d.V.rows();
  if (n_idx % 3) throw file_error(path, 0, "triangle index count is not a multiple of 3");
  d.F.resize(n_idx / 3, 3);
  for (long i = 0; i < n_idx; ++i) {
    const double x = p.indices >= 0 ? idx(i, 0) : static_cast<double>(i);
    if (!(x >= 0 && x < static_cast<double>(d.V.rows()))) throw file_error(path, 0, "triangle index out of range");
    const long vi = static_cast<long>(x);
    d.F(i / 3, i % 3) = static_cast<int>(vi);
  }
  std::vector<Eigen::MatrixXd> J, W;
  for (int s = 0; attr("JOINTS_" + std::to_string(s)) >= 0; ++s) {
    if (attr("WEIGHTS_" + std::to_string(s)) < 0) throw file_error(path, 0, "JOINTS without WEIGHTS");
    J.push_back(read_accessor(m, attr("JOINTS_" + std::to_string(s)), path));
    W.push_back(read_accessor(m, attr("WEIGHTS_" + std::to_string(s)), path));
    for (const Eigen::MatrixXd* a : {&J.back(), &W.back()})
      if (a->rows() != d.V.rows() || a->cols() != 4 || !a->allFinite())
        throw file_error(path, 0, "JOINTS_" + std::to_string(s) + " / WEIGHTS_" + std::to_string(s) +
                                      " must be finite VEC4, one per vertex");
    if (J.back().size() && (J.back().minCoeff() < 0 || J.back().maxCoeff() > 65535))
      throw file_error(path, 0, "JOINTS_" + std::to_string(s) + " holds a joint index out of range");
  }
  if (!J.empty()) {
    d.joints.resize(d.V.rows(), 4 * J.size());
    d.weights.resize(d.V.rows(), 4 * J.size());
    for (size_t s = 0; s < J.size(); ++s) {
      d.joints.middleCols(4 * s, 4) = J[s].cast<int>();
      d.weights.middleCols(4 * s, 4) = W[s];
    }
  }
  for (const auto& t : p.targets) {
    auto it = t.find("POSITION");
    d.targets.push_back(it == t.end() ? Eigen::MatrixXd::Zero(d.V.rows(), 3) : read_accessor(m, it->second, path));
    if (d.targets.back().rows() != d.V.rows() || d.targets.back().cols() != 3)
      throw file_error(path, 0, "a morph target does not match POSITION");
  }
  d.default_weights = mesh.weights;
  d.default_weights.resize(d.targets.size(), 0.0);
  return d;
}

Eigen::Matrix4d node_local(const GltfNode& n) {
  if (n.has_matrix) return n.matrix;
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
  M.topLeftCorner<3, 3>() = n.rotation.normalized().toRotationMatrix() * n.scale.asDiagonal();
  M.topRightCorner<3, 1>() = n.translation;
  return M;
}

// glTF reference slerp (shortest arc).
Eigen::Vector4d slerp(Eigen::Vector4d a, Eigen::Vector4d b, double t) {
  double d = a.dot(b);
  if (d < 0) b = -b, d = -d;
  if (d > 0.9995) return ((1 - t) * a + t * b).normalized();
  const double theta = std::acos(std::min(d, 1.0));
  return (std::sin((1 - t) * theta) * a + std::sin(t * theta) * b) / std::sin(theta);
}

Eigen::VectorXd sample(const GltfChannel& c, double t) {
  const auto& T = c.times;
  if (t <= T.front()) return c.values.row(0).transpose();
  if (t >= T.back()) return c.values.row(T.size() - 1).transpose();
  const size_t k = std::upper_bound(T.begin(), T.end(), t) - T.begin() - 1;
  const double u = (t - T[k]) / (T[k + 1] - T[k]);
  const Eigen::VectorXd a = c.values.row(k).transpose(), b = c.values.row(k + 1).transpose();
  if (c.step) return a;
  if (c.cubic) {  // glTF 2.0, Appendix C: Hermite with tangents scaled by the interval
    const double d = T[k + 1] - T[k], u2 = u * u, u3 = u2 * u;
    const Eigen::VectorXd p = (2 * u3 - 3 * u2 + 1) * a + d * (u3 - 2 * u2 + u) * c.out_tangents.row(k).transpose() +
                              (-2 * u3 + 3 * u2) * b + d * (u3 - u2) * c.in_tangents.row(k + 1).transpose();
    return c.path == GltfChannel::Path::Rotation ? p.normalized() : p;
  }
  if (c.path == GltfChannel::Path::Rotation) return slerp(a, b, u);
  return (1 - u) * a + u * b;
}

// The file's model, by its extension (.glb binary, .gltf text).
tinygltf::Model load_model(const std::string& path) {
  require_readable_file(path);
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  const std::string ext = file_extension(path);
  bool ok;
  if (ext == "glb") ok = loader.LoadBinaryFromFile(&m, &err, &warn, path);
  else if (ext == "gltf") ok = loader.LoadASCIIFromFile(&m, &err, &warn, path);
  else throw file_error(path, 0, "not a .glb or .gltf file");
  if (!ok) throw file_error(path, 0, "cannot load glTF: " + err);
  return m;
}

// Nodes with their local transforms, morph weights and parents (the hierarchy must be a forest).
void read_nodes(const tinygltf::Model& m, const std::string& path, GltfDocument& doc) {
  doc.nodes.resize(m.nodes.size());
  for (size_t i = 0; i < m.nodes.size(); ++i) {
    const tinygltf::Node& s = m.nodes[i];
    GltfNode& n = doc.nodes[i];
    n.name = s.name;
    n.mesh = s.mesh;
    n.skin = s.skin;
    if (s.matrix.size() == 16) {
      n.has_matrix = true;
      for (int k = 0; k < 16; ++k) n.matrix(k % 4, k / 4) = s.matrix[k];
    }
    if (s.translation.size() == 3) n.translation = Eigen::Vector3d(s.translation[0], s.translation[1], s.translation[2]);
    if (s.rotation.size() == 4) n.rotation = Eigen::Quaterniond(s.rotation[3], s.rotation[0], s.rotation[1], s.rotation[2]);
    if (s.scale.size() == 3) n.scale = Eigen::Vector3d(s.scale[0], s.scale[1], s.scale[2]);
    n.weights = s.weights;
    if (s.extras.IsObject() && s.extras.Has("deform_rig") && s.extras.Get("deform_rig").IsString())
      n.deform_rig = s.extras.Get("deform_rig").Get<std::string>();
  }
  for (size_t i = 0; i < m.nodes.size(); ++i)
    for (int c : m.nodes[i].children) {
      if (c < 0 || c >= static_cast<int>(m.nodes.size()) || doc.nodes[c].parent >= 0)
        throw file_error(path, 0, "node hierarchy is not a forest");
      doc.nodes[c].parent = static_cast<int>(i);
    }
}

// The first skinned mesh's node and the first morphing (unskinned, with targets) one.
void find_mesh_nodes(const tinygltf::Model& m, GltfDocument& doc) {
  for (size_t i = 0; i < doc.nodes.size(); ++i) {
    const GltfNode& n = doc.nodes[i];
    if (doc.skinned_node < 0 && n.mesh >= 0 && n.skin >= 0) doc.skinned_node = static_cast<int>(i);
    if (doc.morph_node < 0 && n.mesh >= 0 && n.skin < 0 && !m.meshes.at(n.mesh).primitives.empty() &&
        !m.meshes[n.mesh].primitives[0].targets.empty())
      doc.morph_node = static_cast<int>(i);
  }
}

// The skinned mesh, its skin's joints and inverse bind matrices.
void read_skin(const tinygltf::Model& m, const std::string& path, GltfDocument& doc) {
  const GltfNode& n = doc.nodes[doc.skinned_node];
  doc.skinned = read_mesh(m, n.mesh, path);
  const tinygltf::Skin& skin = m.skins.at(n.skin);
  doc.joints = skin.joints;
  doc.inverse_bind.assign(skin.joints.size(), Eigen::Matrix4d::Identity());
  if (skin.inverseBindMatrices >= 0) {
    const Eigen::MatrixXd ibm = read_accessor(m, skin.inverseBindMatrices, path);
    if (ibm.rows() < static_cast<long>(skin.joints.size()) || ibm.cols() != 16)
      throw file_error(path, 0, "inverse bind matrices do not match the joints");
    for (size_t j = 0; j < skin.joints.size(); ++j)
      for (int k = 0; k < 16; ++k) doc.inverse_bind[j](k % 4, k / 4) = ibm(j, k);
  }
  if (doc.skinned.joints.size() && doc.skinned.joints.maxCoeff() >= static_cast<int>(doc.joints.size()))
    throw file_error(path, 0, "a JOINTS value exceeds the skin's joint count");
}

// One channel of an animation: its target, interpolation, times and values (weights as #times x #targets).
GltfChannel read_channel(const tinygltf::Model& m, const tinygltf::Animation& a, const tinygltf::AnimationChannel& ch,
                         const std::string& path) {
  const tinygltf::AnimationSampler& s = a.samplers.at(ch.sampler);
  GltfChannel c;
  c.node = ch.target_node;
  if (ch.target_path == "translation") c.path = GltfChannel::Path::Translation;
  else if (ch.target_path == "rotation") c.path = GltfChannel::Path::Rotation;
  else if (ch.target_path == "scale") c.path = GltfChannel::Path::Scale;
  else if (ch.target_path == "weights") c.path = GltfChannel::Path::Weights;
  else throw file_error(path, 0, "unknown animation path '" + ch.target_path + "'");
  if (s.interpolation == "STEP") c.step = true;
  else if (s.interpolation == "CUBICSPLINE") c.cubic = true;
  else if (s.interpolation != "LINEAR" && !s.interpolation.empty())
    throw file_error(path, 0, "interpolation " + s.interpolation + " is not supported");
  const Eigen::MatrixXd in = read_accessor(m, s.input, path);
  c.times.assign(in.data(), in.data() + in.rows());
  Eigen::MatrixXd out = read_accessor(m, s.output, path);
  const long elements = c.cubic ? 3 : 1;  // CUBICSPLINE: in-tangent, value, out-tangent per key
  if (c.path == GltfChannel::Path::Weights) {  // flat scalars: #times * elements x #targets
    if (out.cols() != 1) throw file_error(path, 0, "animation output for 'weights' must be scalars");
    const long per = c.times.empty() ? 0 : out.rows() / (elements * static_cast<long>(c.times.size()));
    Eigen::MatrixXd w(elements * static_cast<long>(c.times.size()), per);
    for (long i = 0; i < w.rows(); ++i)
      for (long j = 0; j < per; ++j) w(i, j) = out(i * per + j, 0);
    out = w;
  }
  if (out.rows() != elements * static_cast<long>(c.times.size()) || c.times.empty())
    throw file_error(path, 0, "animation sampler input and output counts differ");
  const long width = c.path == GltfChannel::Path::Rotation ? 4 : 3;
  if (c.path != GltfChannel::Path::Weights && out.cols() != width)
    throw file_error(path, 0, "animation output for '" + ch.target_path + "' has " + std::to_string(out.cols()) +
                                  " components, expected " + std::to_string(width));
  for (size_t i = 0; i < c.times.size(); ++i)
    if (!std::isfinite(c.times[i]) || (i > 0 && !(c.times[i] > c.times[i - 1])))
      throw file_error(path, 0, "animation input times must be finite and increasing");
  if (!out.allFinite()) throw file_error(path, 0, "animation output for '" + ch.target_path + "' is not finite");
  if (!c.cubic) {
    c.values = out;
    return c;
  }
  const long n = static_cast<long>(c.times.size());
  c.in_tangents.resize(n, out.cols());
  c.values.resize(n, out.cols());
  c.out_tangents.resize(n, out.cols());
  for (long k = 0; k < n; ++k) {
    c.in_tangents.row(k) = out.row(3 * k);
    c.values.row(k) = out.row(3 * k + 1);
    c.out_tangents.row(k) = out.row(3 * k + 2);
  }
  return c;
}

}  // namespace

GltfDocument read_gltf(const std::string& path) {
  const tinygltf::Model m = load_model(path);
  GltfDocument doc;
  try {
    read_nodes(m, path, doc);
    find_mesh_nodes(m, doc);
    if (doc.skinned_node >= 0) read_skin(m, path, doc);
    if (doc.morph_node >= 0) doc.morph = read_mesh(m, doc.nodes[doc.morph_node].mesh, path);
    if (!m.animations.empty())
      for (const auto& ch : m.animations[0].channels) doc.channels.push_back(read_channel(m, m.animations[0], ch, path));
  } catch (const std::out_of_range&) {  // an index into the file's arrays (.at()) past their end
    throw file_error(path, 0, "an index (buffer view, buffer, mesh, node or sampler) is out of range");
  }
  return doc;
}

std::vector<double> GltfDocument::key_times() const {
  std::vector<double> t;
  for (const auto& c : channels) {
    t.insert(t.end(), c.times.begin(), c.times.end());
    if (c.cubic)
      for (size_t k = 0; k + 1 < c.times.size(); ++k)
        for (int j = 1; j < kCubicSamplesPerInterval; ++j)
          t.push_back(c.times[k] + (c.times[k + 1] - c.times[k]) * j / kCubicSamplesPerInterval);
  }
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

std::vector<GltfNode> gltf_animated_nodes(const GltfDocument& doc, double t) {
  std::vector<GltfNode> nodes = doc.nodes;
  for (const auto& c : doc.channels) {
    if (c.node < 0 || c.node >= static_cast<int>(nodes.size()) || c.path == GltfChannel::Path::Weights) continue;
    const Eigen::VectorXd x = sample(c, t);
    GltfNode& n = nodes[c.node];
    if (c.path == GltfChannel::Path::Translation) n.translation = x.head<3>();
    else if (c.path == GltfChannel::Path::Scale) n.scale = x.head<3>();
    else n.rotation = Eigen::Quaterniond(x[3], x[0], x[1], x[2]).normalized();
  }
  return nodes;
}

std::vector<Eigen::Matrix4d> gltf_global_transforms(const std::vector<GltfNode>& nodes) {
  std::vector<Eigen::Matrix4d> G(nodes.size());
  std::vector<int> done(nodes.size(), 0);
  for (size_t i = 0; i < nodes.size(); ++i) {
    std::vector<int> chain;  // i and its ancestors not yet computed
    for (int k = static_cast<int>(i); k >= 0 && !done[k]; k = nodes[k].parent) {
      chain.push_back(k);
      if (chain.size() > nodes.size()) throw Error("glTF node hierarchy has a loop");
    }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const int k = *it, p = nodes[k].parent;
      G[k] = p >= 0 ? G[p] * node_local(nodes[k]) : node_local(nodes[k]);
      done[k] = 1;
    }
  }
  return G;
}

Eigen::MatrixXd gltf_skinned_positions(const GltfDocument& doc, double t) {
  if (doc.skinned_node < 0) throw Error("glTF document has no skinned mesh");
  const std::vector<Eigen::Matrix4d> G = gltf_global_transforms(gltf_animated_nodes(doc, t));
  std::vector<Eigen::Matrix4d> joint_matrix(doc.joints.size());
  for (size_t j = 0; j < doc.joints.size(); ++j) joint_matrix[j] = G.at(doc.joints[j]) * doc.inverse_bind[j];
  const GltfMeshData& m = doc.skinned;
  Eigen::MatrixXd base = m.V;
  const std::vector<double> mw = gltf_morph_weights(doc, doc.skinned_node, m, t);
  for (size_t i = 0; i < mw.size(); ++i)
    if (mw[i] != 0) base += mw[i] * m.targets[i];
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(m.V.rows(), 3);
  for (long v = 0; v < m.V.rows(); ++v) {
    const Eigen::Vector4d p(base(v, 0), base(v, 1), base(v, 2), 1.0);
    Eigen::Vector4d q = Eigen::Vector4d::Zero();
    for (long s = 0; s < m.weights.cols(); ++s)
      if (m.weights(v, s) != 0) q += m.weights(v, s) * (joint_matrix[m.joints(v, s)] * p);
    out.row(v) = q.head<3>().transpose();
  }
  return out;
}

std::vector<double> gltf_morph_weights(const GltfDocument& doc, int node, const GltfMeshData& mesh, double t) {
  std::vector<double> w = mesh.default_weights;
  if (node >= 0 && node < static_cast<int>(doc.nodes.size()) && !doc.nodes[node].weights.empty())
    w = doc.nodes[node].weights;
  w.resize(mesh.targets.size(), 0.0);
  for (const auto& c : doc.channels)
    if (c.node == node && c.path == GltfChannel::Path::Weights) {
      const Eigen::VectorXd x = sample(c, t);
      for (long i = 0; i < x.size() && i < static_cast<long>(w.size()); ++i) w[i] = x[i];
    }
  return w;
}

Eigen::MatrixXd gltf_morphed_positions(const GltfDocument& doc, double t) {
  if (doc.morph_node < 0) throw Error("glTF document has no morph-target mesh");
  const std::vector<double> w = gltf_morph_weights(doc, doc.morph_node, doc.morph, t);
  Eigen::MatrixXd V = doc.morph.V;
  for (size_t i = 0; i < w.size(); ++i) V += w[i] * doc.morph.targets[i];
  return V;
}

}  // namespace dfm
