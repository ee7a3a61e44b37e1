// Wavefront OBJ: "v", "vn" and "f" (corners "v", "v/vt", "v//vn", "v/vt/vn"; negative = relative).
// Polygons are fan-triangulated. Per-vertex normals are kept when faces assign one to every vertex.
// Other standard statements (vt, o, g, s, usemtl, l, ...) are ignored; unknown ones are errors so that
// garbage is reported rather than read as an empty mesh.
#include <algorithm>
#include <climits>
#include <cmath>
#include <iomanip>
#include <set>

#include "core/mesh/io_formats.h"
#include "core/mesh/io_parse.h"
#include "core/util/atomic_file.h"

namespace dfm::io {
namespace {

const std::set<std::string_view> kIgnored = {
    "vt", "vp", "o", "g", "s", "usemtl", "mtllib", "l", "p", "cstype", "deg", "bmat", "step", "curv", "curv2",
    "surf", "parm", "trim", "hole", "scrv", "sp", "end", "con", "mg", "lod", "bevel", "c_interp", "d_interp",
    "usemap", "maplib", "shadow_obj", "trace_obj", "ctech", "stech", "call", "csh"};

// Resolves a 1-based or negative (relative) OBJ index against `count`; -1 if out of range.
long long resolve(long long i, long long count) {
  if (i > 0 && i <= count) return i - 1;
  if (i < 0 && i >= -count) return count + i;  // never negate i: it may be LLONG_MIN
  return -1;
}

}  // namespace

TriMesh read_obj(const std::string& path) {
  std::string data = read_file(path);
  LineReader lr(data);
  std::string_view line;
  std::vector<std::string_view> t;
  std::vector<double> V, VN;
  std::vector<int> F, FN;  // FN: normal index per corner or -1
  long faces = 0;
  while (lr.next(line)) {
    split_ws(strip_comment(line), t);
    if (t.empty()) continue;
    auto fail = [&](const std::string& p) { throw file_error(path, lr.line(), p); };
    const std::string_view key = t[0];
    if (key == "v" || key == "vn") {
      const bool is_v = key == "v";
      std::vector<double>& out = is_v ? V : VN;
      const std::string what = (is_v ? "vertex " : "normal ") + std::to_string(out.size() / 3 + 1);
      if (t.size() < 4) fail(what + " needs 3 coordinates, found " + std::to_string(t.size() - 1));
      for (int c = 1; c <= 3; ++c) {
        double x;
        if (!parse_double(t[c], x)) fail(what + " coordinate is not a number: " + quote(t[c]));
        if (!std::isfinite(x)) fail(what + " coordinate is not finite: " + quote(t[c]));
        out.push_back(x);
      }
      if (V.size() / 3 > INT_MAX / 2) fail("too many vertices");
    } else if (key == "f") {
      ++faces;
      const std::string what = "face " + std::to_string(faces);
      if (t.size() < 4) fail(what + " has " + std::to_string(t.size() - 1) + " corners (at least 3 needed)");
      const long long nv = V.size() / 3, nn = VN.size() / 3;
      std::vector<int> cv, cn;
      for (size_t c = 1; c < t.size(); ++c) {
        std::string_view s = t[c];
        size_t s1 = s.find('/');
        long long vi, ni = 0;
        if (!parse_int(s.substr(0, s1), vi)) fail(what + " has a bad corner " + quote(s));
        long long r = resolve(vi, nv);
        if (r < 0)
          fail(what + " has vertex index " + std::to_string(vi) + " out of range [1, " + std::to_string(nv) + "]" +
               (nv > 0 ? " (or [-" + std::to_string(nv) + ", -1])" : ""));
        cv.push_back(static_cast<int>(r));
        long long rn = -1;
        if (s1 != std::string_view::npos) {
          size_t s2 = s.find('/', s1 + 1);
          if (s2 != std::string_view::npos && s2 + 1 < s.size()) {
            if (!parse_int(s.substr(s2 + 1), ni)) fail(what + " has a bad normal index in " + quote(s));
            rn = resolve(ni, nn);
            if (rn < 0)
              fail(what + " has normal index " + std::to_string(ni) + " out of range [1, " + std::to_string(nn) + "]");
          }
        }
        cn.push_back(static_cast<int>(rn));
      }
      for (size_t k = 1; k + 1 < cv.size(); ++k) {
        F.insert(F.end(), {cv[0], cv[k], cv[k + 1]});
        FN.insert(FN.end(), {cn[0], cn[k], cn[k + 1]});
      }
    } else if (!kIgnored.count(key)) {
      fail("unknown OBJ statement " + quote(key) + " (not an OBJ file?)");
    }
  }
  if (V.empty()) throw file_error(path, 0, "no vertices (empty or not an OBJ file)");
  if (F.empty()) throw file_error(path, 0, "no faces (a surface needs at least one triangle)");
  TriMesh m;
  m.V = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(V.data(), V.size() / 3, 3);
  m.F = Eigen::Map<Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>>(F.data(), F.size() / 3, 3);
  // Per-vertex normals only when every vertex got one from some face corner.
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(m.V.rows(), 3);
  std::vector<char> has(m.V.rows(), 0);
  for (size_t i = 0; i < F.size(); ++i)
    if (FN[i] >= 0) {
      N.row(F[i]) << VN[3 * FN[i]], VN[3 * FN[i] + 1], VN[3 * FN[i] + 2];
      has[F[i]] = 1;
    }
  if (std::all_of(has.begin(), has.end(), [](char c) { return c; })) m.N = N;
  return m;
}

void write_obj(const std::string& path, const TriMesh& m) {
  const bool normals = m.N.rows() == m.V.rows() && m.N.rows() > 0;
  write_file_atomic(path, [&](std::ostream& o) {
    o << std::setprecision(17);
    for (int i = 0; i < m.V.rows(); ++i) o << "v " << m.V(i, 0) << ' ' << m.V(i, 1) << ' ' << m.V(i, 2) << '\n';
    if (normals)
      for (int i = 0; i < m.N.rows(); ++i) o << "vn " << m.N(i, 0) << ' ' << m.N(i, 1) << ' ' << m.N(i, 2) << '\n';
    for (int f = 0; f < m.F.rows(); ++f) {
      o << 'f';
      for (int c = 0; c < 3; ++c) {
        o << ' ' << m.F(f, c) + 1;
        if (normals) o << "//" << m.F(f, c) + 1;
      }
      o << '\n';
    }
  });
}

}  // namespace dfm::io
