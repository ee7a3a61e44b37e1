#include "core/anim/pair_file.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/util/error.h"

namespace dfm {

PairFile read_pair_file(const std::string& path, int keys) {
  std::ifstream in(path);
  if (!in) throw file_error(path, 0, "cannot open the pairs file");
  const int gaps = std::max(0, keys - 1);
  std::vector<std::vector<Eigen::Matrix<double, 1, 6>>> rows(gaps);
  PairFile out;
  out.lines.resize(gaps);
  int gap = 0, line_no = 0;
  std::string line;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string s; words >> s;) w.push_back(s);
    if (w.empty() || w[0][0] == '#') continue;
    if (w[0] == "pair") {
      char* end = nullptr;
      const long k = w.size() == 2 ? std::strtol(w[1].c_str(), &end, 10) : -1;
      if (w.size() != 2 || *end || k < 0 || k >= gaps)
        throw file_error(path, line_no, "'pair K' needs K in 0.." + std::to_string(gaps - 1) + " (keys K and K+1 of " +
                                            std::to_string(keys) + "), got '" + line + "'");
      gap = static_cast<int>(k);
      continue;
    }
    if (w.size() != 6)
      throw file_error(path, line_no, "expected 6 numbers (x0 y0 z0 x1 y1 z1), got " + std::to_string(w.size()));
    Eigen::Matrix<double, 1, 6> r;
    for (int j = 0; j < 6; ++j) {
      char* end = nullptr;
      r[j] = std::strtod(w[j].c_str(), &end);
      if (end == w[j].c_str() || *end || !std::isfinite(r[j]))
        throw file_error(path, line_no, "not a finite number '" + w[j] + "' (column " + std::to_string(j + 1) + ")");
    }
    if (gaps == 0) throw file_error(path, line_no, "pairs need at least 2 keys");
    rows[gap].push_back(r);
    out.lines[gap].push_back(line_no);
  }
  for (int g = 0; g < gaps; ++g) {
    Eigen::MatrixXd m(static_cast<Eigen::Index>(rows[g].size()), 6);
    for (size_t i = 0; i < rows[g].size(); ++i) m.row(static_cast<Eigen::Index>(i)) = rows[g][i];
    out.pairs.push_back(m);
  }
  return out;
}

}  // namespace dfm
