#include "core/anim/surface_checks.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "core/mesh/mesh_info.h"

namespace dfm {

namespace {
std::uint64_t dkey(int a, int b) { return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b); }
std::vector<std::uint64_t> directed_edges(const Eigen::MatrixXi& F) {
  std::vector<std::uint64_t> d;
  d.reserve(3 * F.rows());
  for (int f = 0; f < F.rows(); ++f)
    for (int j = 0; j < 3; ++j) d.push_back(dkey(F(f, j), F(f, (j + 1) % 3)));
  std::sort(d.begin(), d.end());
  return d;
}
}  // namespace

bool is_oriented_manifold(const Eigen::MatrixXi& F) {
  const auto d = directed_edges(F);
  for (size_t i = 0; i < d.size(); ++i) {
    if (i + 1 < d.size() && d[i] == d[i + 1]) return false;
    if ((d[i] >> 32) == (d[i] & 0xffffffffu)) return false;
  }
  return true;
}

Eigen::MatrixXi boundary_edges(const Eigen::MatrixXi& F) {
  const auto d = directed_edges(F);
  std::vector<std::uint64_t> open;
  for (auto e : d) {
    const auto a = static_cast<int>(e >> 32), b = static_cast<int>(e & 0xffffffffu);
    if (!std::binary_search(d.begin(), d.end(), dkey(b, a))) open.push_back(e);
  }
  Eigen::MatrixXi E(open.size(), 2);
  for (size_t i = 0; i < open.size(); ++i) E.row(i) << static_cast<int>(open[i] >> 32), static_cast<int>(open[i] & 0xffffffffu);
  return E;
}

double flux_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int axis) {
  double vol = 0.0;
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    vol += (a[axis] + b[axis] + c[axis]) / 3.0 * 0.5 * (b - a).cross(c - a)[axis];
  }
  return vol;
}

bool is_closed_and_oriented(const Eigen::MatrixXi& F) { return F.rows() == 0 || is_closed(F); }

double enclosed_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) { return signed_volume(V, F); }

}  // namespace dfm
