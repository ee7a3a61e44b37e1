// A compressed animation as glTF morph targets (Alexa 2003, 7.3; core/export/gltf_pca.h): read back,
// evaluated here from the file's raw numbers (base + sum_j w_j target_j, then the node's T * R), it
// reproduces every frame; the Khronos validator reports no error and no warning.
#include <filesystem>

#include <catch2/catch.hpp>
#include <tiny_gltf.h>

#include "core/anim/pca_animation.h"
#include "core/export/gltf_import.h"
#include "core/export/gltf_pca.h"
#include "core/util/error.h"
#include "tests/pca_test_frames.h"
#include "tests/test_gltf_validator.h"

using namespace dfm;
using Catch::Contains;
namespace fs = std::filesystem;

namespace {

const GltfChannel& channel(const GltfDocument& doc, GltfChannel::Path path) {
  for (const auto& c : doc.channels)
    if (c.path == path) return c;
  FAIL("no channel of that path");
  return doc.channels.front();
}

// A float accessor as rows, read straight from the buffer (tightly packed, as the exporter writes).
Eigen::MatrixXd float_rows(const tinygltf::Model& m, int index) {
  const tinygltf::Accessor& a = m.accessors.at(index);
  REQUIRE(a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT);
  const int width = tinygltf::GetNumComponentsInType(a.type);
  const tinygltf::BufferView& v = m.bufferViews.at(a.bufferView);
  const float* p = reinterpret_cast<const float*>(m.buffers.at(v.buffer).data.data() + v.byteOffset + a.byteOffset);
  Eigen::MatrixXd out(a.count, width);
  for (size_t i = 0; i < a.count; ++i)
    for (int c = 0; c < width; ++c) out(i, c) = p[i * width + c];
  return out;
}

tinygltf::Model load(const std::string& path) {
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  REQUIRE(loader.LoadBinaryFromFile(&m, &err, &warn, path));
  return m;
}

// Area-weighted vertex normals, made unit.
Eigen::MatrixXd unit_normals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(V.rows(), 3);
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::RowVector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::RowVector3d n = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n;
  }
  return N.rowwise().normalized();
}

double angle_deg(const Eigen::RowVector3d& a, const Eigen::RowVector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI;
}

// Frame i from the file: the channels' values at key i (LINEAR samplers pass exactly through their keys).
Eigen::MatrixXd file_frame(const GltfDocument& doc, int i, const Eigen::MatrixXd& unmorphed) {
  Eigen::MatrixXd p = doc.morph_node >= 0 ? doc.morph.V : unmorphed;
  if (doc.morph_node >= 0) {
    const GltfChannel& w = channel(doc, GltfChannel::Path::Weights);
    for (size_t j = 0; j < doc.morph.targets.size(); ++j) p += w.values(i, j) * doc.morph.targets[j];
  }
  const GltfChannel& t = channel(doc, GltfChannel::Path::Translation);
  const GltfChannel& r = channel(doc, GltfChannel::Path::Rotation);
  const Eigen::Quaterniond q(r.values(i, 3), r.values(i, 0), r.values(i, 1), r.values(i, 2));
  const Eigen::Matrix3d R = q.normalized().toRotationMatrix();
  return (p * R.transpose()).rowwise() + t.values.row(i);
}

struct Fixture {
  TriMesh bar = test::pca_bar();
  std::vector<Eigen::MatrixXd> frames = test::bending_bar_frames(bar, 12, 1e-3);
  PcaDecomposition d = decompose_frames(frames);
  std::vector<double> times = frame_times(12, 24);
};

}  // namespace

TEST_CASE("pca glTF: morph targets + weights + node TRS reproduce every frame", "[pca][gltf]") {
  Fixture fx;
  const fs::path dir = test::gltf_temp_dir("pca");
  const double diag = fx.d.bbox_diagonal;
  for (int k : {0, 3, 12}) {
    INFO("k = " << k);
    const PcaAnimation a = pca_animation(fx.d, k, fx.bar.F, fx.times);
    const PcaErrors e = pca_errors(fx.d, a);
    const std::string path = (dir / ("bar" + std::to_string(k) + ".glb")).string();
    const PcaGltfReport rep = export_pca_gltf(path, a);
    CHECK(rep.morph_targets == k);
    const GltfDocument doc = read_gltf(path);
    REQUIRE(doc.skinned_node < 0);
    if (k > 0) {
      REQUIRE(doc.morph_node == 0);
      REQUIRE(doc.morph.targets.size() == static_cast<size_t>(k));
      CHECK(doc.morph.F == fx.bar.F);
      const GltfChannel& w = channel(doc, GltfChannel::Path::Weights);
      CHECK(w.values.minCoeff() >= 0.0);  // weights in [0, 1]: plays in viewers that clamp sliders
      CHECK(w.values.maxCoeff() <= 1.0);
      for (int j = 0; j < k; ++j) CHECK(doc.morph.default_weights[j] == Approx(w.values(0, j)));
    }
    const GltfChannel& t = channel(doc, GltfChannel::Path::Translation);
    REQUIRE(t.times.size() == 12u);
    // Without morph targets the reader keeps no mesh: take the base POSITION from the buffer.
    const Eigen::MatrixXd mean = k > 0 ? Eigen::MatrixXd() : float_rows(load(path), 0);
    for (int i = 0; i < 12; ++i) {
      INFO("frame " << i);
      CHECK(t.times[i] == Approx(fx.times[i]).margin(1e-7));
      const Eigen::MatrixXd got = file_frame(doc, i, mean);
      // The file is float32: within 1e-5 of the diagonal of the double reconstruction ...
      CHECK((got - pca_frame(a, i)).rowwise().norm().maxCoeff() < 1e-5 * diag);
      // ... and as far from the input frame as the reconstruction error says.
      CHECK(std::abs((got - fx.frames[i]).norm() - e.frobenius[i]) < 1e-5 * diag);
    }
  }
  fs::remove_all(dir);
}

TEST_CASE("pca glTF: the NORMAL deltas, blended and renormalized, follow the frames' normals", "[pca][gltf]") {
  Fixture fx;
  const fs::path dir = test::gltf_temp_dir("pca_normals");
  const int k = 6;
  const PcaAnimation a = pca_animation(fx.d, k, fx.bar.F, fx.times);
  const std::string path = (dir / "n.glb").string();
  const PcaGltfReport rep = export_pca_gltf(path, a);
  const tinygltf::Model m = load(path);
  const tinygltf::Primitive& prim = m.meshes.at(0).primitives.at(0);
  const Eigen::MatrixXd N0 = float_rows(m, prim.attributes.at("NORMAL"));
  CHECK((N0.rowwise().norm().array() - 1.0).abs().maxCoeff() < 1e-6);  // glTF wants unit base normals
  const GltfDocument doc = read_gltf(path);
  const GltfChannel& w = channel(doc, GltfChannel::Path::Weights);
  double blended_sum = 0, fixed_sum = 0, worst = 0;
  const int nv = a.num_vertices();
  for (int i = 0; i < a.num_frames(); ++i) {
    Eigen::MatrixXd N = N0;
    for (int j = 0; j < k; ++j) N += w.values(i, j) * float_rows(m, prim.targets.at(j).at("NORMAL"));
    // The frame's true normals, in the mesh's (aligned) space: the morphed positions' own normals.
    Eigen::MatrixXd P = doc.morph.V;
    for (int j = 0; j < k; ++j) P += w.values(i, j) * doc.morph.targets[j];
    const Eigen::MatrixXd want = unit_normals(P, a.F);
    for (int v = 0; v < nv; ++v) {
      const double e = angle_deg(N.row(v).normalized(), want.row(v));
      blended_sum += e, worst = std::max(worst, e);
      fixed_sum += angle_deg(N0.row(v), want.row(v));
    }
  }
  const double blended = blended_sum / (nv * a.num_frames()), fixed = fixed_sum / (nv * a.num_frames());
  INFO("blended mean " << blended << " max " << worst << ", fixed mean " << fixed);
  // The bar bends by up to 1.2 rad: fixed normals are tens of degrees off, the fitted deltas a few.
  CHECK(fixed > 10.0);
  CHECK(blended < 0.2 * fixed);
  CHECK(rep.normal_mean_angle_deg == Approx(blended).epsilon(1e-3));
  CHECK(rep.fixed_normal_mean_angle_deg == Approx(fixed).epsilon(1e-3));
  const PcaGltfReport none = export_pca_gltf((dir / "none.glb").string(), a, {"bar", false});
  CHECK(none.normal_mean_angle_deg == 0.0);
  CHECK(load((dir / "none.glb").string()).meshes.at(0).primitives.at(0).attributes.count("NORMAL") == 0);
  fs::remove_all(dir);
}

TEST_CASE("pca glTF: bad input is an error naming the problem", "[pca][gltf]") {
  Fixture fx;
  const fs::path dir = test::gltf_temp_dir("pca_bad");
  PcaAnimation a = pca_animation(fx.d, 2, fx.bar.F, fx.times);
  CHECK_THROWS_WITH(export_pca_gltf((dir / "x.obj").string(), a), Contains(".glb or .gltf"));
  PcaAnimation no_tris = a;
  no_tris.F.resize(0, 3);
  CHECK_THROWS_WITH(export_pca_gltf((dir / "x.glb").string(), no_tris), Contains("no triangles"));
  PcaAnimation neg = a;
  for (double& t : neg.times) t -= 1.0;
  CHECK_THROWS_WITH(export_pca_gltf((dir / "x.glb").string(), neg), Contains(">= 0"));
  CHECK(!fs::exists(dir / "x.glb"));
  fs::remove_all(dir);
}

TEST_CASE("pca glTF validator: .glb and .gltf, k = 0, 3 and all, with and without normals, are clean",
          "[pca][gltf][validator]") {
  if (!test::gltf_validator_ready()) return;
  Fixture fx;
  const fs::path dir = test::gltf_temp_dir("pca_validator");
  std::vector<std::string> files;
  for (int k : {0, 3, 12})
    for (const std::string ext : {"glb", "gltf"}) {
      files.push_back((dir / ("bar" + std::to_string(k) + "." + ext)).string());
      export_pca_gltf(files.back(), pca_animation(fx.d, k, fx.bar.F, fx.times));
    }
  files.push_back((dir / "flat.glb").string());
  export_pca_gltf(files.back(), pca_animation(fx.d, 3, fx.bar.F, fx.times), {"bar", false});
  for (const auto& f : files) test::check_gltf_valid(f);
  fs::remove_all(dir);
}
