// Plain text points: one "x y z" per line; '#' comments and blank lines allowed.
#include <cmath>
#include <iomanip>

#include "core/mesh/io.h"
#include "core/mesh/io_parse.h"
#include "core/util/atomic_file.h"

namespace dfm {

Eigen::MatrixXd read_points(const std::string& path) {
  std::string data = io::read_file(path);
  io::LineReader lr(data);
  std::string_view line;
  std::vector<std::string_view> t;
  std::vector<double> P;
  while (lr.next(line)) {
    io::split_ws(io::strip_comment(line), t);
    if (t.empty()) continue;
    const long p = static_cast<long>(P.size() / 3) + 1;
    if (t.size() != 3)
      throw file_error(path, lr.line(), "point " + std::to_string(p) + " needs exactly 3 numbers \"x y z\", found " +
                                            std::to_string(t.size()) + " fields");
    for (auto s : t) {
      double x;
      if (!io::parse_double(s, x))
        throw file_error(path, lr.line(), "point " + std::to_string(p) + " coordinate is not a number: " + io::quote(s));
      if (!std::isfinite(x))
        throw file_error(path, lr.line(), "point " + std::to_string(p) + " coordinate is not finite: " + io::quote(s));
      P.push_back(x);
    }
  }
  return Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(P.data(), P.size() / 3, 3);
}

void write_points(const std::string& path, const Eigen::MatrixXd& P) {
  if (P.cols() != 3 && P.rows() > 0) throw file_error(path, 0, "points must have 3 columns, got " + std::to_string(P.cols()));
  write_file_atomic(path, [&](std::ostream& o) {
    o << std::setprecision(17);
    for (int i = 0; i < P.rows(); ++i) o << P(i, 0) << ' ' << P(i, 1) << ' ' << P(i, 2) << '\n';
  });
}

}  // namespace dfm
