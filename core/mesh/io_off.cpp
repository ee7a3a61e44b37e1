// Object File Format: header OFF / NOFF / COFF / CNOFF (counts may follow on the same line), then
// "#vertices #faces #edges", vertex lines "x y z [nx ny nz] [colour]", face lines "n i1 .. in [colour]"
// (0-based). Polygons are fan-triangulated; '#' comments are allowed. NOFF normals are kept.
#include <cmath>
#include <iomanip>

#include "core/mesh/io_formats.h"
#include "core/mesh/io_parse.h"
#include "core/util/atomic_file.h"

namespace dfm::io {

TriMesh read_off(const std::string& path) {
  std::string data = read_file(path);
  LineReader lr(data);
  std::string_view line;
  std::vector<std::string_view> t;
  auto fail = [&](const std::string& p) { throw file_error(path, lr.line(), p); };
  auto next_fields = [&](const char* expected) {
    while (lr.next(line)) {
      split_ws(strip_comment(line), t);
      if (!t.empty()) return;
    }
    throw file_error(path, lr.line() + 1, std::string("unexpected end of file, expected ") + expected);
  };
  next_fields("the OFF header");
  std::string_view head = t[0];
  bool normals = false;
  if (head.size() >= 3 && head.substr(head.size() - 3) == "OFF") {
    std::string_view pre = head.substr(0, head.size() - 3);
    if (pre.find_first_not_of("STCN") != std::string_view::npos) fail("unsupported OFF variant " + quote(head));
    if (pre.find("ST") != std::string_view::npos) fail("texture coordinates (STOFF) are not supported");
    normals = pre.find('N') != std::string_view::npos;
  } else {
    fail("missing OFF header (found " + quote(head) + ")");
  }
  if (t.size() == 1) next_fields("vertex and face counts");
  else t.erase(t.begin());
  long long nv = 0, nf = 0;
  if (t.size() < 2 || !parse_int(t[0], nv) || !parse_int(t[1], nf))
    fail("expected \"#vertices #faces #edges\", found " + quote(line));
  check_count(path, lr.line(), nv, 6, lr.bytes_left(), "vertex");
  check_count(path, lr.line(), nf, 8, lr.bytes_left() - 6 * nv, "face");
  if (nv == 0) fail("no vertices");
  TriMesh m;
  m.V.resize(nv, 3);
  if (normals) m.N.resize(nv, 3);
  for (long long i = 0; i < nv; ++i) {
    const std::string what = "vertex " + std::to_string(i);
    next_fields("vertex line");
    if (t.size() < (normals ? 6u : 3u))
      fail(what + " needs " + (normals ? "6" : "3") + " numbers, found " + std::to_string(t.size()));
    for (int c = 0; c < (normals ? 6 : 3); ++c) {
      double x;
      if (!parse_double(t[c], x)) fail(what + " coordinate is not a number: " + quote(t[c]));
      if (!std::isfinite(x)) fail(what + " coordinate is not finite: " + quote(t[c]));
      (c < 3 ? m.V(i, c) : m.N(i, c - 3)) = x;
    }
  }
  std::vector<int> F;
  F.reserve(3 * nf);
  std::vector<int> poly;
  for (long long f = 0; f < nf; ++f) {
    const std::string what = "face " + std::to_string(f);
    next_fields("face line");
    long long n;
    if (!parse_int(t[0], n)) fail(what + ": vertex count is not an integer: " + quote(t[0]));
    if (n < 3) fail(what + " has " + std::to_string(n) + " vertices (at least 3 needed)");
    if (n > static_cast<long long>(t.size()) - 1)
      fail(what + " declares " + std::to_string(n) + " vertices but lists " + std::to_string(t.size() - 1));
    poly.clear();
    for (long long k = 1; k <= n; ++k) {
      long long v;
      if (!parse_int(t[k], v)) fail(what + " has a non-integer vertex index " + quote(t[k]));
      if (v < 0 || v >= nv)
        fail(what + " has vertex index " + std::to_string(v) + " out of range [0, " + std::to_string(nv - 1) + "]");
      poly.push_back(static_cast<int>(v));
    }
    for (size_t k = 1; k + 1 < poly.size(); ++k) F.insert(F.end(), {poly[0], poly[k], poly[k + 1]});
  }
  if (F.empty()) throw file_error(path, 0, "no faces (a surface needs at least one triangle)");
  m.F = Eigen::Map<Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>>(F.data(), F.size() / 3, 3);
  return m;
}

void write_off(const std::string& path, const TriMesh& m) {
  const bool normals = m.N.rows() == m.V.rows() && m.N.rows() > 0;
  write_file_atomic(path, [&](std::ostream& o) {
    o << std::setprecision(17) << (normals ? "NOFF\n" : "OFF\n") << m.V.rows() << ' ' << m.F.rows() << " 0\n";
    for (int i = 0; i < m.V.rows(); ++i) {
      o << m.V(i, 0) << ' ' << m.V(i, 1) << ' ' << m.V(i, 2);
      if (normals) o << ' ' << m.N(i, 0) << ' ' << m.N(i, 1) << ' ' << m.N(i, 2);
      o << '\n';
    }
    for (int f = 0; f < m.F.rows(); ++f) o << "3 " << m.F(f, 0) << ' ' << m.F(f, 1) << ' ' << m.F(f, 2) << '\n';
  });
}

}  // namespace dfm::io
