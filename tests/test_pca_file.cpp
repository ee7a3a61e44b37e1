// The .pca file (core/anim/pca_file.h): a round trip keeps every value to float32, and hostile files
// (truncated, corrupt, inconsistent) are dfm::Errors naming the file and the problem. Files are
// re-signed here with a checksum written in this test, so the checks behind the checksum are reached.
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include <catch2/catch.hpp>

#include "core/anim/pca_file.h"
#include "core/util/error.h"
#include "tests/file_bytes.h"
#include "tests/pca_test_frames.h"
#include "tests/scratch_dir.h"

using namespace dfm;
using Catch::Contains;
namespace fs = std::filesystem;

namespace {

using Scratch = test::ScratchDir;

PcaAnimation sample_animation(int k = 3) {
  const TriMesh bar = test::pca_bar(5, 4);
  const std::vector<Eigen::MatrixXd> frames = test::bending_bar_frames(bar, 7, 1e-3);
  return pca_animation(decompose_frames(frames), k, bar.F, frame_times(7, 24));
}

std::string bytes_of(const std::string& path) { return test::slurp(path); }
void put(const std::string& path, const std::string& bytes) { test::spill(path, bytes); }

// FNV-1a 64 (the format's checksum), written out here rather than taken from core/util/hash.h.
uint64_t fnv(const std::string& s, size_t n) {
  uint64_t h = 14695981039346656037ull;
  for (size_t i = 0; i < n; ++i) h = (h ^ static_cast<unsigned char>(s[i])) * 1099511628211ull;
  return h;
}
std::string resign(std::string s) {
  const uint64_t h = fnv(s, s.size() - 8);
  std::memcpy(&s[s.size() - 8], &h, 8);
  return s;
}
template <class T>
void poke(std::string& s, size_t at, T x) {
  std::memcpy(&s[at], &x, sizeof(T));
}

void require_error(const std::string& path, const std::vector<std::string>& parts) {
  try {
    read_pca(path);
  } catch (const Error& e) {
    const std::string msg = e.what();
    INFO("message: " << msg);
    CHECK_THAT(msg, Contains(fs::path(path).filename().string()));
    for (const std::string& p : parts) CHECK_THAT(msg, Contains(p));
    return;
  }
  FAIL("no dfm::Error reading " << path);
}

}  // namespace

TEST_CASE("pca file: the round trip keeps every value as float32 and the size is the layout's", "[pca][io]") {
  Scratch s("test_pca_file");
  const PcaAnimation a = sample_animation();
  const std::string path = s / "a.pca";
  write_pca(path, a);
  const int nv = a.num_vertices(), n = a.num_frames(), k = a.num_bases(), nt = static_cast<int>(a.F.rows());
  // magic + 6 u32 + triangles + mean + bases + coefficients + times + 7 floats of motion + u64.
  CHECK(fs::file_size(path) == 8 + 24 + 12u * nt + 12u * nv + 12u * nv * k + 4u * n * k + 4u * n + 28u * n + 8);
  CHECK(fs::file_size(path) == pca_file_bytes(nv, nt, n, k));
  const PcaAnimation b = read_pca(path);
  CHECK(b.F == a.F);
  CHECK(b.mean == a.mean.cast<float>().cast<double>());
  CHECK(b.bases == a.bases.cast<float>().cast<double>());
  CHECK(b.coefficients == a.coefficients.cast<float>().cast<double>());
  REQUIRE(b.num_frames() == n);
  for (int i = 0; i < n; ++i) {
    CHECK(b.times[i] == static_cast<double>(static_cast<float>(a.times[i])));
    CHECK(b.motion[i].translation == a.motion[i].translation.cast<float>().cast<double>());
    CHECK(b.motion[i].rotation.angularDistance(a.motion[i].rotation) < 1e-6);
    CHECK((pca_frame(b, i) - pca_frame(a, i)).rowwise().norm().maxCoeff() < 1e-5);
  }
  // Rewriting what was read gives the same bytes.
  write_pca(s / "b.pca", b);
  CHECK(bytes_of(s / "b.pca") == bytes_of(path));
  // k = 0: no bases, no coefficients.
  write_pca(s / "k0.pca", sample_animation(0));
  CHECK(read_pca(s / "k0.pca").num_bases() == 0);
}

TEST_CASE("pca file: the writer refuses what the format cannot hold and leaves no file", "[pca][io]") {
  Scratch s("test_pca_file");
  PcaAnimation a = sample_animation();
  a.coefficients(2, 1) = 1e39;  // beyond float32
  CHECK_THROWS_WITH(write_pca(s / "big.pca", a), Contains("big.pca") && Contains("float32"));
  a = sample_animation();
  a.times[3] = a.times[2] + 1e-12;  // collides in float32
  CHECK_THROWS_WITH(write_pca(s / "t.pca", a), Contains("collide"));
  a = sample_animation();
  a.motion.pop_back();
  CHECK_THROWS_WITH(write_pca(s / "m.pca", a), Contains("frame count"));
  CHECK(!fs::exists(s / "big.pca"));
  CHECK(!fs::exists(s / "t.pca"));
  CHECK_THROWS_WITH(write_pca(s / "no-such-dir/a.pca", sample_animation()), Contains("no-such-dir"));
}

TEST_CASE("pca file: hostile files are errors naming the file and the problem", "[pca][io][hostile]") {
  Scratch s("test_pca_file");
  const PcaAnimation a = sample_animation();
  write_pca(s / "good.pca", a);
  const std::string good = bytes_of(s / "good.pca");
  const size_t nv = a.num_vertices(), nt = a.F.rows(), n = a.num_frames(), k = a.num_bases();
  const size_t tri = 32, mean = tri + 12 * nt, bases = mean + 12 * nv, coef = bases + 12 * nv * k, times = coef + 4 * n * k,
               motion = times + 4 * n;
  REQUIRE(motion + 28 * n + 8 == good.size());

  require_error(s / "missing.pca", {"no such file"});
  fs::create_directories(s / "dir.pca");
  require_error(s / "dir.pca", {"directory"});
  put(s / "empty.pca", "");
  require_error(s / "empty.pca", {"truncated", "header"});
  put(s / "short.pca", good.substr(0, 20));
  require_error(s / "short.pca", {"truncated"});
  for (size_t cut : {size_t(32), mean + 5, coef, good.size() - 1}) {
    put(s / "cut.pca", good.substr(0, cut));
    require_error(s / "cut.pca", {"truncated", "needs " + std::to_string(good.size()) + " bytes"});
  }
  put(s / "long.pca", good + "x");
  require_error(s / "long.pca", {"trailing bytes"});
  std::string b = good;
  b[0] = 'X';
  put(s / "magic.pca", b);
  require_error(s / "magic.pca", {"not a .pca file"});
  b = good;
  poke<uint32_t>(b, 8, 2);
  put(s / "version.pca", resign(b));
  require_error(s / "version.pca", {"version 2"});
  b = good;
  b[mean + 17] ^= 0x10;  // one flipped bit in the mean
  put(s / "flip.pca", b);
  require_error(s / "flip.pca", {"checksum"});
  // Counts the size does not hold: frames doubled, and counts whose size overflows 64 bits.
  b = good;
  poke<uint32_t>(b, 20, static_cast<uint32_t>(2 * n));
  put(s / "frames.pca", resign(b));
  require_error(s / "frames.pca", {"truncated", std::to_string(2 * n) + " frames"});
  b = good;
  poke<uint32_t>(b, 12, 700000000u);
  poke<uint32_t>(b, 20, 700000000u);
  poke<uint32_t>(b, 24, 700000000u);
  put(s / "huge.pca", resign(b));
  require_error(s / "huge.pca", {"more than 10^18"});
  b = good;
  poke<uint32_t>(b, 24, static_cast<uint32_t>(n + 1));
  put(s / "k.pca", resign(b));
  require_error(s / "k.pca", {"base shapes: more than"});
  b = good;
  poke<uint32_t>(b, 12, 0u);
  put(s / "nov.pca", resign(b));
  require_error(s / "nov.pca", {"no vertices"});
  // Consistent sizes, bad content.
  b = good;
  poke<uint32_t>(b, tri + 4, static_cast<uint32_t>(nv));
  put(s / "index.pca", resign(b));
  require_error(s / "index.pca", {"byte offset " + std::to_string(tri + 4), "names vertex " + std::to_string(nv)});
  b = good;
  poke<float>(b, mean + 8, std::numeric_limits<float>::quiet_NaN());
  put(s / "nan.pca", resign(b));
  require_error(s / "nan.pca", {"byte offset " + std::to_string(mean + 8), "mean has a non-finite value"});
  b = good;
  poke<float>(b, bases + 4, 0.9f);  // base 0 no longer unit length
  put(s / "ortho.pca", resign(b));
  require_error(s / "ortho.pca", {"not orthonormal"});
  b = good;
  poke<float>(b, times + 8, 0.0f);  // frame 2 at time 0
  put(s / "times.pca", resign(b));
  require_error(s / "times.pca", {"do not increase", "frame 2"});
  b = good;
  poke<float>(b, motion + 28 + 12, 2.0f);  // frame 1: w = 2
  put(s / "quat.pca", resign(b));
  require_error(s / "quat.pca", {"frame 1", "unit quaternion"});
  b = good;
  poke<uint32_t>(b, 28, 1u);
  put(s / "reserved.pca", resign(b));
  require_error(s / "reserved.pca", {"reserved"});
}

TEST_CASE("pca file: random byte changes (re-signed) load or give a dfm::Error, never crash", "[pca][io][hostile]") {
  Scratch s("test_pca_file");
  write_pca(s / "good.pca", sample_animation());
  const std::string good = bytes_of(s / "good.pca");
  std::mt19937 rng(5);
  std::uniform_int_distribution<size_t> pos(0, good.size() - 9);
  std::uniform_int_distribution<int> byte(0, 255);
  int loaded = 0, refused = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::string b = good;
    for (int k = 0; k < 1 + trial % 4; ++k) b[pos(rng)] = static_cast<char>(byte(rng));
    put(s / "mut.pca", resign(b));
    try {
      const PcaAnimation a = read_pca(s / "mut.pca");
      // Whatever loads is consistent: every frame reconstructs to finite positions.
      for (int i = 0; i < a.num_frames(); ++i) REQUIRE(pca_frame(a, i).allFinite());
      ++loaded;
    } catch (const Error& e) {
      REQUIRE_THAT(std::string(e.what()), Contains("mut.pca"));
      ++refused;
    }
  }
  CHECK(loaded > 0);
  CHECK(refused > 0);
}
