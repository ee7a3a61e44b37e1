// CUBICSPLINE animation curves in a rigged glTF (issue 32; glTF 2.0 Appendix C): the reader follows the
// Hermite curve between keys, and the scene import keys it at kCubicSamplesPerInterval points an
// interval. The file is this program's export of a keyed capsule with its samplers rewritten by hand
// (tinygltf) to CUBICSPLINE with tangents that bend the curve away from the linear one.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>

#include <tiny_gltf.h>
#include <unistd.h>

#include "core/export/export_document.h"
#include "core/export/gltf_import.h"
#include "core/export/gltf_scene_import.h"
#include "core/scene/document.h"
#include "core/scene/key_surfaces.h"
#include "core/scene/script.h"
#include "core/util/error.h"
#include "tests/test_support.h"
#include "tests/rigged_test_util.h"

using namespace dfm;

namespace {

// An accessor's floats (#count x width), read by hand from its buffer view.
Eigen::MatrixXd floats(const tinygltf::Model& m, int accessor) {
  const tinygltf::Accessor& a = m.accessors[accessor];
  const tinygltf::BufferView& v = m.bufferViews[a.bufferView];
  const int width = tinygltf::GetNumComponentsInType(a.type);
  const int stride = v.byteStride ? static_cast<int>(v.byteStride) : 4 * width;
  const unsigned char* p = m.buffers[v.buffer].data.data() + v.byteOffset + a.byteOffset;
  Eigen::MatrixXd out(a.count, width);
  for (size_t i = 0; i < a.count; ++i)
    for (int j = 0; j < width; ++j) {
      float f;
      std::memcpy(&f, p + i * stride + 4 * j, 4);
      out(i, j) = f;
    }
  return out;
}

// Appends rows as a new float accessor of `type` (an animation output: no min/max needed).
int add_floats(tinygltf::Model& m, const Eigen::MatrixXd& rows, int type) {
  std::vector<unsigned char>& data = m.buffers[0].data;
  while (data.size() % 4) data.push_back(0);
  tinygltf::BufferView v;
  v.buffer = 0;
  v.byteOffset = data.size();
  v.byteLength = 4 * rows.size();
  for (Eigen::Index i = 0; i < rows.rows(); ++i)
    for (Eigen::Index j = 0; j < rows.cols(); ++j) {
      const float f = static_cast<float>(rows(i, j));
      const auto* b = reinterpret_cast<const unsigned char*>(&f);
      data.insert(data.end(), b, b + 4);
    }
  m.bufferViews.push_back(v);
  tinygltf::Accessor a;
  a.bufferView = static_cast<int>(m.bufferViews.size()) - 1;
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.count = rows.rows();
  a.type = type;
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size()) - 1;
}

struct CubicChannel {
  int node = -1;
  bool rotation = false;
  std::string path;
  std::vector<double> times;
  Eigen::MatrixXd in, value, out;  // per key
};

// Rewrites every sampler of animation 0 to CUBICSPLINE: a key's out-tangent twice the chord's slope to
// the next key, its in-tangent half the slope from the previous one (0 at the ends). Returns them.
std::vector<CubicChannel> make_cubic(tinygltf::Model& m) {
  std::vector<CubicChannel> out;
  tinygltf::Animation& a = m.animations.at(0);
  for (const tinygltf::AnimationChannel& ch : a.channels) {
    tinygltf::AnimationSampler& s = a.samplers[ch.sampler];
    CubicChannel c;
    c.node = ch.target_node;
    c.rotation = ch.target_path == "rotation";
    c.path = ch.target_path;
    const Eigen::MatrixXd t = floats(m, s.input);
    c.times.assign(t.data(), t.data() + t.rows());
    c.value = floats(m, s.output);
    const Eigen::Index n = c.value.rows();
    c.in = Eigen::MatrixXd::Zero(n, c.value.cols());
    c.out = c.in;
    for (Eigen::Index k = 0; k + 1 < n; ++k) {
      const Eigen::RowVectorXd slope = (c.value.row(k + 1) - c.value.row(k)) / (c.times[k + 1] - c.times[k]);
      c.out.row(k) = 2 * slope;
      c.in.row(k + 1) = 0.5 * slope;
    }
    Eigen::MatrixXd rows(3 * n, c.value.cols());
    for (Eigen::Index k = 0; k < n; ++k) rows.row(3 * k) = c.in.row(k), rows.row(3 * k + 1) = c.value.row(k), rows.row(3 * k + 2) = c.out.row(k);
    s.output = add_floats(m, rows, c.rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3);
    s.interpolation = "CUBICSPLINE";
    out.push_back(c);
  }
  return out;
}

// The specification's Hermite curve at t, written out here (normalized for a rotation).
Eigen::RowVectorXd hermite(const CubicChannel& c, double t) {
  size_t k = 0;
  while (k + 2 < c.times.size() && c.times[k + 1] <= t) ++k;
  const double d = c.times[k + 1] - c.times[k], s = (t - c.times[k]) / d;
  const Eigen::RowVectorXd p = (2 * s * s * s - 3 * s * s + 1) * c.value.row(k) + (s * s * s - 2 * s * s + s) * d * c.out.row(k) +
                               (-2 * s * s * s + 3 * s * s) * c.value.row(k + 1) + (s * s * s - s * s) * d * c.in.row(k + 1);
  return c.rotation ? Eigen::RowVectorXd(p.normalized()) : p;
}

}  // namespace

TEST_CASE("glTF CUBICSPLINE: the reader follows the Hermite curve, the import keys it", "[gltf][import]") {
  // A capsule along x with a chain of three bones and two keys (as the round trip test).
  Document d;
  const TriMesh m = test::keyed_capsule(d, "select 1\nrotate 70 0 0 1\nselect 2\nrotate -50 0 1 0\n");
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("dfm_gltf_cubic_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string linear = (dir / "linear.glb").string(), cubic = (dir / "cubic.glb").string();
  export_document_gltf(d, linear);

  tinygltf::Model model;
  tinygltf::TinyGLTF io;
  std::string err, warn;
  REQUIRE(io.LoadBinaryFromFile(&model, &err, &warn, linear));
  const std::vector<CubicChannel> channels = make_cubic(model);
  REQUIRE(io.WriteGltfSceneToFile(&model, cubic, false, true, false, true));

  // The reader: every channel's value at times inside the interval is the curve's.
  const GltfDocument g = read_gltf(cubic);
  bool bent = false;
  for (const CubicChannel& c : channels)
    for (double t : {0.1, 0.3, 0.5, 0.85}) {
      const GltfNode n = gltf_animated_nodes(g, t)[c.node];  // a copy: the vector is a temporary
      const Eigen::RowVectorXd want = hermite(c, t);
      if (c.rotation) {
        const Eigen::RowVector4d got(n.rotation.x(), n.rotation.y(), n.rotation.z(), n.rotation.w());
        CHECK(std::min((got - want).norm(), (got + want).norm()) < 1e-6);
        const Eigen::RowVectorXd lin = ((1 - t) * c.value.row(0) + t * c.value.row(1)).normalized();
        bent |= std::min((want - lin).norm(), (want + lin).norm()) > 1e-2;
      } else {
        CHECK(((c.path == "scale" ? n.scale : n.translation).transpose() - want).norm() < 1e-6);
      }
    }
  CHECK(bent);  // the tangents chosen make a curve that is not the linear one

  // The import: keys at the file's times and kCubicSamplesPerInterval - 1 more an interval; each key's
  // frame is the file's own skinning at that time.
  const SceneData s = import_gltf_scene(cubic);
  REQUIRE(static_cast<int>(s.keys.size()) == 1 + kCubicSamplesPerInterval);
  register_gltf_scene_importer();
  Document back;
  back.import_scene(cubic);
  const double diag = (m.V.colwise().maxCoeff() - m.V.colwise().minCoeff()).norm();
  for (const SceneKey& k : s.keys) {
    back.set_time(k.time);
    const Eigen::MatrixXd ours = posed_surface(back).V;
    const Eigen::MatrixXd file = gltf_skinned_positions(g, k.time);
    // The import welds the file's vertices: match each of ours to the nearest rest vertex of the file.
    double worst = 0;
    for (Eigen::Index i = 0; i < s.surface.V.rows(); ++i) {
      Eigen::Index j;
      (g.skinned.V.rowwise() - s.surface.V.row(i)).rowwise().squaredNorm().minCoeff(&j);
      worst = std::max(worst, (ours.row(i) - file.row(j)).norm());
    }
    INFO("key at " << k.time);
    CHECK(worst < 1e-5 * diag);
  }

  // A CUBICSPLINE sampler without three outputs a key is refused, naming the file.
  model.animations[0].samplers[0].interpolation = "CUBICSPLINE";
  model.animations[0].samplers[0].output = add_floats(model, channels[0].value, channels[0].rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3);
  const std::string bad = (dir / "bad_cubic.glb").string();
  REQUIRE(io.WriteGltfSceneToFile(&model, bad, false, true, false, true));
  CHECK_THROWS_WITH(read_gltf(bad), Catch::Contains("bad_cubic.glb") && Catch::Contains("counts differ"));
  std::filesystem::remove_all(dir);
}
