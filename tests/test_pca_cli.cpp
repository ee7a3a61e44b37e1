// `deform compress` / `deform decompress` end to end (run as child processes): the printed errors are
// the best rank-k errors computed here (Horn alignment + Jacobi SVD), a decompressed frame is as far
// from its input as printed, and bad input exits 1 (naming the file) or 2 (usage).
#include <unistd.h>

#include <filesystem>
#include <regex>

#include <catch2/catch.hpp>

#include "core/anim/interpolate.h"
#include "core/mesh/io.h"
#include "core/rig/pose_params.h"
#include "core/scene/document.h"
#include "core/skin/lbs.h"
#include "tests/cli_test_util.h"
#include "tests/pca_test_frames.h"
#include "tests/scratch_dir.h"

using dfm::test::run_program;
using dfm::test::RunResult;
using Catch::Contains;
namespace fs = std::filesystem;

namespace {

using Scratch = dfm::test::ScratchDir;
using dfm::test::describe_run;

RunResult deform(const Scratch& s, const std::vector<std::string>& args) { return dfm::test::run_deform(s, args); }

// The frames written as OBJ (17 significant digits: they read back exactly).
std::vector<std::string> write_frames(const Scratch& s, const dfm::TriMesh& bar, const std::vector<Eigen::MatrixXd>& frames) {
  std::vector<std::string> files;
  for (size_t i = 0; i < frames.size(); ++i) {
    files.push_back(s / ("f" + std::to_string(i) + ".obj"));
    dfm::write_surface(files.back(), {frames[i], bar.F, {}});
  }
  return files;
}

double number_after(const std::string& text, const std::string& pattern) {
  std::smatch m;
  REQUIRE(std::regex_search(text, m, std::regex(pattern + " ([-+0-9.eE]+)")));
  return std::stod(m[1]);
}

// Frame i's printed Frobenius error (third column of its table row).
double frame_error(const std::string& text, int i) {
  std::smatch m;
  REQUIRE(std::regex_search(text, m, std::regex("\\n +" + std::to_string(i) + " +[0-9.]+ +([-+0-9.eE]+)")));
  return std::stod(m[1]);
}

}  // namespace

TEST_CASE("deform compress: sizes, per-frame errors equal to the best rank-k error, decompress", "[pca][cli]") {
  Scratch s("test_pca_cli");
  const dfm::TriMesh bar = dfm::test::pca_bar();
  const int n = 10;
  const std::vector<Eigen::MatrixXd> frames = dfm::test::bending_bar_frames(bar, n, 1e-3);
  const dfm::test::ReferencePca ref = dfm::test::reference_pca(frames);
  std::vector<std::string> args = {"compress", "--frames"};
  for (const auto& f : write_frames(s, bar, frames)) args.push_back(f);
  args.insert(args.end(), {"-k", "3", "-o", s / "a.pca", "--gltf", s / "a.glb"});
  const RunResult r = deform(s, args);
  INFO(describe_run(r));
  REQUIRE(r.exit_code == 0);
  CHECK(number_after(r.out, "total") == Approx(ref.best_error(3)).epsilon(1e-5));
  const long raw = 12L * n * bar.V.rows();
  CHECK_THAT(r.out, Contains("frames as float32 " + std::to_string(raw) + " bytes"));
  CHECK_THAT(r.out, Contains("a.pca " + std::to_string(fs::file_size(s / "a.pca")) + " bytes"));
  CHECK_THAT(r.out, Contains("wrote " + s / "a.glb" + ": 3 morph targets, 10 frames"));
  double sum = 0;
  for (int i = 0; i < n; ++i) sum += frame_error(r.out, i) * frame_error(r.out, i);
  CHECK(std::sqrt(sum) == Approx(ref.best_error(3)).epsilon(1e-5));

  // A decompressed frame is as far from its input as printed (up to float32 storage).
  for (int i : {0, 4, n - 1}) {
    const std::string out = s / ("d" + std::to_string(i) + ".obj");
    const RunResult d = deform(s, {"decompress", s / "a.pca", "--frame", std::to_string(i), "-o", out});
    INFO(describe_run(d));
    REQUIRE(d.exit_code == 0);
    const dfm::TriMesh m = dfm::read_surface(out);
    CHECK(m.F == bar.F);
    CHECK((m.V - frames[i]).norm() == Approx(frame_error(r.out, i)).epsilon(1e-4).margin(1e-5));
  }
  // All bases: lossless up to float32.
  args[args.size() - 5] = std::to_string(n);
  const RunResult all = deform(s, args);
  REQUIRE(all.exit_code == 0);
  REQUIRE(deform(s, {"decompress", s / "a.pca", "--frame", "7", "-o", s / "d7.obj"}).exit_code == 0);
  CHECK((dfm::read_surface(s / "d7.obj").V - frames[7]).rowwise().norm().maxCoeff() < 1e-5);
  // decompress --gltf writes the same animation from the file.
  const RunResult g = deform(s, {"decompress", s / "a.pca", "--gltf", s / "b.gltf"});
  INFO(describe_run(g));
  CHECK(g.exit_code == 0);
  CHECK(fs::exists(s / "b.bin"));
}

TEST_CASE("deform compress/decompress: bad input exits 1 naming the file, bad usage exits 2", "[pca][cli]") {
  Scratch s("test_pca_cli");
  const dfm::TriMesh bar = dfm::test::pca_bar(4, 4);
  std::vector<std::string> files = write_frames(s, bar, dfm::test::bending_bar_frames(bar, 4, 1e-3));
  // A frame with other triangles.
  dfm::TriMesh other = bar;
  other.F.row(0) = other.F.row(0).reverse().eval();
  dfm::write_surface(s / "other.obj", other);
  RunResult r = deform(s, {"compress", "--frames", files[0], files[1], s / "other.obj", "-k", "1", "-o", s / "x.pca"});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Contains("other.obj") && Contains("one connectivity"));
  CHECK(!fs::exists(s / "x.pca"));
  r = deform(s, {"compress", "--frames", files[0], s / "missing.obj", "-k", "1", "-o", s / "x.pca"});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Contains("missing.obj"));
  CHECK(deform(s, {"compress", "--frames", files[0], files[1], "-o", s / "x.pca"}).exit_code == 2);  // no -k
  CHECK(deform(s, {"compress", "--frames", files[0], files[1], "-k", "3", "-o", s / "x.pca"}).exit_code == 2);
  CHECK(deform(s, {"compress", "--frames", files[0], "-k", "1"}).exit_code == 2);  // no -o
  CHECK(deform(s, {"compress", "-k", "1", "-o", s / "x.pca"}).exit_code == 2);     // no frames
  CHECK(deform(s, {"compress", "--frames", files[0], "-k", "1", "-o", s / "x.pca", "--gltf", s / "x.obj"}).exit_code == 2);
  // decompress
  REQUIRE(deform(s, {"compress", "--frames", files[0], files[1], files[2], "-k", "1", "-o", s / "ok.pca"}).exit_code == 0);
  r = deform(s, {"decompress", s / "ok.pca", "--frame", "3", "-o", s / "f.obj"});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Contains("ok.pca") && Contains("out of range"));
  CHECK(deform(s, {"decompress", s / "ok.pca"}).exit_code == 2);
  CHECK(deform(s, {"decompress", s / "ok.pca", "--frame", "0"}).exit_code == 2);
  std::ofstream(s / "bad.pca") << "not a pca file at all, but long enough for a header";
  r = deform(s, {"decompress", s / "bad.pca", "--frame", "0", "-o", s / "f.obj"});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Contains("bad.pca") && Contains("not a .pca file"));
}

TEST_CASE("deform compress SCENE: the pose keys baked at --count times, or the keys and in-betweens", "[pca][cli]") {
  Scratch s("test_pca_cli");
  const dfm::TriMesh bar = dfm::test::pca_bar();
  dfm::Document doc;
  doc.set_surface(bar, "bar.obj");
  doc.add_bone_chain({{-1, 0, 0}, {0, 0, 0}, {1, 0, 0}});
  Eigen::MatrixXd W(bar.V.rows(), 2);  // a smooth hand-over between the two bones around x = 0
  for (Eigen::Index v = 0; v < bar.V.rows(); ++v) {
    const double u = std::clamp(0.5 + bar.V(v, 0), 0.0, 1.0);
    W.row(v) << 1 - u, u;
  }
  doc.set_weights(W, {});
  doc.set_key(0);
  dfm::PoseParams p = dfm::rest_pose_params(doc.rig());
  p.bone_rotation[1] = Eigen::Quaterniond(Eigen::AngleAxisd(0.9, Eigen::Vector3d::UnitZ()));
  doc.set_pose_params(p);
  doc.set_key(1);
  p.bone_rotation[0] = Eigen::Quaterniond(Eigen::AngleAxisd(1.2, Eigen::Vector3d::UnitY()));
  p.bone_translation[0] = Eigen::Vector3d(0.5, 2, 0);
  doc.set_pose_params(p);
  doc.set_key(2);
  doc.save_scene(s / "bar.scene.json");

  // The frames, baked here: the keys' poses sampled at 9 even times, LBS with the weights.
  dfm::KeyTrack track;
  const std::vector<dfm::Pose> poses = doc.key_poses();
  for (int k = 0; k < 3; ++k) track.set({double(k), poses[k]});
  std::vector<Eigen::MatrixXd> frames;
  for (int i = 0; i < 9; ++i) frames.push_back(dfm::lbs(bar.V, W, dfm::sample_track(track, 2.0 * i / 8)));
  const dfm::test::ReferencePca ref = dfm::test::reference_pca(frames);
  // The bar bends and turns: two significant components (k = 1 leaves the second).
  REQUIRE(ref.sigma[1] > 0.05 * ref.sigma[0]);
  RunResult r = deform(s, {"compress", s / "bar.scene.json", "--count", "9", "-k", "1", "-o", s / "b.pca"});
  INFO(describe_run(r));
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("9 frames of " + std::to_string(bar.V.rows()) + " vertices"));
  CHECK(number_after(r.out, "total") == Approx(ref.best_error(1)).epsilon(1e-5));
  REQUIRE(deform(s, {"decompress", s / "b.pca", "--frame", "8", "-o", s / "last.obj"}).exit_code == 0);
  CHECK((dfm::read_surface(s / "last.obj").V - frames[8]).norm() == Approx(frame_error(r.out, 8)).epsilon(1e-4).margin(1e-5));
  // Without --count: the keys plus the document's in-betweens (4 per interval): 3 + 2 x 4 frames.
  r = deform(s, {"compress", s / "bar.scene.json", "-k", "2", "-o", s / "c.pca"});
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("11 frames"));
  // A scene with a mesh key has two connectivities.
  dfm::TriMesh other = dfm::test::pca_bar(5, 5);
  doc.key_mesh(other, "other.obj", 3);
  doc.save_scene(s / "mesh-key.scene.json");
  r = deform(s, {"compress", s / "mesh-key.scene.json", "-k", "2", "-o", s / "d.pca"});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Contains("mesh-key.scene.json") && Contains("mesh key"));
  CHECK(deform(s, {"compress", s / "bar.scene.json", "--count", "1", "-k", "1", "-o", s / "e.pca"}).exit_code == 2);
}
