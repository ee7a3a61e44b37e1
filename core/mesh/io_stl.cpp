// STL, ascii and binary. STL stores a triangle soup: corners with bit-identical coordinates are merged
// into one vertex, numbered in order of first appearance. Facet normals are ignored on reading and
// computed from the geometry on writing. Binary STL stores 32-bit floats, so a binary round trip is
// exact only for float-representable coordinates.
// Which form: binary when the size is exactly 84 + 50 * (triangle count at byte 80); ascii when the file
// starts with "solid" and holds no NUL byte near the start; otherwise a binary size error.
#include <array>
#include <cmath>
#include <iomanip>
#include <unordered_map>

#include <Eigen/Geometry>

#include "core/mesh/io_binary.h"
#include "core/mesh/io_formats.h"
#include "core/mesh/io_parse.h"
#include "core/util/atomic_file.h"

namespace dfm::io {
namespace {

struct KeyHash {
  size_t operator()(const std::array<double, 3>& k) const {
    size_t h = 0;
    for (double d : k) {
      uint64_t b;
      std::memcpy(&b, &d, 8);
      h ^= std::hash<uint64_t>()(b) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
    }
    return h;
  }
};

// Merges identical corners into vertices.
class Welder {
 public:
  int add(double x, double y, double z) {
    std::array<double, 3> k = {x + 0.0, y + 0.0, z + 0.0};  // +0.0 folds -0 into 0
    auto it = index_.emplace(k, static_cast<int>(V_.size() / 3));
    if (it.second) V_.insert(V_.end(), k.begin(), k.end());
    return it.first->second;
  }
  TriMesh mesh(const std::vector<int>& F) {
    TriMesh m;
    m.V = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(V_.data(), V_.size() / 3, 3);
    m.F = Eigen::Map<const Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>>(F.data(), F.size() / 3, 3);
    return m;
  }

 private:
  std::vector<double> V_;
  std::unordered_map<std::array<double, 3>, int, KeyHash> index_;
};

TriMesh read_binary(const std::string& path, const std::string& data, uint32_t n) {
  ByteCursor bc(path, data, 84);
  Welder w;
  std::vector<int> F;
  F.reserve(3 * size_t(n));
  for (uint32_t t = 0; t < n; ++t) {
    float f[12];
    const size_t at = bc.pos();
    for (float& x : f) bc.read(&x, 4, true, "triangle " + std::to_string(t));
    uint16_t attr;
    bc.read(&attr, 2, true, "triangle " + std::to_string(t) + " attribute");
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 3; ++k)
        if (!std::isfinite(f[3 + 3 * c + k]))
          bc.fail(at + 12 + 12 * c + 4 * k, "triangle " + std::to_string(t) + " has a non-finite vertex coordinate");
      F.push_back(w.add(f[3 + 3 * c], f[4 + 3 * c], f[5 + 3 * c]));
    }
  }
  return w.mesh(F);
}

TriMesh read_ascii(const std::string& path, const std::string& data) {
  Tokenizer tk(path, data, false);
  std::string_view tok = tk.expect("solid");
  if (tok != "solid") tk.fail("ascii STL must start with \"solid\"");
  // The solid's name: the rest of its line.
  const long name_line = tk.line();
  Welder w;
  std::vector<int> F, poly;
  long facets = 0;
  auto expect_word = [&](const char* word) {
    std::string_view t = tk.expect(std::string("\"") + word + "\"");
    if (t != word) tk.fail(std::string("expected \"") + word + "\", found " + quote(t));
  };
  while (true) {
    tok = tk.expect("\"facet\" or \"endsolid\"");
    if (tk.line() == name_line && tok != "facet" && tok != "endsolid") continue;  // name words
    if (tok == "endsolid") break;
    if (tok != "facet") tk.fail("expected \"facet\" or \"endsolid\", found " + quote(tok));
    ++facets;
    const std::string what = "facet " + std::to_string(facets);
    expect_word("normal");
    for (int k = 0; k < 3; ++k) {  // ignored; some exporters write nan for degenerate facets
      std::string_view s = tk.expect(what + " normal");
      double d;
      if (!parse_double(s, d)) tk.fail(what + " normal is not a number: " + quote(s));
    }
    expect_word("outer");
    expect_word("loop");
    poly.clear();
    while (true) {
      tok = tk.expect("\"vertex\" or \"endloop\"");
      if (tok == "endloop") break;
      if (tok != "vertex") tk.fail(what + ": expected \"vertex\" or \"endloop\", found " + quote(tok));
      double x = tk.real(what + " vertex x"), y = tk.real(what + " vertex y"), z = tk.real(what + " vertex z");
      poly.push_back(w.add(x, y, z));
    }
    if (poly.size() < 3) tk.fail(what + " has " + std::to_string(poly.size()) + " vertices (at least 3 needed)");
    expect_word("endfacet");
    for (size_t k = 1; k + 1 < poly.size(); ++k) F.insert(F.end(), {poly[0], poly[k], poly[k + 1]});
  }
  if (F.empty()) throw file_error(path, tk.line(), "no facets");
  return w.mesh(F);
}

}  // namespace

TriMesh read_stl(const std::string& path) {
  std::string data = read_file(path);
  const size_t size = data.size();
  if (size == 0) throw file_error(path, 0, "empty file");
  uint32_t n = 0;
  if (size >= 84) {
    ByteCursor bc(path, data, 80);
    bc.read(&n, 4, true, "triangle count");
    if (size == 84 + 50 * uint64_t(n)) {
      if (n == 0) throw byte_error(path, 80, "binary STL with 0 triangles");
      return read_binary(path, data, n);
    }
  }
  size_t s = 0;
  while (s < size && std::isspace(static_cast<unsigned char>(data[s]))) ++s;
  const bool has_nul = data.find('\0', 0) < std::min<size_t>(size, 512);
  if (data.compare(s, 5, "solid") == 0 && !has_nul) return read_ascii(path, data);
  if (size < 84) throw byte_error(path, 0, "too short for binary STL (" + std::to_string(size) +
                                               " bytes, the header alone is 84) and not ascii STL (no \"solid\")");
  throw byte_error(path, 80, "binary STL says " + std::to_string(n) + " triangles, which needs 84 + 50 * " +
                                 std::to_string(n) + " = " + std::to_string(84 + 50 * uint64_t(n)) +
                                 " bytes, but the file has " + std::to_string(size) + " (truncated or not STL)");
}

void write_stl(const std::string& path, const TriMesh& m, bool binary) {
  auto normal = [&](int f) {
    Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    Eigen::Vector3d n = (b - a).cross(c - a);
    double l = n.norm();
    return l > 0 ? Eigen::Vector3d(n / l) : Eigen::Vector3d::Zero();
  };
  write_file_atomic(
      path,
      [&](std::ostream& o) {
        if (!binary) {
          o << std::setprecision(17) << "solid deform\n";
          for (int f = 0; f < m.F.rows(); ++f) {
            Eigen::Vector3d n = normal(f);
            o << " facet normal " << n.x() << ' ' << n.y() << ' ' << n.z() << "\n  outer loop\n";
            for (int c = 0; c < 3; ++c)
              o << "   vertex " << m.V(m.F(f, c), 0) << ' ' << m.V(m.F(f, c), 1) << ' ' << m.V(m.F(f, c), 2) << '\n';
            o << "  endloop\n endfacet\n";
          }
          o << "endsolid deform\n";
          return;
        }
        char header[80] = {};
        std::snprintf(header, sizeof header, "binary STL written by deform");
        o.write(header, 80);
        auto put = [&](const void* p, size_t k) {
          unsigned char b[4];
          std::memcpy(b, p, k);
          if (!host_is_little_endian()) std::reverse(b, b + k);
          o.write(reinterpret_cast<const char*>(b), k);
        };
        const uint32_t n = static_cast<uint32_t>(m.F.rows());
        put(&n, 4);
        for (int f = 0; f < m.F.rows(); ++f) {
          Eigen::Vector3d nn = normal(f);
          float v[12] = {float(nn.x()), float(nn.y()), float(nn.z())};
          for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 3; ++k) v[3 + 3 * c + k] = static_cast<float>(m.V(m.F(f, c), k));
          for (float x : v) put(&x, 4);
          const uint16_t attr = 0;
          put(&attr, 2);
        }
      },
      binary);
}

}  // namespace dfm::io
