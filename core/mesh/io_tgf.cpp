// .tgf skeletons (see ../shared/data/README.md): joint lines "index x y z [ignored columns]", a line
// "#", edge lines "a b [is_bone is_pseudo_edge is_cage_edge]" (1-based), optionally a further "#"
// after which everything is ignored. An edge with only two numbers is a bone.
#include <cmath>
#include <iomanip>

#include "core/mesh/io.h"
#include "core/mesh/io_parse.h"
#include "core/util/atomic_file.h"

namespace dfm {

TgfData read_tgf(const std::string& path) {
  std::string data = io::read_file(path);
  io::LineReader lr(data);
  std::string_view line;
  std::vector<std::string_view> t;
  std::vector<double> J;
  std::vector<int> E, Fl;
  int section = 0;  // 0 joints, 1 edges, 2 ignored
  double x;
  long long v;
  while (section < 2 && lr.next(line)) {
    io::split_ws(line, t);
    if (t.empty()) continue;
    if (t[0][0] == '#') {
      ++section;
      continue;
    }
    auto fail = [&](const std::string& p) { throw file_error(path, lr.line(), p); };
    if (section == 0) {
      const long j = static_cast<long>(J.size() / 3) + 1;
      if (t.size() < 4) fail("joint " + std::to_string(j) + " needs \"index x y z\", found " + io::quote(line));
      if (!io::parse_int(t[0], v)) fail("joint index is not an integer: " + io::quote(t[0]));
      for (int c = 1; c <= 3; ++c) {
        if (!io::parse_double(t[c], x)) fail("joint " + std::to_string(j) + " coordinate is not a number: " + io::quote(t[c]));
        if (!std::isfinite(x)) fail("joint " + std::to_string(j) + " coordinate is not finite: " + io::quote(t[c]));
        J.push_back(x);
      }
    } else {
      const long e = static_cast<long>(E.size() / 2) + 1;
      if (t.size() < 2) fail("edge " + std::to_string(e) + " needs two joint indices, found " + io::quote(line));
      const long nj = static_cast<long>(J.size() / 3);
      for (int c = 0; c < 2; ++c) {
        if (!io::parse_int(t[c], v)) fail("edge " + std::to_string(e) + " joint index is not an integer: " + io::quote(t[c]));
        if (v < 1 || v > nj)
          fail("edge " + std::to_string(e) + " has joint index " + std::to_string(v) + " out of range [1, " +
               std::to_string(nj) + "]");
        E.push_back(static_cast<int>(v - 1));
      }
      if (E[E.size() - 1] == E[E.size() - 2]) fail("edge " + std::to_string(e) + " joins joint " + std::to_string(v) + " to itself");
      int f[3] = {1, 0, 0};  // two numbers: a bone
      if (t.size() > 2) {
        for (int c = 0; c < 3; ++c) {
          f[c] = 0;
          if (2 + c < static_cast<int>(t.size())) {
            if (!io::parse_int(t[2 + c], v) || (v != 0 && v != 1))
              fail("edge " + std::to_string(e) + " flag must be 0 or 1, found " + io::quote(t[2 + c]));
            f[c] = static_cast<int>(v);
          }
        }
      }
      Fl.insert(Fl.end(), f, f + 3);
    }
  }
  if (J.empty()) throw file_error(path, 0, "no joints (empty or not a .tgf file)");
  TgfData out;
  const int nj = static_cast<int>(J.size() / 3), ne = static_cast<int>(E.size() / 2);
  out.joints = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(J.data(), nj, 3);
  out.edges = Eigen::Map<Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor>>(E.data(), ne, 2);
  out.flags = Eigen::Map<Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>>(Fl.data(), ne, 3);
  return out;
}

void write_tgf(const std::string& path, const TgfData& tgf) {
  write_file_atomic(path, [&](std::ostream& o) {
    o << std::setprecision(17);
    for (int i = 0; i < tgf.joints.rows(); ++i)
      o << i + 1 << ' ' << tgf.joints(i, 0) << ' ' << tgf.joints(i, 1) << ' ' << tgf.joints(i, 2) << '\n';
    o << "#\n";
    for (int e = 0; e < tgf.edges.rows(); ++e) {
      o << tgf.edges(e, 0) + 1 << ' ' << tgf.edges(e, 1) + 1;
      if (tgf.flags.rows() == tgf.edges.rows())
        o << ' ' << tgf.flags(e, 0) << ' ' << tgf.flags(e, 1) << ' ' << tgf.flags(e, 2);
      o << '\n';
    }
    o << "#\n";
  });
}

}  // namespace dfm
