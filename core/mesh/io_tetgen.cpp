// TetGen .node/.ele pairs. The first point's index sets the numbering base (0 or 1) for both files,
// as TetGen does. Extra attributes, boundary markers and region attributes are read and dropped;
// 10-node (quadratic) tets keep their 4 corners.
#include <filesystem>
#include <iomanip>

#include "core/mesh/io_formats.h"
#include "core/mesh/io_parse.h"
#include "core/util/atomic_file.h"

namespace dfm::io {
namespace {

std::string with_ext(const std::string& path, const char* ext) {
  return std::filesystem::path(path).replace_extension(ext).string();
}

// X.node: the points; returns the numbering base (the first point's index).
int read_nodes(const std::string& node_path, Eigen::MatrixXd& V) {
  const std::string data = read_file(node_path);
  Tokenizer tk(node_path, data, true);
  const long long n = tk.integer("point count");
  const long long dim = tk.integer("dimension");
  if (dim != 3) tk.fail("dimension " + std::to_string(dim) + " is not supported (only 3)");
  const long long nattr = tk.integer("attribute count");
  const long long nmark = tk.integer("boundary marker flag");
  if (nattr < 0 || nattr > 1000) tk.fail("bad attribute count " + std::to_string(nattr));
  if (nmark != 0 && nmark != 1) tk.fail("boundary marker flag must be 0 or 1, found " + std::to_string(nmark));
  check_count(node_path, tk.line(), n, 2 * (4 + nattr + nmark), tk.bytes_left(), "point");
  V.resize(n, 3);
  int base = 0;
  for (long long i = 0; i < n; ++i) {
    const long long idx = tk.integer_or([] { return std::string("point index"); });
    if (i == 0) {
      if (idx != 0 && idx != 1) tk.fail("first point index must be 0 or 1, found " + std::to_string(idx));
      base = static_cast<int>(idx);
    }
    if (idx != i + base)
      tk.fail("point index " + std::to_string(idx) + " out of sequence (expected " + std::to_string(i + base) + ")");
    const auto coordinate = [idx] { return "point " + std::to_string(idx) + " coordinate"; };
    for (int c = 0; c < 3; ++c) V(i, c) = tk.real_or(coordinate);
    const auto attribute = [idx] { return "point " + std::to_string(idx) + " attribute"; };
    for (long long a = 0; a < nattr + nmark; ++a) tk.real_or(attribute);
  }
  return base;
}

// X.ele: the tets (the first 4 of 10 nodes), indices from `base`, into nv points.
Eigen::MatrixXi read_eles(const std::string& ele_path, int base, int nv) {
  const std::string data = read_file(ele_path);
  Tokenizer tk(ele_path, data, true);
  const long long n = tk.integer("tetrahedron count");
  const long long k = tk.integer("nodes per tetrahedron");
  if (k != 4 && k != 10) tk.fail("nodes per tetrahedron must be 4 or 10, found " + std::to_string(k));
  const long long nattr = tk.integer("region attribute count");
  if (nattr < 0 || nattr > 1000) tk.fail("bad attribute count " + std::to_string(nattr));
  check_count(ele_path, tk.line(), n, 2 * (1 + k + nattr), tk.bytes_left(), "tetrahedron");
  Eigen::MatrixXi T(n, 4);
  for (long long i = 0; i < n; ++i) {
    const long long idx = tk.integer_or([] { return std::string("tetrahedron index"); });
    const auto vertex = [idx] { return "tetrahedron " + std::to_string(idx) + " vertex"; };
    for (long long c = 0; c < k; ++c) {
      const long long v = tk.integer_or(vertex);
      if (v < base || v >= nv + base)
        tk.fail("tetrahedron " + std::to_string(idx) + " has vertex index " + std::to_string(v) +
                " out of range [" + std::to_string(base) + ", " + std::to_string(nv + base - 1) + "]");
      if (c < 4) T(i, c) = static_cast<int>(v - base);
    }
    const auto attribute = [idx] { return "tetrahedron " + std::to_string(idx) + " attribute"; };
    for (long long a = 0; a < nattr; ++a) tk.real_or(attribute);
  }
  return T;
}

}  // namespace

TetMesh read_tetgen(const std::string& path) {
  TetMesh m;
  const int base = read_nodes(with_ext(path, ".node"), m.V);
  m.T = read_eles(with_ext(path, ".ele"), base, m.num_vertices());
  orient_tets_positively(m.V, m.T);
  return m;
}

void write_tetgen(const std::string& path, const TetMesh& m) {
  // 1-based like TetGen's default output. The .ele is written first: a failure leaves both old files.
  write_file_atomic(with_ext(path, ".ele"), [&](std::ostream& o) {
    o << m.T.rows() << " 4 0\n";
    for (int i = 0; i < m.T.rows(); ++i)
      o << i + 1 << ' ' << m.T(i, 0) + 1 << ' ' << m.T(i, 1) + 1 << ' ' << m.T(i, 2) + 1 << ' ' << m.T(i, 3) + 1
        << '\n';
  });
  write_file_atomic(with_ext(path, ".node"), [&](std::ostream& o) {
    o << std::setprecision(17) << m.V.rows() << " 3 0 0\n";
    for (int i = 0; i < m.V.rows(); ++i)
      o << i + 1 << ' ' << m.V(i, 0) << ' ' << m.V(i, 1) << ' ' << m.V(i, 2) << '\n';
  });
}

}  // namespace dfm::io
