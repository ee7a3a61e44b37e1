#include "core/anim/pca_file.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/mesh/io_binary.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/util/hash.h"

namespace dfm {
namespace {

constexpr char kMagic[8] = {'D', 'F', 'M', 'P', 'C', 'A', '\r', '\n'};
constexpr uint32_t kVersion = 1;
constexpr size_t kHeaderBytes = 32;

// Little-endian appends.
void put_bytes(std::string& out, const void* p, size_t n) {
  const char* b = static_cast<const char*>(p);
  if (io::host_is_little_endian()) {
    out.append(b, n);
  } else {
    for (size_t i = n; i-- > 0;) out.push_back(b[i]);
  }
}
void put_u32(std::string& out, uint32_t x) { put_bytes(out, &x, 4); }
void put_f32(std::string& out, float x) { put_bytes(out, &x, 4); }

// Reads little-endian scalars from a buffer whose size was checked against the header beforehand.
template <class T>
T get(const std::string& data, size_t at) {
  T x;
  std::memcpy(&x, data.data() + at, sizeof(T));
  if (!io::host_is_little_endian()) {
    unsigned char* b = reinterpret_cast<unsigned char*>(&x);
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  }
  return x;
}

float to_float(double x, const std::string& path, const char* what) {
  if (!std::isfinite(x) || std::abs(x) > std::numeric_limits<float>::max())
    throw Error(path + ": cannot write the animation: " + what + " has a value float32 cannot hold (" +
                std::to_string(x) + ")");
  return static_cast<float>(x);
}

void check_shape(const PcaAnimation& a, const std::string& path) {
  const int nv = a.num_vertices(), n = a.num_frames(), k = a.num_bases();
  auto bad = [&](const std::string& what) { return Error(path + ": cannot write the animation: " + what); };
  if (nv == 0 || a.mean.cols() != 3) throw bad("the mean is not a #V x 3 matrix with vertices");
  if (n == 0) throw bad("it has no frames");
  if (a.bases.rows() != 3 * nv) throw bad("the bases do not have 3 x #V rows");
  if (a.coefficients.cols() != k) throw bad("coefficients and bases differ in count");
  if (static_cast<int>(a.motion.size()) != n || static_cast<int>(a.times.size()) != n)
    throw bad("frame times or rigid motions do not match the frame count");
  if (k > std::min(3 * nv, n)) throw bad("more bases than min(3 x vertices, frames)");
  if (a.F.rows() > 0 && (a.F.cols() != 3 || a.F.minCoeff() < 0 || a.F.maxCoeff() >= nv))
    throw bad("a triangle names a vertex outside the mesh");
}

struct Header {
  uint32_t vertices = 0, triangles = 0, frames = 0, bases = 0;
};

Header read_header(const std::string& path, const std::string& head, std::uintmax_t file_size) {
  if (head.size() < kHeaderBytes)
    throw byte_error(path, static_cast<long long>(head.size()),
                     "truncated: the header needs " + std::to_string(kHeaderBytes) + " bytes, the file has " +
                         std::to_string(file_size));
  if (std::memcmp(head.data(), kMagic, 8) != 0) throw byte_error(path, 0, "not a .pca file (bad magic)");
  const uint32_t version = get<uint32_t>(head, 8);
  if (version != kVersion)
    throw byte_error(path, 8, "unsupported .pca version " + std::to_string(version) + " (this build reads 1)");
  Header h{get<uint32_t>(head, 12), get<uint32_t>(head, 16), get<uint32_t>(head, 20), get<uint32_t>(head, 24)};
  if (get<uint32_t>(head, 28) != 0) throw byte_error(path, 28, "the reserved field is not 0");
  if (h.vertices == 0) throw byte_error(path, 12, "the animation has no vertices");
  if (h.frames == 0) throw byte_error(path, 20, "the animation has no frames");
  const uint64_t limit = std::numeric_limits<int>::max() / 3;
  if (h.vertices > limit || h.triangles > limit || h.frames > limit)
    throw byte_error(path, 12, "a count is beyond what this reader handles");
  if (h.bases > std::min<uint64_t>(3ull * h.vertices, h.frames))
    throw byte_error(path, 24, std::to_string(h.bases) + " base shapes: more than min(3 x " +
                                   std::to_string(h.vertices) + " vertices, " + std::to_string(h.frames) + " frames)");
  // Overflow guard in floating point before the exact size (12 V K can exceed 64 bits for hostile counts).
  const double approx = 12.0 * h.vertices * (1.0 + h.bases) + 12.0 * h.triangles + 36.0 * h.frames + 4.0 * h.frames * h.bases;
  const uint64_t want = approx < 1e18 ? pca_file_bytes(h.vertices, h.triangles, h.frames, h.bases) : 0;
  if (want == 0 || want != file_size)
    throw byte_error(path, static_cast<long long>(std::min<std::uintmax_t>(file_size, want ? want : file_size)),
                     std::string(want > file_size || want == 0 ? "truncated" : "trailing bytes") + ": the header (" +
                         std::to_string(h.vertices) + " vertices, " + std::to_string(h.triangles) + " triangles, " +
                         std::to_string(h.frames) + " frames, " + std::to_string(h.bases) + " bases) needs " +
                         (want ? std::to_string(want) : std::string("more than 10^18")) + " bytes, the file has " +
                         std::to_string(file_size));
  return h;
}

// `count` finite floats from `at`; the byte offset of the first bad one is reported.
Eigen::VectorXd get_floats(const std::string& path, const std::string& data, size_t at, size_t count,
                           const char* what) {
  Eigen::VectorXd out(count);
  for (size_t i = 0; i < count; ++i) {
    const float f = get<float>(data, at + 4 * i);
    if (!std::isfinite(f)) throw byte_error(path, static_cast<long long>(at + 4 * i), std::string(what) + " has a non-finite value");
    out[i] = f;
  }
  return out;
}

void check_orthonormal(const std::string& path, const Eigen::MatrixXd& B, size_t at) {
  if (B.cols() == 0) return;
  const double off = (B.transpose() * B - Eigen::MatrixXd::Identity(B.cols(), B.cols())).cwiseAbs().maxCoeff();
  if (!(off <= 1e-4))
    throw byte_error(path, static_cast<long long>(at),
                     "the base shapes are not orthonormal (|B^T B - I| up to " + std::to_string(off) + ")");
}

}  // namespace

std::uint64_t pca_file_bytes(std::uint64_t vertices, std::uint64_t triangles, std::uint64_t frames,
                             std::uint64_t bases) {
  return kHeaderBytes + 12 * triangles + 12 * vertices * (1 + bases) + 4 * frames * bases + 32 * frames + 8;
}

void write_pca(const std::string& path, const PcaAnimation& a) {
  check_shape(a, path);
  const int nv = a.num_vertices(), n = a.num_frames(), k = a.num_bases();
  std::string out;
  out.reserve(pca_file_bytes(nv, a.F.rows(), n, k));
  out.append(kMagic, 8);
  for (uint32_t x : {kVersion, uint32_t(nv), uint32_t(a.F.rows()), uint32_t(n), uint32_t(k), 0u}) put_u32(out, x);
  for (Eigen::Index f = 0; f < a.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) put_u32(out, static_cast<uint32_t>(a.F(f, c)));
  for (int v = 0; v < nv; ++v)
    for (int c = 0; c < 3; ++c) put_f32(out, to_float(a.mean(v, c), path, "the mean"));
  for (int j = 0; j < k; ++j)
    for (int r = 0; r < 3 * nv; ++r) put_f32(out, to_float(a.bases(r, j), path, "a base shape"));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < k; ++j) put_f32(out, to_float(a.coefficients(i, j), path, "a coefficient"));
  float prev = -std::numeric_limits<float>::infinity();
  for (int i = 0; i < n; ++i) {
    const float t = to_float(a.times[i], path, "a frame time");
    if (!(t > prev)) throw Error(path + ": cannot write the animation: frame times collide or decrease in float32 (frame " + std::to_string(i) + ")");
    put_f32(out, prev = t);
  }
  for (int i = 0; i < n; ++i) {
    const Eigen::Quaterniond q = a.motion[i].rotation.normalized();
    for (double x : {q.x(), q.y(), q.z(), q.w()}) put_f32(out, to_float(x, path, "a rotation"));
    for (int c = 0; c < 3; ++c) put_f32(out, to_float(a.motion[i].translation[c], path, "a translation"));
  }
  const uint64_t h = fnv1a(kFnv1aBasis, out.data(), out.size());
  put_bytes(out, &h, 8);
  write_file_atomic(path, [&](std::ostream& os) { os.write(out.data(), static_cast<std::streamsize>(out.size())); },
                    true);
}

PcaAnimation read_pca(const std::string& path) {
  require_readable_file(path);
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw file_error(path, 0, "cannot read its size: " + ec.message());
  std::ifstream in(path, std::ios::binary);
  if (!in) throw file_error(path, 0, "cannot open it");
  std::string data(std::min<std::uintmax_t>(size, kHeaderBytes), '\0');
  in.read(data.data(), static_cast<std::streamsize>(data.size()));
  const Header h = read_header(path, in ? data : std::string(), size);
  data.resize(size);
  in.read(data.data() + kHeaderBytes, static_cast<std::streamsize>(size - kHeaderBytes));
  if (!in) throw file_error(path, 0, "read failed");
  if (get<uint64_t>(data, size - 8) != fnv1a(kFnv1aBasis, data.data(), size - 8))
    throw byte_error(path, static_cast<long long>(size - 8), "checksum mismatch: the file is corrupt");

  const int nv = static_cast<int>(h.vertices), nt = static_cast<int>(h.triangles), n = static_cast<int>(h.frames),
            k = static_cast<int>(h.bases);
  PcaAnimation a;
  size_t at = kHeaderBytes;
  a.F.resize(nt, 3);
  for (int f = 0; f < nt; ++f)
    for (int c = 0; c < 3; ++c, at += 4) {
      const uint32_t v = get<uint32_t>(data, at);
      if (v >= h.vertices)
        throw byte_error(path, static_cast<long long>(at), "triangle " + std::to_string(f) + " names vertex " +
                                                               std::to_string(v) + " of " + std::to_string(nv));
      a.F(f, c) = static_cast<int>(v);
    }
  const Eigen::VectorXd mean = get_floats(path, data, at, 3 * size_t(nv), "the mean");
  a.mean = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(mean.data(), nv, 3);
  at += 12 * size_t(nv);
  const Eigen::VectorXd bases = get_floats(path, data, at, 3 * size_t(nv) * k, "a base shape");
  a.bases = Eigen::Map<const Eigen::MatrixXd>(bases.data(), 3 * nv, k);
  check_orthonormal(path, a.bases, at);
  at += 12 * size_t(nv) * k;
  const Eigen::VectorXd coef = get_floats(path, data, at, size_t(n) * k, "a coefficient");
  a.coefficients = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(coef.data(), n, k);
  at += 4 * size_t(n) * k;
  const Eigen::VectorXd times = get_floats(path, data, at, n, "a frame time");
  for (int i = 1; i < n; ++i)
    if (!(times[i] > times[i - 1]))
      throw byte_error(path, static_cast<long long>(at + 4 * i), "frame times do not increase (frame " + std::to_string(i) + ")");
  a.times.assign(times.data(), times.data() + n);
  at += 4 * size_t(n);
  for (int i = 0; i < n; ++i, at += 28) {
    const Eigen::VectorXd m = get_floats(path, data, at, 7, "a rigid motion");
    const Eigen::Quaterniond q(m[3], m[0], m[1], m[2]);
    if (std::abs(q.norm() - 1.0) > 1e-4)
      throw byte_error(path, static_cast<long long>(at), "frame " + std::to_string(i) + "'s rotation is not a unit quaternion");
    a.motion.push_back({q.normalized(), m.tail<3>()});
  }
  return a;
}

}  // namespace dfm
