#pragma once
// Picked pairs for transitions from a text file (`deform manifold --pairs P.txt`, issue 30): one pair
// a line, `x0 y0 z0 x1 y1 z1` (a point on one key, its partner on the next). A line `pair K` sends
// the lines after it to keys K and K+1 (0-based, in the keyframes' order); lines before any such
// header go to keys 0 and 1. Blank lines and lines starting with # are skipped.
#include <string>
#include <vector>

#include <Eigen/Core>

namespace dfm {

struct PairFile {
  // Per neighbouring key pair K (keys K and K+1): #pairs x 6, and each row's line in the file.
  std::vector<Eigen::MatrixXd> pairs;
  std::vector<std::vector<int>> lines;
};

// Reads `path` for `keys` keys (keys - 1 neighbouring pairs). Throws dfm::Error "path:line: problem"
// on a line without exactly 6 numbers, a number that is not finite, or a `pair K` out of range.
PairFile read_pair_file(const std::string& path, int keys);

}  // namespace dfm
